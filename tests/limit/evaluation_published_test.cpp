// Published limit masks, reproduced by the limit basis:
//   - regular Catmull–Clark: the limit of a vertex is (1,4,1)/6 ⊗ (1,4,1)/6 of its 3×3
//     neighbourhood (uniform bicubic B-spline at a knot; iga-with-catmull-clark §3);
//   - Catmull–Clark extraordinary vertex of valence n (Halstead, Kass, DeRose 1993):
//     (n² v + 4 Σ edge neighbours + Σ face-diagonal neighbours) / (n (n + 5));
//   - Loop vertex of valence n (Loop 1987): (1 − n χ) v + χ Σ neighbours with
//     χ = 1 / (3 / (8 β) + n), β = (5/8 − (3/8 + cos(2π/n)/4)²) / n;
//   - the crease/boundary curve: (1,4,1)/6 along the boundary (cubic B-spline).
#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

Topology load_topology(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    return built.mesh.topology();
}

std::map<Index, double> mask_of(const LimitWeights& w) {
    std::map<Index, double> mask;
    for (Index i = 0; i < w.size(); ++i) {
        if (std::abs(w.w(0, i)) > 1e-15) {
            mask[w.vertices[static_cast<std::size_t>(i)]] += w.w(0, i);
        }
    }
    return mask;
}

/// Neighbours of interior vertex v: across an edge, and face-diagonal (quads).
void neighbours(const Topology& t, Index v, std::vector<Index>& edge, std::vector<Index>& diagonal) {
    for (Index e : t.vertex_edges(v)) {
        edge.push_back(t.other_vertex(e, v));
    }
    const auto faces = t.vertex_faces(v);
    const auto corners = t.vertex_face_corners(v);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const auto fv = t.face_vertices(faces[i]);
        if (fv.size() == 4) {
            diagonal.push_back(fv[static_cast<std::size_t>((corners[i] + 2) % 4)]);
        }
    }
}

void expect_catmull_clark_mask(const Topology& t, const LimitBasis& basis, Index v) {
    const auto n = static_cast<double>(t.valence(v));
    std::vector<Index> edge, diagonal;
    neighbours(t, v, edge, diagonal);
    const auto mask = mask_of(basis.vertex_limit(v));
    ASSERT_EQ(mask.size(), 1 + edge.size() + diagonal.size()) << "vertex " << v;
    const double denominator = n * (n + 5.0);
    EXPECT_NEAR(mask.at(v), n * n / denominator, 1e-14) << "vertex " << v;
    for (Index x : edge) {
        EXPECT_NEAR(mask.at(x), 4.0 / denominator, 1e-14) << "edge neighbour " << x << " of " << v;
    }
    for (Index x : diagonal) {
        EXPECT_NEAR(mask.at(x), 1.0 / denominator, 1e-14) << "diagonal neighbour " << x << " of " << v;
    }
}

TEST(LimitPublished, RegularCatmullClarkVertexIsOneFourOneSquared) {
    const Topology t = load_topology("quad_grid");
    const LimitBasis basis(t, SchemeKind::CatmullClark);
    int checked = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (!t.is_boundary_vertex(v) && t.valence(v) == 4) {
            // n = 4: 16/36 centre, 4/36 edge neighbours, 1/36 diagonal = (1,4,1)/6 ⊗ (1,4,1)/6.
            expect_catmull_clark_mask(t, basis, v);
            ++checked;
        }
    }
    EXPECT_GT(checked, 0);
}

TEST(LimitPublished, CatmullClarkExtraordinaryVertexMaskOfHalstead) {
    for (int n : {3, 5, 6, 7, 8}) {
        const Topology t = load_topology("quad_valence_" + std::to_string(n));
        const LimitBasis basis(t, SchemeKind::CatmullClark);
        int checked = 0;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (!t.is_boundary_vertex(v) && t.valence(v) == n) {
                SCOPED_TRACE("valence " + std::to_string(n));
                expect_catmull_clark_mask(t, basis, v);
                ++checked;
            }
        }
        EXPECT_GT(checked, 0) << "no vertex of valence " << n;
    }
}

TEST(LimitPublished, LoopVertexMask) {
    for (int n : {3, 4, 5, 6, 7, 8, 9, 10, 11, 12}) {
        const Topology t = load_topology("tri_valence_" + std::to_string(n));
        const LimitBasis basis(t, SchemeKind::Loop);
        const double c = 3.0 / 8.0 + std::cos(2.0 * std::numbers::pi / n) / 4.0;
        const double beta = (5.0 / 8.0 - c * c) / n;
        const double chi = 1.0 / (3.0 / (8.0 * beta) + n);
        int checked = 0;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (t.is_boundary_vertex(v) || t.valence(v) != n) {
                continue;
            }
            const auto mask = mask_of(basis.vertex_limit(v));
            ASSERT_EQ(static_cast<int>(mask.size()), n + 1) << "valence " << n;
            EXPECT_NEAR(mask.at(v), 1.0 - n * chi, 1e-14) << "valence " << n;
            for (Index e : t.vertex_edges(v)) {
                EXPECT_NEAR(mask.at(t.other_vertex(e, v)), chi, 1e-14) << "valence " << n;
            }
            ++checked;
        }
        EXPECT_GT(checked, 0) << "no vertex of valence " << n;
    }
}

TEST(LimitPublished, BoundaryVertexIsOneFourOneAlongTheBoundary) {
    const Topology t = load_topology("quad_grid");
    const LimitBasis basis(t, SchemeKind::CatmullClark);
    int checked = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (!t.is_boundary_vertex(v) || t.vertex_faces(v).size() != 2) {
            continue;
        }
        const auto mask = mask_of(basis.vertex_limit(v));
        ASSERT_EQ(mask.size(), 3u) << "vertex " << v;
        EXPECT_NEAR(mask.at(v), 4.0 / 6.0, 1e-14);
        for (Index e : t.vertex_edges(v)) {
            if (t.is_boundary_edge(e)) {
                EXPECT_NEAR(mask.at(t.other_vertex(e, v)), 1.0 / 6.0, 1e-14);
            }
        }
        ++checked;
    }
    EXPECT_GT(checked, 0);
}

}  // namespace
}  // namespace limsurf::test
