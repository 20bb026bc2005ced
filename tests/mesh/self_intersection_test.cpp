// Self-intersection of triangle meshes (mesh/self_intersection.h): each configuration of CGAL's rule
// built by hand with its answer known, the grid search against a pair-by-pair search, welding.
// The peer comparison with CGAL itself is self_intersection_cgal_test.cpp.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/mesh/self_intersection.h"
#include "triangle_soup.h"

namespace limsurf {
namespace {

using Pairs = std::vector<std::array<Index, 2>>;

Points points_of(std::initializer_list<std::array<double, 3>> rows) {
    Points p(static_cast<Index>(rows.size()), 3);
    Index i = 0;
    for (const auto& r : rows) {
        p.row(i++) << r[0], r[1], r[2];
    }
    return p;
}

Triangles triangles_of(std::initializer_list<std::array<Index, 3>> rows) {
    Triangles t(static_cast<Index>(rows.size()), 3);
    Index i = 0;
    for (const auto& r : rows) {
        t.row(i++) << r[0], r[1], r[2];
    }
    return t;
}

bool meet(const Points& p, const Triangles& t) {
    return !intersecting_triangle_pairs(p, t).empty();
}

TEST(SelfIntersection, TrianglesWithoutCommonVertices) {
    // A horizontal triangle and a vertical one through its middle.
    const Points p = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, -1}, {1, 1, 1}, {2, 1, 1}});
    EXPECT_EQ(intersecting_triangle_pairs(p, triangles_of({{0, 1, 2}, {3, 4, 5}})), (Pairs{{0, 1}}));
    // The vertical one lifted clear of the plane, then moved beside the horizontal one.
    Points lifted = p;
    lifted.block(3, 2, 3, 1).array() += 1.5;
    EXPECT_FALSE(meet(lifted, triangles_of({{0, 1, 2}, {3, 4, 5}})));
    Points beside = p;
    beside.block(3, 0, 3, 1).array() += 10.0;
    EXPECT_FALSE(meet(beside, triangles_of({{0, 1, 2}, {3, 4, 5}})));
    // Touching: a vertex of one on the other's interior (closed point sets meet).
    const Points touch = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}, {1, 1, 1}, {2, 1, 1}});
    EXPECT_TRUE(meet(touch, triangles_of({{0, 1, 2}, {3, 4, 5}})));
    // Coplanar: overlapping, then apart.
    const Points flat = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}, {5, 1, 0}, {1, 5, 0}});
    EXPECT_TRUE(meet(flat, triangles_of({{0, 1, 2}, {3, 4, 5}})));
    Points flat_apart = flat;
    flat_apart.block(3, 0, 3, 1).array() += 10.0;
    EXPECT_FALSE(meet(flat_apart, triangles_of({{0, 1, 2}, {3, 4, 5}})));
    // Coplanar, one inside the other: no edges cross.
    const Points nested = points_of({{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0}, {1.5, 1, 0}, {1, 1.5, 0}});
    EXPECT_TRUE(meet(nested, triangles_of({{0, 1, 2}, {3, 4, 5}})));
}

TEST(SelfIntersection, TrianglesWithACommonEdge) {
    // Edge 0-1 shared; the second triangle's free vertex d.
    const auto pair_with = [](const std::array<double, 3>& d) {
        return points_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, d});
    };
    const Triangles t = triangles_of({{0, 1, 2}, {1, 0, 3}});
    EXPECT_FALSE(meet(pair_with({0.5, -1, 0}), t));      // flat, on the other side: a plane
    EXPECT_FALSE(meet(pair_with({0.5, 0.5, 1}), t));     // a hinge
    EXPECT_FALSE(meet(pair_with({0.3, 0.3, 1e-9}), t));  // nearly folded, not in the plane
    EXPECT_TRUE(meet(pair_with({0.5, 0.5, 0}), t));      // folded back onto the first: they overlap
    EXPECT_TRUE(meet(pair_with({2, 3, 0}), t));          // folded, d beyond the first triangle
}

TEST(SelfIntersection, TrianglesWithACommonVertex) {
    // Vertex 0 shared; the second triangle (0, 3, 4).
    const auto pair_with = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        return points_of({{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, a, b});
    };
    const Triangles t = triangles_of({{0, 1, 2}, {0, 3, 4}});
    EXPECT_FALSE(meet(pair_with({-1, 0, 0}, {0, -1, 0}), t));  // a flat fan, apart
    EXPECT_FALSE(meet(pair_with({1, 1, 1}, {-1, 1, 1}), t));   // above, touching only at 0
    // The second triangle's opposite edge passes through the first.
    EXPECT_TRUE(meet(pair_with({0.5, 0.5, 1}, {0.5, 0.5, -1}), t));
    // The first's opposite edge (from (2,0,0) to (0,2,0)) pierces the second, a large vertical one.
    EXPECT_TRUE(meet(pair_with({3, 3, 2}, {3, 3, -2}), t));
    // Coplanar and overlapping beyond 0.
    EXPECT_TRUE(meet(pair_with({1, 0.2, 0}, {0.2, 1, 0}), t));
    // Coplanar, the second inside the first's wedge but reaching beyond its opposite edge.
    EXPECT_TRUE(meet(pair_with({3, 1, 0}, {1, 3, 0}), t));
}

TEST(SelfIntersection, TwoTrianglesTwiceAreNotSelfIntersecting) {
    // The same triangle listed twice (all three vertices shared) and degenerate triangles are skipped.
    const Points p = points_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -1}, {0.2, 0.2, 1}});
    EXPECT_FALSE(meet(p, triangles_of({{0, 1, 2}, {0, 1, 2}})));
    EXPECT_FALSE(meet(p, triangles_of({{0, 1, 2}, {3, 4, 4}})));
}

// The octahedron, faces counter-clockwise seen from outside.
Points octahedron_points() {
    return points_of({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
}
Triangles octahedron_triangles() {
    return triangles_of({{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}});
}

TEST(SelfIntersection, ClosedSurfaceAndAVertexPushedThroughIt) {
    EXPECT_FALSE(meet(octahedron_points(), octahedron_triangles()));
    // Vertex 0 pulled across, over the top vertex: its faces pass through the faces of vertices 1
    // and 4. (Pushed straight through to beyond vertex 1 the mesh would only turn inside out, its
    // faces nested around the others' without meeting them.)
    Points p = octahedron_points();
    p.row(0) << -0.5, 0.1, 1.8;
    const Pairs pairs = intersecting_triangle_pairs(p, octahedron_triangles());
    ASSERT_FALSE(pairs.empty());
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    for (const auto& pair : pairs) {
        EXPECT_LT(pair[0], pair[1]);
    }
    // max_pairs keeps the first pairs of the sorted list.
    const Pairs two = intersecting_triangle_pairs(p, octahedron_triangles(), 2);
    ASSERT_EQ(two.size(), 2u);
    EXPECT_EQ(two[0], pairs[0]);
    EXPECT_EQ(two[1], pairs[1]);
}

// The pairs do not depend on the size: the tests multiply coordinates, and at 1e200 their products
// overflowed (a closed octahedron "met itself"). Scaled by 2^±800 the points give the same pairs.
TEST(SelfIntersection, ThePairsDoNotDependOnTheSize) {
    Points crossing = octahedron_points();
    crossing.row(0) << -0.5, 0.1, 1.8;
    for (const Points& p : {octahedron_points(), crossing}) {
        const Pairs unit = intersecting_triangle_pairs(p, octahedron_triangles());
        for (const int k : {-800, 670, 800}) {
            EXPECT_EQ(intersecting_triangle_pairs(Points(p * std::ldexp(1.0, k)), octahedron_triangles()), unit) << k;
        }
    }
    // Welding compares squared distances, which underflowed at 2^-800 (every point merged): each
    // point and a copy 1e-3 away merge, the others do not, at any size.
    Points doubled(12, 3);
    doubled << octahedron_points(), octahedron_points().array() + 1e-3;
    const WeldedTriangles unit = weld_coincident_points(doubled, octahedron_triangles(), 2e-3);
    ASSERT_EQ(unit.points.rows(), 6);
    for (const int k : {-800, 800}) {
        const double s = std::ldexp(1.0, k);
        EXPECT_EQ(weld_coincident_points(Points(doubled * s), octahedron_triangles(), 2e-3 * s).index, unit.index) << k;
    }
}

// Random triangles in a box: the grid search must find what testing every pair on its own finds,
// whatever the order of the triangles.
TEST(SelfIntersection, GridSearchFindsEveryPairOnce) {
    const Index n = 150;
    const auto [p, t] = test::random_triangle_soup(7, n, 6.0);
    Pairs brute;
    for (Index i = 0; i < n; ++i) {
        for (Index j = i + 1; j < n; ++j) {
            Triangles two(2, 3);
            two.row(0) = t.row(i);
            two.row(1) = t.row(j);
            if (meet(p, two)) {
                brute.push_back({i, j});
            }
        }
    }
    ASSERT_GT(brute.size(), 20u);  // the box is crowded enough to test the search
    EXPECT_EQ(intersecting_triangle_pairs(p, t), brute);

    // Reversed order: the same pairs under the renumbering.
    Triangles reversed = t.colwise().reverse();
    Pairs mapped;
    for (const auto& pair : intersecting_triangle_pairs(p, reversed)) {
        mapped.push_back({n - 1 - pair[1], n - 1 - pair[0]});
    }
    std::sort(mapped.begin(), mapped.end());
    EXPECT_EQ(mapped, brute);
}

// One triangle 10^6 times larger than 20 000 small ones crossing it. Cells sized by the mean triangle
// alone would list the large one in about (n/2)^2 = 10^8 cells; the grid coarsens instead, and the
// crossings are all found (measured: 0.05 s and 17 MB; 16.7 s and 2.6 GB before the cap). The
// search must take under 2 s: without the bound the test would pass on the uncapped grid too, only slowly.
TEST(SelfIntersection, OneHugeTriangleAmongSmallOnes) {
    const Index n = 20000;
    Points p(3 * n + 3, 3);
    Triangles t(n + 1, 3);
    for (Index k = 0; k < n; ++k) {       // small vertical triangles through the plane z = 0, on a diagonal
        const double x = 1.0 + 0.02 * k;  // up to 401: inside the large triangle (x + y <= 1000)
        p.row(3 * k) << x, x, -1e-3;
        p.row(3 * k + 1) << x + 1e-3, x, 1e-3;
        p.row(3 * k + 2) << x, x + 1e-3, 1e-3;
        t.row(k) << 3 * k, 3 * k + 1, 3 * k + 2;
    }
    p.row(3 * n) << 0, 0, 0;
    p.row(3 * n + 1) << 1e3, 0, 0;
    p.row(3 * n + 2) << 0, 1e3, 0;
    t.row(n) << 3 * n, 3 * n + 1, 3 * n + 2;
    const auto start = std::chrono::steady_clock::now();
    const Pairs pairs = intersecting_triangle_pairs(p, t);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
    ASSERT_EQ(pairs.size(), static_cast<std::size_t>(n));
    for (Index k = 0; k < n; ++k) {
        EXPECT_EQ(pairs[static_cast<std::size_t>(k)], (std::array<Index, 2>{k, n}));
    }
}

TEST(SelfIntersection, WeldingMergesCopiesOfAPoint) {
    // Two triangles with their own copies of the shared edge's ends, one copy off by 1e-13.
    const Points p = points_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1e-13, 0}, {0, 0, 0}, {1, -1, 0}});
    const Triangles t = triangles_of({{0, 1, 2}, {3, 4, 5}});
    const WeldedTriangles exact = weld_coincident_points(p, t, 0.0);
    EXPECT_EQ(exact.points.rows(), 5);  // only the exact copy of (0, 0, 0) merges
    const WeldedTriangles welded = weld_coincident_points(p, t, 1e-12);
    EXPECT_EQ(welded.points.rows(), 4);
    EXPECT_EQ(welded.index, (std::vector<Index>{0, 1, 2, 1, 0, 3}));
    EXPECT_EQ(welded.triangles.row(1), (Eigen::Matrix<Index, 1, 3>(1, 0, 3)));
    EXPECT_EQ(welded.points.row(1), p.row(1));  // the first copy represents the point
}

TEST(SelfIntersection, BadInputNamesTheElement) {
    const Points p = octahedron_points();
    Triangles t = octahedron_triangles();
    t(3, 2) = 6;
    EXPECT_THROW(
        {
            try {
                (void)intersecting_triangle_pairs(p, t);
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("triangle 3 corner 2: index 6 out of range"), std::string::npos)
                    << e.what();
                throw;
            }
        },
        InputError);
    Points nan = octahedron_points();
    nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)intersecting_triangle_pairs(nan, octahedron_triangles()), InputError);
    EXPECT_THROW((void)weld_coincident_points(octahedron_points(), octahedron_triangles(), -1.0), InputError);
    EXPECT_THROW((void)weld_coincident_points(octahedron_points(), octahedron_triangles(),
                                              std::numeric_limits<double>::infinity()),
                 InputError);
}

}  // namespace
}  // namespace limsurf
