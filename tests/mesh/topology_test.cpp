// Topology queries on small generated meshes; the bundled meshes are checked
// against their analytic counts in bundled_meshes_test.cpp.
#include <algorithm>
#include <cstddef>
#include <set>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/mesh/topology.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

/// The invariants every Topology must satisfy, checked element by element.
void expect_consistent(const Topology& t) {
    // face -> edge incidence and signs
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto corners = t.face_vertices(f);
        const auto n = static_cast<Index>(corners.size());
        ASSERT_EQ(t.face_degree(f), n);
        for (Index k = 0; k < n; ++k) {
            const Index a = corners[static_cast<std::size_t>(k)];
            const Index b = corners[static_cast<std::size_t>((k + 1) % n)];
            const Index e = t.face_edges(f)[static_cast<std::size_t>(k)];
            const auto ends = t.edge_vertices(e);
            EXPECT_LT(ends[0], ends[1]);
            EXPECT_EQ(ends[0], std::min(a, b));
            EXPECT_EQ(ends[1], std::max(a, b));
            EXPECT_EQ(t.face_edge_signs(f)[static_cast<std::size_t>(k)], a < b ? 1 : -1);
            const auto faces = t.edge_faces(e);
            EXPECT_NE(std::find(faces.begin(), faces.end(), f), faces.end());
            EXPECT_EQ(t.find_edge(a, b), e);
            EXPECT_EQ(t.find_edge(b, a), e);
        }
    }
    // one-rings: face i lies between edge i (leaving v) and edge i+1 (entering v)
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const auto faces = t.vertex_faces(v);
        const auto edges = t.vertex_edges(v);
        const auto corners = t.vertex_face_corners(v);
        ASSERT_FALSE(faces.empty());
        EXPECT_EQ(edges.size(), faces.size() + (t.is_boundary_vertex(v) ? 1 : 0));
        EXPECT_EQ(t.valence(v), static_cast<Index>(edges.size()));
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const auto fv = t.face_vertices(faces[i]);
            const auto n = fv.size();
            const auto k = static_cast<std::size_t>(corners[i]);
            ASSERT_EQ(fv[k], v);
            EXPECT_EQ(t.other_vertex(edges[i], v), fv[(k + 1) % n]);
            EXPECT_EQ(t.other_vertex(edges[(i + 1) % edges.size()], v), fv[(k + n - 1) % n]);
        }
        if (t.is_boundary_vertex(v)) {
            EXPECT_TRUE(t.is_boundary_edge(edges.front()));
            EXPECT_TRUE(t.is_boundary_edge(edges.back()));
        }
    }
    EXPECT_EQ(t.euler_characteristic(), t.num_vertices() - t.num_edges() + t.num_faces());
}

TEST(Topology, CubeCountsAndInvariants) {
    const Topology t = Topology::from_polygons(8, test::cube_faces());
    EXPECT_EQ(t.num_vertices(), 8);
    EXPECT_EQ(t.num_edges(), 12);
    EXPECT_EQ(t.num_faces(), 6);
    EXPECT_EQ(t.num_corners(), 24);
    EXPECT_EQ(t.euler_characteristic(), 2);
    EXPECT_EQ(t.genus(), 0);
    EXPECT_EQ(t.num_components(), 1);
    EXPECT_TRUE(t.is_closed());
    EXPECT_EQ(t.num_boundary_loops(), 0);
    EXPECT_TRUE(t.all_faces_have_degree(4));
    for (Index v = 0; v < 8; ++v) {
        EXPECT_EQ(t.valence(v), 3);
        EXPECT_FALSE(t.is_boundary_vertex(v));
    }
    for (Index e = 0; e < t.num_edges(); ++e) {
        ASSERT_EQ(t.edge_faces(e).size(), 2U);
        // The first face traverses the edge from lower to higher index.
        const Index f = t.edge_faces(e)[0];
        const auto edges = t.face_edges(f);
        const auto k = static_cast<std::size_t>(std::find(edges.begin(), edges.end(), e) - edges.begin());
        EXPECT_EQ(t.face_edge_signs(f)[k], 1);
    }
    expect_consistent(t);
}

TEST(Topology, EveryEdgeIsTraversedOnceEachWayOnClosedMeshes) {
    // d1 columns on a closed oriented surface: one +1 and one -1 per edge.
    const Topology t = Topology::from_polygons(48, test::torus_faces(8, 6));
    std::vector<int> sum(static_cast<std::size_t>(t.num_edges()), 0);
    for (Index f = 0; f < t.num_faces(); ++f) {
        for (std::size_t k = 0; k < t.face_edges(f).size(); ++k) {
            sum[static_cast<std::size_t>(t.face_edges(f)[k])] += t.face_edge_signs(f)[k];
        }
    }
    EXPECT_TRUE(std::all_of(sum.begin(), sum.end(), [](int s) { return s == 0; }));
}

TEST(Topology, TorusHasGenusOne) {
    const Topology t = Topology::from_polygons(48, test::torus_faces(8, 6));
    EXPECT_EQ(t.num_edges(), 96);
    EXPECT_EQ(t.euler_characteristic(), 0);
    EXPECT_EQ(t.genus(), 1);
    EXPECT_TRUE(t.is_closed());
    expect_consistent(t);
}

TEST(Topology, GridBoundaryLoopRunsWithInteriorOnTheLeft) {
    const Index n = 3;
    const Topology t = Topology::from_polygons((n + 1) * (n + 1), test::grid_faces(n, n));
    const Points x = test::grid_positions(n, n);
    expect_consistent(t);
    EXPECT_EQ(t.num_boundary_loops(), 1);
    EXPECT_FALSE(t.is_closed());
    EXPECT_EQ(t.euler_characteristic(), 1);
    EXPECT_EQ(t.genus(), 0);
    const auto loop = t.boundary_loop(0);
    ASSERT_EQ(loop.size(), 12U);
    // Counter-clockwise around the +z normal: positive signed area.
    double area = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const auto a = x.row(loop[i]);
        const auto b = x.row(loop[(i + 1) % loop.size()]);
        area += 0.5 * (a(0) * b(1) - b(0) * a(1));
        EXPECT_NE(t.find_edge(loop[i], loop[(i + 1) % loop.size()]), invalid_index);
    }
    EXPECT_DOUBLE_EQ(area, 9.0);
    // Corner vertex: valence 2, one face; interior vertex: valence 4.
    EXPECT_EQ(t.valence(0), 2);
    EXPECT_EQ(t.vertex_faces(0).size(), 1U);
    EXPECT_TRUE(t.is_boundary_vertex(0));
    EXPECT_EQ(t.valence(5), 4);
    EXPECT_FALSE(t.is_boundary_vertex(5));
}

TEST(Topology, OneRingsTurnCounterClockwiseInThePlane) {
    const Index n = 4;
    const Topology t = Topology::from_polygons((n + 1) * (n + 1), test::grid_faces(n, n));
    const Points x = test::grid_positions(n, n);
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const auto edges = t.vertex_edges(v);
        for (std::size_t i = 0; i + 1 < edges.size() || (!t.is_boundary_vertex(v) && i < edges.size()); ++i) {
            const Eigen::RowVector3d a = x.row(t.other_vertex(edges[i], v)) - x.row(v);
            const Eigen::RowVector3d b = x.row(t.other_vertex(edges[(i + 1) % edges.size()], v)) - x.row(v);
            EXPECT_GT(a.cross(b)(2), 0.0) << "vertex " << v << " step " << i;
        }
    }
}

TEST(Topology, CornersBeyondAByteAreKeptExactly) {
    // A Topology keeps one-ring corners in a byte each and the corners of faces of 255 corners and
    // more beside that table: a 300-gon in a ring of quads, built from its face list (the one-ring
    // walk) and its Doo–Sabin child (whose F-face is a 300-gon again) built from the parent's tables.
    const Index n = 300;
    std::vector<std::vector<Index>> faces(1);
    for (Index i = 0; i < n; ++i) {
        faces[0].push_back(i);
        faces.push_back({(i + 1) % n, i, n + i, n + (i + 1) % n});
    }
    const Topology t = Topology::from_polygons(2 * n, faces);
    expect_consistent(t);
    for (Index v = 0; v < n; ++v) {
        const auto ring = t.vertex_faces(v);
        const auto corners = t.vertex_face_corners(v);
        const auto in_polygon = std::find(ring.begin(), ring.end(), 0) - ring.begin();
        ASSERT_LT(in_polygon, static_cast<std::ptrdiff_t>(ring.size()));
        EXPECT_EQ(corners[static_cast<std::size_t>(in_polygon)], v);
        // Iterating the view gives what indexing it gives, slot by slot, large corners included.
        const std::vector<Index> iterated(corners.begin(), corners.end());
        ASSERT_EQ(iterated.size(), ring.size());
        for (std::size_t k = 0; k < iterated.size(); ++k) {
            EXPECT_EQ(iterated[k], corners[k]) << "vertex " << v << " slot " << k;
            EXPECT_EQ(t.face_vertices(ring[k])[static_cast<std::size_t>(iterated[k])], v);
        }
    }

    const Topology child = detail::doo_sabin_topology(t, true);
    std::vector<Index> offsets;
    std::vector<Index> corners;
    detail::doo_sabin_faces(t, true, offsets, corners);
    const Topology general(child.num_vertices(), offsets, corners);
    expect_consistent(child);
    ASSERT_EQ(child.num_vertices(), general.num_vertices());
    Index large = 0;
    for (Index v = 0; v < child.num_vertices(); ++v) {
        const auto ours = child.vertex_face_corners(v);
        const auto theirs = general.vertex_face_corners(v);
        EXPECT_EQ(std::vector<Index>(ours.begin(), ours.end()), std::vector<Index>(theirs.begin(), theirs.end()))
            << "vertex " << v;
        large += std::count_if(ours.begin(), ours.end(), [](Index c) { return c >= 255; });
    }
    EXPECT_EQ(large, n - 255);  // the F-face's corners 255..299
}

TEST(Topology, MixedDegreesAndComponents) {
    // A square pyramid (4 triangles + 1 quad) and, disjoint, a tetrahedron.
    const std::vector<std::vector<Index>> faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4},
                                                   {5, 7, 6},    {5, 6, 8}, {6, 7, 8}, {7, 5, 8}};
    const Topology t = Topology::from_polygons(9, faces);
    expect_consistent(t);
    EXPECT_EQ(t.num_components(), 2);
    EXPECT_EQ(t.euler_characteristic(), 4);
    EXPECT_EQ(t.genus(), 0);
    EXPECT_EQ(t.face_component(0), 0);
    EXPECT_EQ(t.face_component(5), 1);
    EXPECT_EQ(t.vertex_component(8), 1);
    EXPECT_EQ(t.valence(4), 4);
    EXPECT_FALSE(t.all_faces_have_degree(3));
}

TEST(Topology, SharpnessIsCarriedOnEdgesAndVertices) {
    SharpnessTags tags;
    tags.creases.push_back({3, 1, 2.5, 0});
    tags.corners.push_back({7, infinite_sharpness, 0});
    tags.holes.push_back({2, 0});
    const Topology t = Topology::from_polygons(8, test::cube_faces(), tags);
    EXPECT_TRUE(t.has_sharpness());
    EXPECT_DOUBLE_EQ(t.edge_sharpness(t.find_edge(1, 3)), 2.5);
    EXPECT_DOUBLE_EQ(t.edge_sharpness(t.find_edge(0, 1)), 0.0);
    EXPECT_DOUBLE_EQ(t.vertex_sharpness(7), infinite_sharpness);
    EXPECT_DOUBLE_EQ(t.vertex_sharpness(0), 0.0);
    EXPECT_TRUE(t.is_hole(2));
    EXPECT_FALSE(t.is_hole(0));
    const SharpnessTags back = t.sharpness_tags();
    ASSERT_EQ(back.creases.size(), 1U);
    EXPECT_EQ(back.creases[0].v0, 1);
    EXPECT_EQ(back.creases[0].v1, 3);
    ASSERT_EQ(back.corners.size(), 1U);
    ASSERT_EQ(back.holes.size(), 1U);

    const Topology smooth = Topology::from_polygons(8, test::cube_faces());
    EXPECT_FALSE(smooth.has_sharpness());
}

TEST(Topology, RefusesBadConnectivityWithTheElementNamed) {
    auto message = [](Index nv, const std::vector<std::vector<Index>>& faces) -> std::string {
        try {
            (void)Topology::from_polygons(nv, faces);
        } catch (const Error& error) {
            return error.what();
        }
        return "no error";
    };
    EXPECT_EQ(message(5, {{0, 1, 2}, {0, 3, 4}}),
              "vertex 0 is non-manifold: its faces form 2 fans that meet only at this vertex (bow-tie)");
    EXPECT_EQ(message(4, {{0, 1, 2}}), "vertex 3 is in no face (isolated); a Topology cannot hold isolated vertices");
    EXPECT_EQ(message(2, {{0, 1}}), "face 0 has 2 vertices (a face needs at least 3)");
    EXPECT_EQ(message(3, {{0, 1, 3}}), "face 0 refers to vertex 3, out of range [0, 2] (and 1 more error)");
    EXPECT_EQ(message(0, {}), "no faces (0 vertices and no face)");
    EXPECT_THROW((void)Topology::from_polygons(5, {{0, 1, 2}, {0, 3, 4}}), TopologyError);
    EXPECT_THROW((void)Topology::from_polygons(3, {{0, 1, 1}}), InputError);
}

// The Topology constructor leaves bow-ties to its one-ring walk (which stops short at one) and then
// reports them as validate() does: closed fans (the walk comes round early), open fans (it meets a
// boundary edge early), mixed, three fans, a bow-tie walked after good vertices, and two of them.
TEST(Topology, FindsEveryKindOfBowTieInItsOneRingWalk) {
    const auto tetrahedron = [](Index a, Index b, Index c, Index d) {
        return std::vector<std::vector<Index>>{{a, c, b}, {a, b, d}, {a, d, c}, {b, c, d}};
    };
    const auto joined = [](std::vector<std::vector<Index>> x, const std::vector<std::vector<Index>>& y) {
        x.insert(x.end(), y.begin(), y.end());
        return x;
    };
    const auto error_of = [](Index nv, const std::vector<std::vector<Index>>& faces) -> std::string {
        try {
            (void)Topology::from_polygons(nv, faces);
        } catch (const TopologyError& error) {
            return error.what();
        }
        return "no error";
    };
    const std::string two_fans =
        "vertex 0 is non-manifold: its faces form 2 fans that meet only at this vertex (bow-tie)";
    EXPECT_EQ(error_of(7, joined(tetrahedron(0, 1, 2, 3), tetrahedron(0, 4, 5, 6))), two_fans);  // closed + closed
    EXPECT_EQ(error_of(6, joined(tetrahedron(0, 1, 2, 3), {{0, 4, 5}})), two_fans);              // closed + open
    EXPECT_EQ(error_of(6, joined({{0, 4, 5}}, tetrahedron(0, 1, 2, 3))), two_fans);              // open + closed
    EXPECT_EQ(error_of(7, {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}}),
              "vertex 0 is non-manifold: its faces form 3 fans that meet only at this vertex (bow-tie)");
    // Vertex 6 is walked after vertices 1..5, whose walks are complete.
    EXPECT_EQ(error_of(7, joined(tetrahedron(1, 2, 3, 6), tetrahedron(4, 5, 0, 6))),
              "vertex 6 is non-manifold: its faces form 2 fans that meet only at this vertex (bow-tie)");
    EXPECT_EQ(error_of(9, joined(joined(tetrahedron(0, 1, 2, 3), tetrahedron(0, 4, 5, 6)), {{6, 7, 8}})),
              two_fans + " (and 1 more error)");
    // Manifold meshes next to them still build: a closed and an open fan at every vertex.
    EXPECT_NO_THROW((void)Topology::from_polygons(4, tetrahedron(0, 1, 2, 3)));
    EXPECT_NO_THROW((void)Topology::from_polygons(4, {{0, 1, 2}, {0, 2, 3}}));
}

TEST(Topology, RejectsCreaseOnMissingEdge) {
    SharpnessTags tags;
    tags.creases.push_back({0, 7, 1.0, 0});
    EXPECT_THROW((void)Topology::from_polygons(8, test::cube_faces(), tags), InputError);
}

}  // namespace
}  // namespace limsurf
