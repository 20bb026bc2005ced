// Doo–Sabin refinement: classic weights, F-, E- and V-faces, and limsurf's
// Chaikin boundary rule (docs/doo_sabin.md).
//
// Child vertex c is the child of parent corner c of parent.all_face_vertices():
// corner i of face f has child index parent.face_offset(f) + i. Its provenance
// is (Face, f); the corner i is implied by c - face_offset(f), so it is not
// stored separately.
//
// Child faces, in this order:
//   F-faces: one per parent face f, [child(f, 0), ..., child(f, n-1)];
//   E-faces: one per interior parent edge e (edge order), [f_b, f_a, g_a, g_b]
//     where f traverses e from a to b and g from b to a;
//   V-faces: one per parent vertex v (vertex order) that is interior, or (unless
//     the boundary rule is None) a boundary vertex in k >= 3 faces:
//     [child of v in vertex_faces(v)[0], ..., in vertex_faces(v)[k-1]].
// Orientation follows the parent: each E- and V-face traverses its shared
// edges opposite to its neighbours.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <Eigen/SparseCore>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

/// How the child of one corner is placed.
enum class CornerRule : std::uint8_t {
    Classic,      ///< the classic Doo–Sabin mask of the face
    ChaikinPrev,  ///< 3/4 v_i + 1/4 v_{i-1}: the edge (v_{i-1}, v_i) is a boundary edge
    ChaikinNext,  ///< 3/4 v_i + 1/4 v_{i+1}: the edge (v_i, v_{i+1}) is a boundary edge
    Corner        ///< v_i: both face edges at the corner are boundary edges (a one-face corner)
};

void check_supported(const Topology& parent) {
    // An interior vertex in two faces (a two-face "pillow") would make a V-face of two corners.
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        LIMSURF_CHECK_AT(parent.is_boundary_vertex(v) || parent.vertex_faces(v).size() >= 3, UnsupportedError,
                         vertex_element(v), "Doo-Sabin refinement needs interior vertices in at least 3 faces: vertex ",
                         v, " is in ", parent.vertex_faces(v).size(),
                         " (its vertex face would have fewer than 3 corners)");
    }
    if (!parent.has_sharpness()) {
        return;
    }
    for (Index e = 0; e < parent.num_edges(); ++e) {
        LIMSURF_CHECK(parent.edge_sharpness(e) == 0.0, UnsupportedError,
                      "Doo-Sabin refinement has no crease rule: edge ", e, " has sharpness ", parent.edge_sharpness(e));
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        LIMSURF_CHECK(parent.vertex_sharpness(v) == 0.0, UnsupportedError,
                      "Doo-Sabin refinement has no corner rule: vertex ", v, " has sharpness ",
                      parent.vertex_sharpness(v));
    }
    for (Index f = 0; f < parent.num_faces(); ++f) {
        LIMSURF_CHECK(!parent.is_hole(f), UnsupportedError, "Doo-Sabin refinement does not support holes: face ", f,
                      " is a hole");
    }
}

CornerRule corner_rule(const Topology& parent, Index f, Index i, Index n, bool boundary_rule) {
    if (!boundary_rule) {
        return CornerRule::Classic;
    }
    const auto edges = parent.face_edges(f);
    const bool prev = parent.is_boundary_edge(edges[static_cast<std::size_t>((i + n - 1) % n)]);
    const bool next = parent.is_boundary_edge(edges[static_cast<std::size_t>(i)]);
    if (prev && next) {
        return CornerRule::Corner;
    }
    if (prev) {
        return CornerRule::ChaikinPrev;
    }
    if (next) {
        return CornerRule::ChaikinNext;
    }
    return CornerRule::Classic;
}

}  // namespace

Level refine_doo_sabin(const Topology& parent, const SchemeOptions& options) {
    check_supported(parent);
    const bool boundary_rule = options.boundary != BoundaryInterpolation::None;
    const Index num_faces = parent.num_faces();
    const Index num_child_vertices = parent.num_corners();
    const auto corners = parent.all_face_vertices();

    // --- S0 -------------------------------------------------------------------
    // Classic masks: row nnz = n per corner (Σ n² in all); boundary rows use at most 2.
    std::size_t num_triplets = 0;
    Index max_degree = 0;
    for (Index f = 0; f < num_faces; ++f) {
        const Index n = parent.face_degree(f);
        for (Index i = 0; i < n; ++i) {
            num_triplets +=
                corner_rule(parent, f, i, n, boundary_rule) == CornerRule::Classic ? static_cast<std::size_t>(n) : 2;
        }
        max_degree = std::max(max_degree, n);
    }
    std::vector<Eigen::Triplet<double, Index>> triplets;
    triplets.reserve(num_triplets);
    // weights[d] = (3 + 2cos(2πd/n)) / (4n) for d = 1..n-1, (n+5)/(4n) for d = 0; refilled per degree.
    std::vector<double> weights(static_cast<std::size_t>(max_degree));
    Index weights_degree = 0;
    for (Index f = 0; f < num_faces; ++f) {
        const Index n = parent.face_degree(f);
        const Index offset = parent.face_offset(f);
        const auto fv = parent.face_vertices(f);
        if (n != weights_degree) {
            const double dn = static_cast<double>(n);
            weights[0] = (dn + 5.0) / (4.0 * dn);
            for (Index d = 1; d < n; ++d) {
                weights[static_cast<std::size_t>(d)] =
                    (3.0 + 2.0 * std::cos(2.0 * std::numbers::pi * static_cast<double>(d) / dn)) / (4.0 * dn);
            }
            weights_degree = n;
        }
        for (Index i = 0; i < n; ++i) {
            const Index child = offset + i;
            const Index vi = fv[static_cast<std::size_t>(i)];
            const Index prev = fv[static_cast<std::size_t>((i + n - 1) % n)];
            const Index next = fv[static_cast<std::size_t>((i + 1) % n)];
            switch (corner_rule(parent, f, i, n, boundary_rule)) {
            case CornerRule::Classic:
                for (Index k = 0; k < n; ++k) {
                    triplets.emplace_back(child, fv[static_cast<std::size_t>(k)],
                                          weights[static_cast<std::size_t>((k - i + n) % n)]);
                }
                break;
            case CornerRule::ChaikinPrev:
                triplets.emplace_back(child, vi, 0.75);
                triplets.emplace_back(child, prev, 0.25);
                break;
            case CornerRule::ChaikinNext:
                triplets.emplace_back(child, vi, 0.75);
                triplets.emplace_back(child, next, 0.25);
                break;
            case CornerRule::Corner:
                triplets.emplace_back(child, vi, 1.0);
                break;
            }
        }
    }
    Level level;
    level.S0.resize(num_child_vertices, parent.num_vertices());
    level.S0.setFromTriplets(triplets.begin(), triplets.end());
    level.S0.makeCompressed();

    // --- child faces -------------------------------------------------------------
    Index num_e_faces = 0;
    for (Index e = 0; e < parent.num_edges(); ++e) {
        num_e_faces += parent.is_boundary_edge(e) ? 0 : 1;
    }
    Index num_v_faces = 0;
    std::size_t num_v_corners = 0;
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto k = parent.vertex_faces(v).size();
        if (!parent.is_boundary_vertex(v) || (boundary_rule && k >= 3)) {
            ++num_v_faces;
            num_v_corners += k;
        }
    }
    const Index num_child_faces = num_faces + num_e_faces + num_v_faces;
    std::vector<Index> offsets;
    offsets.reserve(static_cast<std::size_t>(num_child_faces) + 1);
    std::vector<Index> face_vertices;
    face_vertices.reserve(corners.size() + 4 * static_cast<std::size_t>(num_e_faces) + num_v_corners);
    Provenance& prov = level.provenance;
    prov.face_parent_kind.reserve(static_cast<std::size_t>(num_child_faces));
    prov.face_parent.reserve(static_cast<std::size_t>(num_child_faces));
    prov.face_parent_corner.assign(static_cast<std::size_t>(num_child_faces), invalid_index);

    offsets.push_back(0);
    // F-faces: the children of the corners of f, in corner order.
    for (Index f = 0; f < num_faces; ++f) {
        const Index offset = parent.face_offset(f);
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            face_vertices.push_back(offset + i);
        }
        offsets.push_back(static_cast<Index>(face_vertices.size()));
        prov.face_parent_kind.push_back(ParentKind::Face);
        prov.face_parent.push_back(f);
    }
    // E-faces. The child of the corner of face g at vertex w: g's corner k with
    // face_vertices(g)[k] == w; face_edges(g)[k] runs from corner k to k+1.
    for (Index e = 0; e < parent.num_edges(); ++e) {
        const auto ef = parent.edge_faces(e);
        if (ef.size() != 2) {
            continue;
        }
        // edge_faces lists first the face traversing lower -> higher: f runs a -> b, g runs b -> a.
        const Index f = ef[0];
        const Index g = ef[1];
        Index fa = invalid_index;  // f's corner at a (f's tail)
        Index gb = invalid_index;  // g's corner at b (g's tail)
        const auto f_edges = parent.face_edges(f);
        for (std::size_t k = 0; k < f_edges.size(); ++k) {
            if (f_edges[k] == e) {
                fa = parent.face_offset(f) + static_cast<Index>(k);
            }
        }
        const auto g_edges = parent.face_edges(g);
        for (std::size_t k = 0; k < g_edges.size(); ++k) {
            if (g_edges[k] == e) {
                gb = parent.face_offset(g) + static_cast<Index>(k);
            }
        }
        LIMSURF_ASSERT(fa != invalid_index && gb != invalid_index, "edge ", e);
        const Index fn = parent.face_degree(f);
        const Index gn = parent.face_degree(g);
        const Index f_offset = parent.face_offset(f);
        const Index g_offset = parent.face_offset(g);
        const Index fb = f_offset + (fa - f_offset + 1) % fn;
        const Index ga = g_offset + (gb - g_offset + 1) % gn;
        LIMSURF_ASSERT(corners[static_cast<std::size_t>(fa)] == corners[static_cast<std::size_t>(ga)] &&
                           corners[static_cast<std::size_t>(fb)] == corners[static_cast<std::size_t>(gb)],
                       "edge ", e);
        face_vertices.push_back(fb);
        face_vertices.push_back(fa);
        face_vertices.push_back(ga);
        face_vertices.push_back(gb);
        offsets.push_back(static_cast<Index>(face_vertices.size()));
        prov.face_parent_kind.push_back(ParentKind::Edge);
        prov.face_parent.push_back(e);
    }
    // V-faces: the children of v's corners, counter-clockwise about v.
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto vf = parent.vertex_faces(v);
        if (parent.is_boundary_vertex(v) && !(boundary_rule && vf.size() >= 3)) {
            continue;
        }
        const auto vc = parent.vertex_face_corners(v);
        for (std::size_t i = 0; i < vf.size(); ++i) {
            face_vertices.push_back(parent.face_offset(vf[i]) + vc[i]);
        }
        offsets.push_back(static_cast<Index>(face_vertices.size()));
        prov.face_parent_kind.push_back(ParentKind::Vertex);
        prov.face_parent.push_back(v);
    }

    prov.vertex_parent_kind.assign(static_cast<std::size_t>(num_child_vertices), ParentKind::Face);
    prov.vertex_parent.resize(static_cast<std::size_t>(num_child_vertices));
    for (Index f = 0; f < num_faces; ++f) {
        const Index offset = parent.face_offset(f);
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            prov.vertex_parent[static_cast<std::size_t>(offset + i)] = f;
        }
    }
    level.topology = detail::refined_topology(num_child_vertices, offsets, face_vertices, {});
    return level;
}

}  // namespace limsurf
