// Published and analytic volumes (volume-trilinear-forms): the Doo–Sabin unit cube encloses
// 6241/9920, the Loop surface of the regular tetrahedron with unit edges
// 44192429513855101 / (6865302375425894400 √2); the paper's degenerate calibration meshes enclose
// exactly the cube and the tetrahedron they collapse onto.
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/refine/refine.h"
#include "limsurf/volume/enclosed_volume.h"

namespace limsurf {
namespace {

struct Solid {
    Topology topology;
    Points X;
};

/// The box [0,a]×[0,b]×[0,c] as 6 quads, counter-clockwise seen from outside.
Solid box(double a, double b, double c) {
    Points X(8, 3);
    for (int v = 0; v < 8; ++v) {
        X.row(v) << a * (v & 1), b * ((v >> 1) & 1), c * ((v >> 2) & 1);
    }
    const std::vector<std::vector<Index>> faces{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    return {Topology::from_polygons(8, faces), X};
}

/// The tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1).
Solid corner_tetrahedron() {
    Points X(4, 3);
    X << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
    return {Topology::from_polygons(4, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}), X};
}

TEST(VolumePublished, DooSabinUnitCubeEncloses6241Over9920) {
    const Solid cube = box(1, 1, 1);
    const double v = EnclosedVolume(cube.topology, SchemeKind::DooSabin).volume(cube.X);
    EXPECT_NEAR(v, 6241.0 / 9920.0, 1e-15);
    // Doo–Sabin commutes with affine maps: a box a×b×c encloses 6241/9920 · abc.
    const Solid b = box(0.5, 2.0, 3.0);
    EXPECT_NEAR(EnclosedVolume(b.topology, SchemeKind::DooSabin).volume(b.X), 6241.0 / 9920.0 * 3.0, 1e-14);
}

TEST(VolumePublished, LoopRegularTetrahedronWithUnitEdges) {
    Points X(4, 3);
    const long double r = 1.0L / std::sqrt(3.0L);
    const long double h = std::sqrt(2.0L / 3.0L);
    X << static_cast<double>(r), 0, 0, static_cast<double>(-r / 2), 0.5, 0, static_cast<double>(-r / 2), -0.5, 0, 0, 0,
        static_cast<double>(h);
    const Topology t = Topology::from_polygons(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
    const double v = EnclosedVolume(t, SchemeKind::Loop).volume(X);
    // 44192429513855101 has 17 digits: long double holds it exactly (64-bit mantissa).
    const long double published = 44192429513855101.0L / (6865302375425894400.0L * std::sqrt(2.0L));
    EXPECT_NEAR(v, static_cast<double>(published), 1e-14 * static_cast<double>(published));
    // The control tetrahedron encloses 1/(6√2); the Loop surface about 0.0295 of it.
    EXPECT_NEAR(polyhedral_volume(t, X), 1.0 / (6.0 * std::sqrt(2.0)), 1e-15);
}

/// The paper's calibration mesh: @p solid refined linearly @p times, every vertex moved onto the
/// nearest corner (cube: each coordinate rounded, 0.5 going down; tetrahedron: the corner of the
/// largest barycentric coordinate, ties to the first).
Solid degenerate(const Solid& solid, bool triangles, int times) {
    Topology t = solid.topology;
    Points X = solid.X;
    for (int i = 0; i < times; ++i) {
        Level level = triangles ? refine_linear(t) : refine_bilinear(t);
        X = level.S0 * X;
        t = std::move(level.topology);
    }
    for (Eigen::Index v = 0; v < X.rows(); ++v) {
        if (!triangles) {
            for (int c = 0; c < 3; ++c) {
                X(v, c) = X(v, c) <= 0.5 ? 0.0 : 1.0;
            }
            continue;
        }
        const std::array<double, 4> barycentric{1.0 - X(v, 0) - X(v, 1) - X(v, 2), X(v, 0), X(v, 1), X(v, 2)};
        int best = 0;
        for (int c = 1; c < 4; ++c) {
            if (barycentric[static_cast<std::size_t>(c)] > barycentric[static_cast<std::size_t>(best)]) {
                best = c;
            }
        }
        X.row(v) = solid.X.row(best);
    }
    return {t, X};
}

TEST(VolumePublished, DegenerateMeshesEncloseTheirPolyhedron) {
    // Their limit surfaces are the cube and the tetrahedron themselves (the paper's calibration).
    const Solid cc = degenerate(box(1, 1, 1), false, 3);
    EXPECT_NEAR(EnclosedVolume(cc.topology, SchemeKind::CatmullClark).volume(cc.X), 1.0, 1e-13);
    const Solid ds = degenerate(box(1, 1, 1), false, 2);
    EXPECT_NEAR(EnclosedVolume(ds.topology, SchemeKind::DooSabin).volume(ds.X), 1.0, 1e-13);
    const Solid loop = degenerate(corner_tetrahedron(), true, 3);
    EXPECT_NEAR(EnclosedVolume(loop.topology, SchemeKind::Loop).volume(loop.X), 1.0 / 6.0, 1e-14);
    // One more linear level keeps the limit surface (more collapsed points on the same polyhedron).
    const Solid cc4 = degenerate(box(1, 1, 1), false, 4);
    EXPECT_NEAR(EnclosedVolume(cc4.topology, SchemeKind::CatmullClark).volume(cc4.X), 1.0, 1e-13);
}

}  // namespace
}  // namespace limsurf
