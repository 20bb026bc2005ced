// The periodic unit squares for plane elasticity (data/meshes/rve_block.obj and
// square_inclusion.obj, tools/make_meshes.py): opposite sides carry the same boundary nodes, the
// square's corners are corner vertices, the limit map has no fold-over, the material groups are
// read, and the inclusion's interface is a closed crease of radius 0.25.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

struct Sides {
    std::vector<double> left, right, bottom, top;  ///< y on left/right, x on bottom/top
};

Sides boundary_sides(const ControlMesh& mesh) {
    const Topology& t = mesh.topology();
    const Points& x = mesh.positions();
    Sides sides;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (!t.is_boundary_vertex(v)) {
            EXPECT_GT(std::min({x(v, 0), x(v, 1), 1.0 - x(v, 0), 1.0 - x(v, 1)}), 0.0) << "interior vertex " << v;
            continue;
        }
        bool on_a_side = false;
        const auto add = [&](bool on, std::vector<double>& side, double coordinate) {
            if (on) {
                side.push_back(coordinate);
                on_a_side = true;
            }
        };
        add(x(v, 0) == 0.0, sides.left, x(v, 1));
        add(x(v, 0) == 1.0, sides.right, x(v, 1));
        add(x(v, 1) == 0.0, sides.bottom, x(v, 0));
        add(x(v, 1) == 1.0, sides.top, x(v, 0));
        EXPECT_TRUE(on_a_side) << "boundary vertex " << v << " at (" << x(v, 0) << ", " << x(v, 1) << ")";
    }
    for (auto* side : {&sides.left, &sides.right, &sides.bottom, &sides.top}) {
        std::sort(side->begin(), side->end());
    }
    return sides;
}

void expect_same_nodes(const std::vector<double>& a, const std::vector<double>& b) {
    ASSERT_EQ(a.size(), b.size());
    ASSERT_GE(a.size(), 3U);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i], b[i], 1e-15) << "node " << i;
    }
    EXPECT_EQ(a.front(), 0.0);
    EXPECT_EQ(a.back(), 1.0);
}

class PeriodicSquares : public ::testing::TestWithParam<std::string> {};

TEST_P(PeriodicSquares, OppositeSidesMatchAndCornersAreCornerVertices) {
    const BuildResult built = read_mesh(test::find_bundled(GetParam()).path);
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    EXPECT_EQ(t.num_boundary_loops(), 1);
    EXPECT_TRUE((mesh.positions().col(2).array() == 0.0).all());
    const Sides sides = boundary_sides(mesh);
    expect_same_nodes(sides.left, sides.right);
    expect_same_nodes(sides.bottom, sides.top);
    // The four corners: valence 2, i.e. the corner of exactly one face.
    int corners = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const double x = mesh.positions()(v, 0);
        const double y = mesh.positions()(v, 1);
        if ((x == 0.0 || x == 1.0) && (y == 0.0 || y == 1.0)) {
            ++corners;
            EXPECT_EQ(t.valence(v), 2) << "corner (" << x << ", " << y << ")";
            EXPECT_EQ(t.vertex_faces(v).size(), 1U);
        }
    }
    EXPECT_EQ(corners, 4);
}

TEST_P(PeriodicSquares, TheLimitMapIsOrientationPreserving) {
    // det(d(x, y)/d(u, v)) > 0 on a grid of points of every ptex face, boundary and corners
    // included: with the boundary mapped onto the square's sides, the map has no fold-over.
    const BuildResult built = read_mesh(test::find_bundled(GetParam()).path);
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark);
    double smallest = 1e300;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        for (int i = 0; i <= 6; ++i) {
            for (int j = 0; j <= 6; ++j) {
                const SurfacePoint point{p, i / 6.0, j / 6.0};
                const auto e = basis.evaluate(built.mesh.positions(), point, DerivativeOrder::First);
                EXPECT_EQ(e(0, 2), 0.0);
                const double det = e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0);
                smallest = std::min(smallest, det);
                EXPECT_GT(det, 0.0) << "ptex face " << p << " (u, v) = (" << point.u << ", " << point.v << ")";
                EXPECT_GE(std::min(e(0, 0), e(0, 1)), -1e-15);
                EXPECT_LE(std::max(e(0, 0), e(0, 1)), 1.0 + 1e-15);
            }
        }
    }
    EXPECT_GT(smallest, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Bundled, PeriodicSquares, ::testing::Values("rve_block", "square_inclusion"));

std::map<std::string, int> group_sizes(const FaceGroups& groups) {
    std::map<std::string, int> sizes;
    for (const Index g : groups.face_group) {
        ++sizes[g < 0 ? std::string("(none)") : groups.names[static_cast<std::size_t>(g)]];
    }
    return sizes;
}

TEST(PeriodicSquares, TheBlockHasMatrixAndGrains) {
    const BuildResult built = read_mesh(test::find_bundled("rve_block").path);
    EXPECT_EQ(built.groups.face_group.size(), static_cast<std::size_t>(built.mesh.num_faces()));
    // The grains are the one-rings of a valence-6, two valence-5 and one valence-4 vertex.
    EXPECT_EQ(group_sizes(built.groups), (std::map<std::string, int>{{"grain", 20}, {"matrix", 92}}));
}

TEST(PeriodicSquares, TheInclusionIsBoundedByACreaseOfRadiusAQuarter) {
    const BuildResult built = read_mesh(test::find_bundled("square_inclusion").path);
    const Topology& t = built.mesh.topology();
    const Points& x = built.mesh.positions();
    EXPECT_EQ(group_sizes(built.groups), (std::map<std::string, int>{{"inclusion", 84}, {"matrix", 112}}));
    // The infinitely sharp edges are exactly those between an inclusion and a matrix face.
    const Index inclusion = built.groups.find("inclusion");
    int interface_edges = 0;
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto faces = t.edge_faces(e);
        const bool interface = faces.size() == 2 && (built.groups.group_of(faces[0]) == inclusion) !=
                                                        (built.groups.group_of(faces[1]) == inclusion);
        interface_edges += interface ? 1 : 0;
        EXPECT_EQ(t.edge_sharpness(e) >= infinite_sharpness, interface) << "edge " << e;
    }
    EXPECT_EQ(interface_edges, 24);
    // The limit surface at the interface vertices lies on the circle of radius 0.25 about the
    // centre (the crease is the closed cubic B-spline whose value at a vertex is (p- + 6p + p+)/8).
    const LimitBasis basis(t, SchemeKind::CatmullClark);
    const Points limit = basis.vertex_limit_matrix() * x;
    int on_circle = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        int sharp = 0;
        for (const Index e : t.vertex_edges(v)) {
            sharp += t.edge_sharpness(e) >= infinite_sharpness ? 1 : 0;
        }
        if (sharp == 0) {
            continue;
        }
        EXPECT_EQ(sharp, 2) << "vertex " << v;
        ++on_circle;
        EXPECT_NEAR(std::hypot(limit(v, 0) - 0.5, limit(v, 1) - 0.5), 0.25, 1e-12) << "vertex " << v;
    }
    EXPECT_EQ(on_circle, 24);
}

}  // namespace
}  // namespace limsurf
