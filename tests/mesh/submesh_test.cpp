// face_submesh: kept faces as a mesh of their own, vertices split into their fans. The fans are
// counted here independently, by joining kept faces across the edges they share at a vertex, and
// where no vertex is pinched the result must equal the plain renumbering (test::carve).
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/mesh/submesh.h"
#include "limsurf/mesh/topology.h"
#include "support/mesh_zoo.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// The number of fans of kept faces at v: kept faces at v joined when they share an edge at v.
Index count_fans(const Topology& t, const std::vector<char>& keep, Index v) {
    const auto faces = t.vertex_faces(v);
    std::vector<std::size_t> root(faces.size());
    std::iota(root.begin(), root.end(), std::size_t{0});
    const auto find = [&](std::size_t i) {
        while (root[i] != i) {
            i = root[i];
        }
        return i;
    };
    for (std::size_t i = 0; i < faces.size(); ++i) {
        for (std::size_t j = 0; j < faces.size(); ++j) {
            if (!keep[at(faces[i])] || !keep[at(faces[j])] || i == j) {
                continue;
            }
            for (const Index e : t.face_edges(faces[i])) {
                const auto ends = t.edge_vertices(e);
                const auto across = t.edge_faces(e);
                const bool at_v = ends[0] == v || ends[1] == v;
                if (at_v && across.size() == 2 && (across[0] == faces[j] || across[1] == faces[j])) {
                    root[find(i)] = find(j);
                }
            }
        }
    }
    Index fans = 0;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        fans += keep[at(faces[i])] && find(i) == i ? 1 : 0;
    }
    return fans;
}

/// Every kept face's corners map back to the parent's, each parent vertex has one submesh vertex
/// per fan, and where the plain renumbering is a manifold the submesh is exactly it.
void expect_submesh_of(const Topology& t, const std::vector<char>& keep) {
    const Submesh sub = face_submesh(t, keep);
    ASSERT_EQ(sub.vertex_origin.size(), at(sub.topology.num_vertices()));
    ASSERT_EQ(sub.face_origin.size(), at(sub.topology.num_faces()));
    std::vector<Index> kept_faces;
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (keep[at(f)]) {
            kept_faces.push_back(f);
        }
    }
    ASSERT_EQ(sub.face_origin, kept_faces);
    for (Index g = 0; g < sub.topology.num_faces(); ++g) {
        const auto corners = sub.topology.face_vertices(g);
        const auto parent = t.face_vertices(sub.face_origin[at(g)]);
        ASSERT_EQ(corners.size(), parent.size());
        for (std::size_t k = 0; k < corners.size(); ++k) {
            EXPECT_EQ(sub.vertex_origin[at(corners[k])], parent[k]);
        }
    }
    std::vector<Index> copies(at(t.num_vertices()), 0);
    for (const Index v : sub.vertex_origin) {
        ++copies[at(v)];
    }
    bool pinched = false;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        EXPECT_EQ(copies[at(v)], count_fans(t, keep, v)) << "vertex " << v;
        pinched = pinched || copies[at(v)] > 1;
    }
    const auto carved = test::carve(t, std::vector<bool>(keep.begin(), keep.end()));
    EXPECT_EQ(carved.has_value(), !pinched);
    if (carved) {
        EXPECT_EQ(sub.vertex_origin, carved->original_vertex);
        EXPECT_TRUE(std::ranges::equal(sub.topology.all_face_vertices(), carved->topology.all_face_vertices()));
        EXPECT_EQ(sub.topology.num_boundary_loops(), carved->topology.num_boundary_loops());
    }
}

TEST(Submesh, KeepingEveryFaceGivesTheParentBack) {
    for (const char* name : {"genus2", "shell_hemisphere", "disk_ev7_tris"}) {
        const FinestLevel mesh = test::refined_bundled(name, SchemeKind::Bilinear, 0);
        const Topology& t = mesh.topology;
        const std::vector<char> all(at(t.num_faces()), 1);
        const Submesh sub = face_submesh(t, all);
        EXPECT_EQ(sub.topology.num_vertices(), t.num_vertices()) << name;
        EXPECT_EQ(sub.topology.num_edges(), t.num_edges()) << name;
        EXPECT_EQ(sub.topology.genus(), t.genus()) << name;
        EXPECT_EQ(sub.topology.num_boundary_loops(), t.num_boundary_loops()) << name;
        expect_submesh_of(t, all);
    }
}

TEST(Submesh, SplitsAVertexWhereKeptFacesMeetOnlyAtIt) {
    // A 4×4 grid keeping its diagonal quads 0, 5, 10, 15 (each meets the next at one corner only)
    // and the other two corner quads: each quad becomes a component of its own.
    const Topology t = Topology::from_polygons(25, test::grid_faces(4, 4));
    std::vector<char> keep(16, 0);
    keep[0] = keep[5] = keep[10] = keep[15] = keep[3] = keep[12] = 1;
    const Submesh sub = face_submesh(t, keep);
    EXPECT_EQ(sub.topology.num_vertices(), 6 * 4);
    EXPECT_EQ(sub.topology.num_components(), 6);
    expect_submesh_of(t, keep);
    // Quads that share an edge at a vertex stay one fan: the bottom row's quads 1 and 2.
    std::vector<char> bottom(16, 0);
    bottom[1] = bottom[2] = 1;
    const Submesh two = face_submesh(t, bottom);
    EXPECT_EQ(two.topology.num_vertices(), 6);
    EXPECT_EQ(two.topology.num_components(), 1);
    expect_submesh_of(t, bottom);
}

TEST(Submesh, EveryRandomSelectionIsAManifoldWithAVertexPerFan) {
    std::mt19937 random(2027);
    for (const auto& [name, scheme] :
         {std::pair{"genus2", SchemeKind::CatmullClark}, std::pair{"disk_ev7_tris", SchemeKind::Loop},
          std::pair{"shell_hemisphere", SchemeKind::CatmullClark}}) {
        const FinestLevel mesh = test::refined_bundled(name, scheme, 1);
        const Topology& t = mesh.topology;
        for (const double fraction : {0.2, 0.5, 0.8}) {
            std::bernoulli_distribution coin(fraction);
            for (int trial = 0; trial < 5; ++trial) {
                std::vector<char> keep(at(t.num_faces()));
                for (char& k : keep) {
                    k = coin(random) ? 1 : 0;
                }
                keep[0] = 1;
                SCOPED_TRACE(testing::Message() << name << " fraction " << fraction << " trial " << trial);
                expect_submesh_of(t, keep);
            }
        }
    }
}

TEST(Submesh, RefusesASelectionOfTheWrongSizeOrOfNothing) {
    const Topology t = Topology::from_polygons(9, test::grid_faces(2, 2));
    EXPECT_THROW((void)face_submesh(t, std::vector<char>(3, 1)), InputError);
    EXPECT_THROW((void)face_submesh(t, std::vector<char>(4, 0)), InputError);
}

}  // namespace
}  // namespace limsurf
