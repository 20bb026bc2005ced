// limit_self_intersections (apps/self_intersection.h): the welded tessellation of every closed bundled
// surface is one closed surface of the right Euler characteristic and does not meet itself, under
// each scheme; a surface pulled through itself does, at every resolution; bad options are refused.
#include <gtest/gtest.h>

#include "limsurf/apps/self_intersection.h"
#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "support/paths.h"

namespace limsurf {
namespace {

struct ClosedCase {
    const char* mesh;
    SchemeKind scheme;
    int euler_characteristic;
};

TEST(LimitSelfIntersections, ClosedSurfacesWeldIntoOneAndDoNotMeetThemselves) {
    for (const ClosedCase& c :
         {ClosedCase{"icosahedron.obj", SchemeKind::Loop, 2}, ClosedCase{"tetra_3.obj", SchemeKind::C2g0, 2},
          ClosedCase{"cube.obj", SchemeKind::CatmullClark, 2}, ClosedCase{"tri_torus.obj", SchemeKind::Loop, 0},
          ClosedCase{"genus2.obj", SchemeKind::CatmullClark, -2}}) {
        SCOPED_TRACE(c.mesh);
        const BuildResult built = read_mesh(test::mesh_dir() / c.mesh);
        const LimitBasis basis(built.mesh.topology(), c.scheme);
        SelfIntersectionOptions options;
        options.resolution = 5;
        const SelfIntersections found = limit_self_intersections(basis, built.mesh.positions(), options);
        EXPECT_FALSE(found.intersects());
        EXPECT_TRUE(found.control_faces.empty());
        EXPECT_EQ(found.resolution, 5);
        // V − E + F = χ with E = 3F/2: the copies along ptex edges and at vertices became one point.
        EXPECT_EQ(found.points, found.triangles / 2 + c.euler_characteristic);
    }
}

// A Catmull–Clark n-gon's sub-faces put 2N segments along a control edge where the quad beside it
// puts N (render/tessellation.h): T-junctions, so the welded tessellation is not one closed surface
// there. The triangles on the two sides of a T-junction lie on their own sides of the limit curve and
// do not meet: no self-intersection is reported, at any resolution.
TEST(LimitSelfIntersections, TJunctionsOfNGonSubFacesAreNotCrossings) {
    const BuildResult built = read_mesh(test::mesh_dir() / "cube_ngons.obj");
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark);
    for (const int resolution : {1, 2, 3, 5, 8, 13, 21, 40}) {
        SelfIntersectionOptions options;
        options.resolution = resolution;
        const SelfIntersections found = limit_self_intersections(basis, built.mesh.positions(), options);
        EXPECT_FALSE(found.intersects()) << resolution;
        EXPECT_GT(found.points, found.triangles / 2 + 2) << resolution;  // the T-junctions' points
    }
}

TEST(LimitSelfIntersections, APulledSurfaceMeetsItselfAtEveryResolution) {
    const BuildResult built = read_mesh(test::mesh_dir() / "icosahedron.obj");
    const LimitBasis basis(built.mesh.topology(), SchemeKind::Loop);
    Points X = built.mesh.positions();
    X.row(0) = -3.0 * X.row(0) + 0.3 * X.row(5);  // as in tests/mesh/self_intersection_cgal_test.cpp
    for (const int resolution : {3, 6, 16}) {
        SelfIntersectionOptions options;
        options.resolution = resolution;
        const SelfIntersections found = limit_self_intersections(basis, X, options);
        EXPECT_TRUE(found.intersects()) << resolution;
        EXPECT_FALSE(found.control_faces.empty());
        EXPECT_TRUE(std::is_sorted(found.control_faces.begin(), found.control_faces.end()));
    }
    // The answer does not depend on the threads of the tessellation.
    SelfIntersectionOptions one, three;
    one.num_threads = 1;
    three.num_threads = 3;
    const SelfIntersections a = limit_self_intersections(basis, X, one), b = limit_self_intersections(basis, X, three);
    EXPECT_EQ(a.intersecting_pairs, b.intersecting_pairs);
    EXPECT_EQ(a.control_faces, b.control_faces);
}

TEST(LimitSelfIntersections, RefusesBadOptions) {
    const BuildResult built = read_mesh(test::mesh_dir() / "icosahedron.obj");
    const LimitBasis basis(built.mesh.topology(), SchemeKind::Loop);
    SelfIntersectionOptions options;
    options.resolution = 257;
    EXPECT_THROW((void)limit_self_intersections(basis, built.mesh.positions(), options), InputError);
    options.resolution = 0;
    options.weld_tolerance = 0.0;
    EXPECT_THROW((void)limit_self_intersections(basis, built.mesh.positions(), options), InputError);
    EXPECT_THROW((void)limit_self_intersections(basis, Points::Zero(3, 3)), InputError);
}

}  // namespace
}  // namespace limsurf
