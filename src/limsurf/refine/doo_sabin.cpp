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
//
// A step runs as the face splits' do (detail::StepRun): the rows, one per child vertex in
// corner order, are built in order (SparseRowBuilder, or the carried points), while the
// child's Topology (detail::doo_sabin_topology: built from the parent's tables, as the face
// splits' are), or only its face list, is built on a second thread.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

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
    const bool prev = parent.is_boundary_edge(edges[at((i + n - 1) % n)]);
    const bool next = parent.is_boundary_edge(edges[at(i)]);
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

/// How many child faces of each kind.
struct ChildFaceCounts {
    Index edge_faces = 0;             ///< interior parent edges
    Index vertex_faces = 0;           ///< parent vertices with a V-face
    Index boundary_vertex_faces = 0;  ///< of which on the boundary (each closes with a boundary edge)
};

ChildFaceCounts count_child_faces(const Topology& parent, bool boundary_rule) {
    ChildFaceCounts counts;
    for (Index e = 0; e < parent.num_edges(); ++e) {
        counts.edge_faces += parent.is_boundary_edge(e) ? 0 : 1;
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (detail::has_doo_sabin_vertex_face(parent, v, boundary_rule)) {
            ++counts.vertex_faces;
            counts.boundary_vertex_faces += parent.is_boundary_vertex(v) ? 1 : 0;
        }
    }
    return counts;
}

/// The parent of each child face (F-, E-, V-faces in detail::doo_sabin_faces' order) and of each
/// child vertex (the face of its corner).
Provenance doo_sabin_provenance(const Topology& parent, bool boundary_rule) {
    const ChildFaceCounts counts = count_child_faces(parent, boundary_rule);
    const auto num_child_faces = at(parent.num_faces() + counts.edge_faces + counts.vertex_faces);
    Provenance p;
    p.face_parent_kind.reserve(num_child_faces);
    p.face_parent.reserve(num_child_faces);
    p.face_parent_corner.assign(num_child_faces, invalid_index);
    const auto add = [&p](ParentKind kind, Index element) {
        p.face_parent_kind.push_back(kind);
        p.face_parent.push_back(element);
    };
    for (Index f = 0; f < parent.num_faces(); ++f) {
        add(ParentKind::Face, f);
    }
    for (Index e = 0; e < parent.num_edges(); ++e) {
        if (!parent.is_boundary_edge(e)) {
            add(ParentKind::Edge, e);
        }
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (detail::has_doo_sabin_vertex_face(parent, v, boundary_rule)) {
            add(ParentKind::Vertex, v);
        }
    }
    p.vertex_parent_kind.assign(at(parent.num_corners()), ParentKind::Face);
    p.vertex_parent.resize(at(parent.num_corners()));
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index offset = parent.face_offset(f);
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            p.vertex_parent[at(offset + i)] = f;
        }
    }
    return p;
}

/// One row per parent corner (= child vertex), in corner order: the classic mask of its face, or
/// Chaikin's rule along the boundary.
void add_corner_rows(const Topology& parent, bool boundary_rule, detail::SparseRowBuilder& rows) {
    // weights[d] = (3 + 2cos(2πd/n)) / (4n) for d = 1..n-1, (n+5)/(4n) for d = 0; refilled per degree.
    std::vector<double> weights;
    Index weights_degree = 0;
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index n = parent.face_degree(f);
        const auto fv = parent.face_vertices(f);
        if (n != weights_degree) {
            const double dn = static_cast<double>(n);
            weights.resize(at(n));
            weights[0] = (dn + 5.0) / (4.0 * dn);
            for (Index d = 1; d < n; ++d) {
                weights[at(d)] =
                    (3.0 + 2.0 * std::cos(2.0 * std::numbers::pi * static_cast<double>(d) / dn)) / (4.0 * dn);
            }
            weights_degree = n;
        }
        for (Index i = 0; i < n; ++i) {
            const Index vi = fv[at(i)];
            switch (corner_rule(parent, f, i, n, boundary_rule)) {
            case CornerRule::Classic:
                for (Index k = 0; k < n; ++k) {
                    rows.add(fv[at(k)], weights[at((k - i + n) % n)]);
                }
                break;
            case CornerRule::ChaikinPrev:
                rows.add(vi, 0.75);
                rows.add(fv[at((i + n - 1) % n)], 0.25);
                break;
            case CornerRule::ChaikinNext:
                rows.add(vi, 0.75);
                rows.add(fv[at((i + 1) % n)], 0.25);
                break;
            case CornerRule::Corner:
                rows.add(vi, 1.0);
                break;
            }
            rows.end_row();
        }
    }
}

/// The non-zeros of the rows: n per corner of an n-gon away from the boundary, at most 2 on it.
Index row_nonzeros(const Topology& parent, bool boundary_rule) {
    Index nonzeros = 0;
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index n = parent.face_degree(f);
        for (Index i = 0; i < n; ++i) {
            nonzeros += corner_rule(parent, f, i, n, boundary_rule) == CornerRule::Classic ? n : 2;
        }
    }
    return nonzeros;
}

}  // namespace

Level refine_doo_sabin(const Topology& parent, const SchemeOptions& options) {
    return detail::refine_doo_sabin_step(parent, options, {});
}

Level detail::refine_doo_sabin_step(const Topology& parent, const SchemeOptions& options, const StepRun& run) {
    check_supported(parent);
    const bool boundary_rule = options.boundary != BoundaryInterpolation::None;
    auto child = detail::concurrently(run.threads, [&parent, boundary_rule, &run]() -> Topology {
        if (run.faces != nullptr) {  // Doo–Sabin has no sharpness to write
            detail::doo_sabin_faces(parent, boundary_rule, run.faces->face_offsets, run.faces->face_vertices);
            run.faces->sharpness = {};
            return Topology{};
        }
        return detail::doo_sabin_topology(parent, boundary_rule);
    });

    detail::SparseRowBuilder rows(parent.num_corners(), parent.num_vertices(),
                                  run.keeps_matrix() ? row_nonzeros(parent, boundary_rule) : 0, run);
    add_corner_rows(parent, boundary_rule, rows);
    SparseMatrix S0 = rows.finish();
    Provenance provenance = run.keeps_matrix() ? doo_sabin_provenance(parent, boundary_rule) : Provenance{};
    return Level{child.get(), std::move(S0), std::move(provenance)};
}

std::array<Index, 3> detail::doo_sabin_child_counts(const Topology& parent, const SchemeOptions& options) {
    const ChildFaceCounts counts = count_child_faces(parent, options.boundary != BoundaryInterpolation::None);
    // Every F-face side is an edge of its own (shared with the E-face of an interior parent edge);
    // each E-face adds its two ends (shared with a V-face or on the boundary); a boundary V-face
    // closes with one boundary edge of its own. A closed mesh: 2C edges.
    const Index edges = parent.num_corners() + 2 * counts.edge_faces + counts.boundary_vertex_faces;
    return {parent.num_corners(), edges, parent.num_faces() + counts.edge_faces + counts.vertex_faces};
}

}  // namespace limsurf
