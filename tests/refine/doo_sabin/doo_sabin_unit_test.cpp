// Doo–Sabin by hand: the masks, the boundary rule on tiny meshes, refusals.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

double weight(const SparseMatrix& S0, Index row, Index col) {
    return S0.coeff(row, col);
}

TEST(DooSabinUnit, QuadMaskIsCornerCentroidAndEdgeMidpoints) {
    // For quads the classic mask equals (corner + centroid + both edge midpoints) / 4 (PEERS.md).
    const BuildResult r = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = r.mesh.topology();
    const Points& x = r.mesh.positions();
    const Level level = refine_doo_sabin(t);
    const Points child = level.S0 * x;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto fv = t.face_vertices(f);
        const Eigen::RowVector3d centroid = (x.row(fv[0]) + x.row(fv[1]) + x.row(fv[2]) + x.row(fv[3])) / 4.0;
        for (std::size_t i = 0; i < 4; ++i) {
            const Eigen::RowVector3d v = x.row(fv[i]);
            const Eigen::RowVector3d next = (v + Eigen::RowVector3d(x.row(fv[(i + 1) % 4]))) / 2.0;
            const Eigen::RowVector3d prev = (v + Eigen::RowVector3d(x.row(fv[(i + 3) % 4]))) / 2.0;
            const Eigen::RowVector3d expected = (v + centroid + next + prev) / 4.0;
            const Eigen::RowVector3d got = child.row(t.face_offset(f) + static_cast<Index>(i));
            EXPECT_LE((got - expected).cwiseAbs().maxCoeff(), 1e-14) << "face " << f << " corner " << i;
        }
    }
}

TEST(DooSabinUnit, ClassicWeightsForTrianglesAndPentagons) {
    const Topology tetra = Topology::from_polygons(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
    const Level t3 = refine_doo_sabin(tetra);
    // Face 0 = (0 2 1): corner 0 -> vertex 0 with 2/3, the others 1/6.
    EXPECT_DOUBLE_EQ(weight(t3.S0, 0, 0), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(weight(t3.S0, 0, 2), 1.0 / 6.0);
    EXPECT_DOUBLE_EQ(weight(t3.S0, 0, 1), 1.0 / 6.0);
    EXPECT_EQ(weight(t3.S0, 0, 3), 0.0);

    const BuildResult r = read_mesh(test::find_bundled("dodecahedron").path);
    const Topology& t = r.mesh.topology();
    const Level level = refine_doo_sabin(t);
    const auto fv = t.face_vertices(0);
    for (Index i = 0; i < 5; ++i) {
        for (Index k = 0; k < 5; ++k) {
            const double expected =
                i == k ? 10.0 / 20.0 : (3.0 + 2.0 * std::cos(2.0 * std::numbers::pi * (k - i) / 5.0)) / 20.0;
            EXPECT_NEAR(weight(level.S0, i, fv[static_cast<std::size_t>(k)]), expected, 1e-15);
        }
    }
}

TEST(DooSabinUnit, CubeFacesHaveTheExpectedShape) {
    const Topology cube = Topology::from_polygons(8, test::cube_faces());
    const Level level = refine_doo_sabin(cube);
    const Topology& t = level.topology;
    ASSERT_EQ(t.num_faces(), 6 + 12 + 8);
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto kind = level.provenance.face_parent_kind[static_cast<std::size_t>(f)];
        const Index expected = kind == ParentKind::Vertex ? 3 : 4;
        EXPECT_EQ(t.face_degree(f), expected) << "face " << f;
        EXPECT_EQ(kind, f < 6 ? ParentKind::Face : (f < 18 ? ParentKind::Edge : ParentKind::Vertex));
    }
    // The child is a truncated-and-chamfered cube: every child vertex has valence 4.
    for (Index v = 0; v < t.num_vertices(); ++v) {
        EXPECT_EQ(t.valence(v), 4);
    }
}

TEST(DooSabinUnit, SingleQuadIsKeptUnderTheCornerRule) {
    const Topology quad = Topology::from_polygons(4, {{0, 1, 2, 3}});
    const Level level = refine_doo_sabin(quad);
    ASSERT_EQ(level.topology.num_faces(), 1);
    EXPECT_TRUE(Eigen::MatrixXd(level.S0).isIdentity(0.0));
    // None: CGAL's behaviour, the quad shrinks to its classic corner points.
    SchemeOptions none;
    none.boundary = BoundaryInterpolation::None;
    const Level shrunk = refine_doo_sabin(quad, none);
    EXPECT_DOUBLE_EQ(weight(shrunk.S0, 0, 0), 9.0 / 16.0);
    EXPECT_DOUBLE_EQ(weight(shrunk.S0, 0, 1), 3.0 / 16.0);
    EXPECT_DOUBLE_EQ(weight(shrunk.S0, 0, 2), 1.0 / 16.0);
}

TEST(DooSabinUnit, GridBoundaryRows) {
    // 2×1 grid: vertices 0 1 2 / 3 4 5; vertex 1 is a boundary vertex in two faces.
    const Topology grid = Topology::from_polygons(6, test::grid_faces(2, 1));
    const Level level = refine_doo_sabin(grid);
    const Topology& t = level.topology;
    EXPECT_EQ(t.num_faces(), 2 + 1);  // two F-faces and the E-face of the middle edge
    const Points x = level.S0 * test::grid_positions(2, 1);
    // Every child vertex lies on the parent boundary: Chaikin points or corners.
    for (Index f = 0; f < grid.num_faces(); ++f) {
        const auto fv = grid.face_vertices(f);
        for (std::size_t i = 0; i < 4; ++i) {
            const Index child = grid.face_offset(f) + static_cast<Index>(i);
            const Index v = fv[i];
            const bool corner = grid.vertex_faces(v).size() == 1;
            double sum = 0.0;
            for (SparseMatrix::InnerIterator it(level.S0, child); it; ++it) {
                sum += it.value();
                if (it.col() == v) {
                    EXPECT_DOUBLE_EQ(it.value(), corner ? 1.0 : 0.75);
                } else {
                    EXPECT_DOUBLE_EQ(it.value(), 0.25);
                }
            }
            EXPECT_DOUBLE_EQ(sum, 1.0);
        }
    }
    EXPECT_EQ(x.col(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(DooSabinUnit, BoundaryVertexInThreeFacesGetsAVFace) {
    // Three quads around vertex 0 leaving a gap: 0 is a boundary vertex in 3 faces.
    const Topology fan = Topology::from_polygons(8, {{0, 1, 2, 3}, {0, 3, 4, 5}, {0, 5, 6, 7}});
    ASSERT_TRUE(fan.is_boundary_vertex(0));
    const Level level = refine_doo_sabin(fan);
    const auto& kinds = level.provenance.face_parent_kind;
    const auto v_faces = std::count(kinds.begin(), kinds.end(), ParentKind::Vertex);
    EXPECT_EQ(v_faces, 1);
    EXPECT_EQ(level.topology.num_faces(), 3 + 2 + 1);
    SchemeOptions none;
    none.boundary = BoundaryInterpolation::None;
    EXPECT_EQ(refine_doo_sabin(fan, none).topology.num_faces(), 3 + 2);
}

TEST(DooSabinUnit, SharpnessAndHolesAreRefused) {
    SharpnessTags crease;
    crease.creases.push_back({0, 1, 2.0, 0});
    const Topology creased = Topology::from_polygons(8, test::cube_faces(), crease);
    EXPECT_THROW((void)refine_doo_sabin(creased), UnsupportedError);
    SharpnessTags hole;
    hole.holes.push_back({2, 0});
    const Topology holed = Topology::from_polygons(8, test::cube_faces(), hole);
    EXPECT_THROW((void)refine_doo_sabin(holed), UnsupportedError);
}

}  // namespace
}  // namespace limsurf
