// The tessellation of the limit surface (render/tessellation.h): its points are points of the limit
// surface (against LimitBasis::evaluate, for every scheme), its weights reproduce the positions and carry
// vertex fields, its normals are unit, outward on closed meshes and agree with the triangles'
// orientation, its area converges to the measured area like 1/N², extraordinary vertices get finite
// normals and curvatures from nearby, faces without a limit surface are skipped, threads do not matter.
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/render/tessellation.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

struct Loaded {
    Loaded(const std::string& name, SchemeKind scheme, const SchemeOptions& options = {})
        : built(read_mesh(find_bundled(name).path)), basis(built.mesh.topology(), scheme, options) {}
    [[nodiscard]] const Points& X() const { return built.mesh.positions(); }
    BuildResult built;
    LimitBasis basis;
};

struct Case {
    const char* mesh;
    SchemeKind scheme;
};

class TessellationOnEveryScheme : public ::testing::TestWithParam<Case> {};

TEST_P(TessellationOnEveryScheme, PointsLieOnTheLimitSurfaceAndWeightsReproduceThem) {
    const Loaded m(GetParam().mesh, GetParam().scheme);
    const LimitTessellation t = tessellate_limit_surface(m.basis, m.X(), {.resolution = 3});
    ASSERT_GT(t.num_points(), 0);
    const double size = std::max(1.0, m.X().cwiseAbs().maxCoeff());
    for (Index p = 0; p < t.num_points(); ++p) {
        const Eigen::Matrix<double, 6, 3> d = m.basis.evaluate(m.X(), t.points[static_cast<std::size_t>(p)]);
        EXPECT_LT((t.positions.row(p) - d.row(0)).norm(), 1e-13 * size) << "point " << p;
    }
    EXPECT_LT((t.value_weights * m.X() - t.positions).cwiseAbs().maxCoeff(), 1e-13 * size);
    // u_h = Σ u_i φ_i reproduces the coordinates (affine invariance) and constants (partition of unity).
    EXPECT_LT((evaluate_vertex_field(t, m.X().col(0)) - t.positions.col(0)).cwiseAbs().maxCoeff(), 1e-13 * size);
    EXPECT_LT((evaluate_vertex_field(t, Eigen::VectorXd::Ones(m.X().rows())).array() - 1.0).abs().maxCoeff(), 1e-13);
    EXPECT_TRUE(t.normals.allFinite());
    EXPECT_TRUE(t.mean_curvature.allFinite());
    EXPECT_TRUE(t.gaussian_curvature.allFinite());
    EXPECT_LT(((t.normals.rowwise().norm()).array() - 1.0).abs().maxCoeff(), 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Schemes, TessellationOnEveryScheme,
                         ::testing::Values(Case{"cube", SchemeKind::CatmullClark},
                                           Case{"cube_ngons", SchemeKind::CatmullClark},
                                           Case{"icosahedron", SchemeKind::Loop},
                                           Case{"disk_ev7_tris", SchemeKind::Loop}, Case{"tetra_1", SchemeKind::C2g0},
                                           Case{"dodecahedron", SchemeKind::DooSabin}),
                         [](const auto& param_info) { return std::string(param_info.param.mesh); });

TEST(Tessellation, GridsHaveTheDocumentedLayout) {
    const Loaded quads("cube", SchemeKind::CatmullClark);
    const LimitTessellation q = tessellate_limit_surface(quads.basis, quads.X(), {.resolution = 4});
    EXPECT_EQ(q.num_points(), 6 * 25);
    EXPECT_EQ(q.num_triangles(), 6 * 32);
    EXPECT_EQ(q.resolution, 4);
    EXPECT_EQ(q.points[7].face, 0);
    EXPECT_DOUBLE_EQ(q.points[7].u, 0.5);  // (i, j) = (2, 1)
    EXPECT_DOUBLE_EQ(q.points[7].v, 0.25);
    const Loaded tris("icosahedron", SchemeKind::Loop);
    const LimitTessellation t = tessellate_limit_surface(tris.basis, tris.X(), {.resolution = 4});
    EXPECT_EQ(t.num_points(), 20 * 15);
    EXPECT_EQ(t.num_triangles(), 20 * 16);
    for (const SurfacePoint& p : t.points) {
        EXPECT_LE(p.u + p.v, 1.0);
    }
}

// On a sphere-like closed mesh every normal points away from the centre, and every triangle's
// geometric normal agrees with the normals at its corners (counter-clockwise seen from outside).
TEST(Tessellation, NormalsAreOutwardAndAgreeWithTheTriangles) {
    for (const auto& [name, scheme] :
         {std::pair{"sphere_quads", SchemeKind::CatmullClark}, std::pair{"sphere_tris", SchemeKind::Loop},
          std::pair{"tetra_2", SchemeKind::C2g0}}) {
        SCOPED_TRACE(name);
        const Loaded m(name, scheme);
        const LimitTessellation t = tessellate_limit_surface(m.basis, m.X(), {.resolution = 4, .curvature = false});
        EXPECT_TRUE(t.mean_curvature.size() == 0 && t.gaussian_curvature.size() == 0);
        for (Index p = 0; p < t.num_points(); ++p) {
            EXPECT_GT(t.normals.row(p).dot(t.positions.row(p)), 0.5 * t.positions.row(p).norm()) << "point " << p;
        }
        for (Index k = 0; k < t.num_triangles(); ++k) {
            const Eigen::Vector3d a = t.positions.row(t.triangles(k, 0));
            const Eigen::Vector3d n = (t.positions.row(t.triangles(k, 1)).transpose() - a)
                                          .cross(t.positions.row(t.triangles(k, 2)).transpose() - a);
            EXPECT_GT(n.dot(t.normals.row(t.triangles(k, 0))), 0.0) << "triangle " << k;
        }
    }
}

// The triangles' area approaches the area measured by quadrature like 1/N² (chords of a smooth surface).
TEST(Tessellation, AreaConvergesToTheMeasuredArea) {
    const Loaded m("sphere_quads", SchemeKind::CatmullClark);
    const double measured = area(LimitSampler(m.basis, 10, 8), m.X());
    double previous = 0.0;
    for (const int n : {2, 4, 8}) {
        const double error =
            measured -
            tessellation_area(tessellate_limit_surface(m.basis, m.X(), {.resolution = n, .curvature = false}));
        EXPECT_GT(error, 0.0) << "N = " << n;  // inscribed triangles are smaller
        if (previous > 0.0) {
            EXPECT_NEAR(previous / error, 4.0, 0.6) << "N = " << n;
        }
        previous = error;
    }
    EXPECT_LT(previous / measured, 1e-3);
}

// At the cube's corners (valence 3) the curvature is not defined at the vertex itself: it comes from a
// nearby point, finite, and the point is flagged. The limit surface is convex there: K > 0.
TEST(Tessellation, ExtraordinaryVerticesTakeCurvatureFromNearby) {
    const Loaded m("cube", SchemeKind::CatmullClark);
    const LimitTessellation t = tessellate_limit_surface(m.basis, m.X(), {.resolution = 2});
    int flagged = 0;
    for (Index p = 0; p < t.num_points(); ++p) {
        const SurfacePoint& s = t.points[static_cast<std::size_t>(p)];
        const bool corner = (s.u == 0.0 || s.u == 1.0) && (s.v == 0.0 || s.v == 1.0);
        const bool at_vertex = m.basis.evaluate(s).at_extraordinary_vertex;
        EXPECT_EQ(t.estimated(p), at_vertex) << "point " << p;
        flagged += at_vertex ? 1 : 0;
        EXPECT_TRUE(!at_vertex || corner);
        EXPECT_GT(t.gaussian_curvature(p), 0.0) << "point " << p;
        EXPECT_GT(t.mean_curvature(p), 0.0) << "point " << p;
    }
    EXPECT_EQ(flagged, 24);  // the 4 corners of each of the 6 faces
}

TEST(Tessellation, FacesWithoutALimitSurfaceAreSkipped) {
    SchemeOptions none;
    none.boundary = BoundaryInterpolation::None;
    const Loaded m("quad_grid", SchemeKind::CatmullClark, none);
    const LimitTessellation t = tessellate_limit_surface(m.basis, m.X(), {.resolution = 2});
    EXPECT_EQ(t.num_points(), 4 * 9);  // the 2x2 inner faces of the 4x4 grid
    for (const SurfacePoint& p : t.points) {
        EXPECT_TRUE(m.basis.has_limit_surface(p.face));
    }
}

TEST(Tessellation, ResultDoesNotDependOnTheThreads) {
    const Loaded m("genus2", SchemeKind::CatmullClark);
    const LimitTessellation one = tessellate_limit_surface(m.basis, m.X(), {.resolution = 3, .num_threads = 1});
    const LimitTessellation two = tessellate_limit_surface(m.basis, m.X(), {.resolution = 3, .num_threads = 3});
    EXPECT_EQ(one.positions, two.positions);
    EXPECT_EQ(one.normals, two.normals);
    EXPECT_EQ(one.mean_curvature, two.mean_curvature);
    EXPECT_TRUE(one.value_weights.isApprox(two.value_weights, 0.0));
}

TEST(Tessellation, RefusesBadInput) {
    const Loaded m("cube", SchemeKind::CatmullClark);
    EXPECT_THROW((void)tessellate_limit_surface(m.basis, m.X(), {.resolution = 0}), InputError);
    EXPECT_THROW((void)tessellate_limit_surface(m.basis, m.X().topRows(4), {}), InputError);
    const LimitTessellation t = tessellate_limit_surface(m.basis, m.X(), {.resolution = 1});
    Eigen::VectorXd values = Eigen::VectorXd::Zero(8);
    values(5) = std::nan("");
    try {
        (void)evaluate_vertex_field(t, values);
        ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 5"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)evaluate_vertex_field(t, Eigen::VectorXd::Zero(7)), InputError);
}

TEST(Tessellation, AutomaticResolutionBoundsThePoints) {
    const Loaded m("genus2", SchemeKind::CatmullClark);
    const int n = automatic_resolution(m.basis, 20000);
    EXPECT_LE(50 * (n + 1) * (n + 1), 20000);  // 50 quads, one ptex face each
    EXPECT_GT(50 * (n + 2) * (n + 2), 20000);
    EXPECT_EQ(automatic_resolution(m.basis, 10), 2);
}

}  // namespace
}  // namespace limsurf::test
