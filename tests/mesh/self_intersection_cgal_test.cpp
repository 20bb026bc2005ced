// The peer of mesh/self_intersection.h: CGAL 5.5's Polygon_mesh_processing::self_intersections (exact
// predicates) on the same triangles must report the same pairs — on a crowded soup of loose
// triangles, on a folded manifold grid (pairs that share a vertex or an edge), and on the welded
// limit tessellation of a Loop surface pulled through itself (what `limsurf membrane` checks).
#include <algorithm>
#include <array>
#include <random>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/self_intersection.h"
#include "triangle_soup.h"
#include "limsurf/render/tessellation.h"
#include "support/paths.h"

namespace limsurf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Pairs = std::vector<std::array<Index, 2>>;

Pairs cgal_pairs(const Points& points, const Triangles& triangles) {
    CgalMesh mesh;
    std::vector<CgalMesh::Vertex_index> vertices;
    for (Index p = 0; p < points.rows(); ++p) {
        vertices.push_back(mesh.add_vertex(Kernel::Point_3(points(p, 0), points(p, 1), points(p, 2))));
    }
    for (Index t = 0; t < triangles.rows(); ++t) {
        const auto face = mesh.add_face(vertices[static_cast<std::size_t>(triangles(t, 0))],
                                        vertices[static_cast<std::size_t>(triangles(t, 1))],
                                        vertices[static_cast<std::size_t>(triangles(t, 2))]);
        EXPECT_NE(face, CgalMesh::null_face()) << "CGAL refused triangle " << t << " (not manifold)";
    }
    std::vector<std::pair<CgalMesh::Face_index, CgalMesh::Face_index>> found;
    CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(found));
    Pairs pairs;
    for (const auto& [a, b] : found) {
        const auto i = static_cast<Index>(a.idx()), j = static_cast<Index>(b.idx());
        pairs.push_back({std::min(i, j), std::max(i, j)});
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

TEST(SelfIntersectionCgal, CrowdedSoupOfLooseTriangles) {
    const Index n = 400;
    const auto [p, t] = test::random_triangle_soup(11, n, 8.0);
    const Pairs expected = cgal_pairs(p, t);
    ASSERT_GT(expected.size(), 50u);
    EXPECT_EQ(intersecting_triangle_pairs(p, t), expected);
}

// An n×n grid of squares split into triangles, its points shaken in the plane by up to 0.6 of a
// cell and lifted a little: triangles fold over their neighbours, so pairs with a common vertex
// cross (and the mesh stays manifold for CGAL).
TEST(SelfIntersectionCgal, FoldedGridWithNeighboursCrossing) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> shake(-0.6, 0.6), lift(-0.05, 0.05);
    const int n = 14;
    Points p((n + 1) * (n + 1), 3);
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            p.row(j * (n + 1) + i) << i + shake(rng), j + shake(rng), lift(rng);
        }
    }
    Triangles t(2 * n * n, 3);
    Index k = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const Index a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            t.row(k++) << a, b, c;
            t.row(k++) << a, c, d;
        }
    }
    const Pairs expected = cgal_pairs(p, t);
    ASSERT_GT(expected.size(), 20u);
    EXPECT_EQ(intersecting_triangle_pairs(p, t), expected);
}

TEST(SelfIntersectionCgal, LimitTessellationOfALoopSurfacePulledThroughItself) {
    const BuildResult built = read_mesh(test::mesh_dir() / "icosahedron.obj");
    const LimitBasis basis(built.mesh.topology(), SchemeKind::Loop);
    for (const bool pulled : {false, true}) {
        Points X = built.mesh.positions();
        if (pulled) {
            // Vertex 0 pulled through the middle to 3 radii beyond the far side, off the axis: the
            // stretched patches pass through the far ones. (Pulled to 1-2 radii the sheet only turns
            // inside out around the far patches without meeting them.)
            X.row(0) = -3.0 * X.row(0) + 0.3 * X.row(5);
        }
        TessellationOptions options;
        options.resolution = 6;
        options.curvature = false;
        const LimitTessellation tessellation = tessellate_limit_surface(basis, X, options);
        const WeldedTriangles welded = weld_coincident_points(tessellation.positions, tessellation.triangles, 1e-9);
        // Welded into one closed sphere: V − E + F = 2 with E = 3F/2.
        EXPECT_EQ(welded.points.rows(), welded.triangles.rows() / 2 + 2);
        const Pairs expected = cgal_pairs(welded.points, welded.triangles);
        EXPECT_EQ(expected.empty(), !pulled);
        EXPECT_EQ(intersecting_triangle_pairs(welded.points, welded.triangles), expected);
    }
}

}  // namespace
}  // namespace limsurf
