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
// child's Topology, or only its face list, is built on a second thread.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/detail/huge_pages.h"
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

/// Whether parent vertex @p v has a V-face.
bool has_vertex_face(const Topology& parent, Index v, bool boundary_rule) {
    return !parent.is_boundary_vertex(v) || (boundary_rule && parent.vertex_faces(v).size() >= 3);
}

/// How many child faces of each kind, and how many corners they have.
struct ChildFaceCounts {
    Index edge_faces = 0;                 ///< interior parent edges
    Index vertex_faces = 0;               ///< parent vertices with a V-face
    Index boundary_vertex_faces = 0;      ///< of which on the boundary (each closes with a boundary edge)
    std::size_t vertex_face_corners = 0;  ///< Σ valence over the V-faces
};

ChildFaceCounts count_child_faces(const Topology& parent, bool boundary_rule) {
    ChildFaceCounts counts;
    for (Index e = 0; e < parent.num_edges(); ++e) {
        counts.edge_faces += parent.is_boundary_edge(e) ? 0 : 1;
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (has_vertex_face(parent, v, boundary_rule)) {
            ++counts.vertex_faces;
            counts.boundary_vertex_faces += parent.is_boundary_vertex(v) ? 1 : 0;
            counts.vertex_face_corners += parent.vertex_faces(v).size();
        }
    }
    return counts;
}

/// The child's F-, E- and V-faces, in that order, into @p offsets (#F_child + 1) and @p vertices;
/// with @p provenance, each face's parent element there.
void write_child_faces(const Topology& parent, bool boundary_rule, std::vector<Index>& offsets,
                       std::vector<Index>& vertices, Provenance* provenance) {
    const ChildFaceCounts counts = count_child_faces(parent, boundary_rule);
    const Index num_faces = parent.num_faces();
    const auto num_child_faces = at(num_faces + counts.edge_faces + counts.vertex_faces);
    detail::reserve_huge(offsets, num_child_faces + 1);
    detail::reserve_huge(vertices, at(parent.num_corners()) + 4 * at(counts.edge_faces) + counts.vertex_face_corners);
    offsets.assign(1, 0);
    vertices.clear();
    const auto add_parent = [provenance](ParentKind kind, Index element) {
        if (provenance != nullptr) {
            provenance->face_parent_kind.push_back(kind);
            provenance->face_parent.push_back(element);
        }
    };
    if (provenance != nullptr) {
        provenance->face_parent_kind.reserve(num_child_faces);
        provenance->face_parent.reserve(num_child_faces);
        provenance->face_parent_corner.assign(num_child_faces, invalid_index);
    }
    // F-faces: the children of the corners of f, in corner order.
    for (Index f = 0; f < num_faces; ++f) {
        const Index offset = parent.face_offset(f);
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            vertices.push_back(offset + i);
        }
        offsets.push_back(static_cast<Index>(vertices.size()));
        add_parent(ParentKind::Face, f);
    }
    // E-faces. face_edges(g)[k] runs from g's corner k to corner k+1, so the corner of face g at the
    // tail of e is the k with face_edges(g)[k] == e.
    const auto tail_corner = [&parent](Index g, Index e) {
        const auto edges = parent.face_edges(g);
        const auto k = std::find(edges.begin(), edges.end(), e) - edges.begin();
        return parent.face_offset(g) + static_cast<Index>(k);
    };
    const auto next_corner = [&parent](Index g, Index corner) {
        const Index offset = parent.face_offset(g);
        return offset + (corner - offset + 1) % parent.face_degree(g);
    };
    for (Index e = 0; e < parent.num_edges(); ++e) {
        const auto ef = parent.edge_faces(e);
        if (ef.size() != 2) {
            continue;
        }
        // edge_faces lists first the face traversing lower -> higher: f runs a -> b, g runs b -> a.
        const Index fa = tail_corner(ef[0], e);
        const Index gb = tail_corner(ef[1], e);
        vertices.insert(vertices.end(), {next_corner(ef[0], fa), fa, next_corner(ef[1], gb), gb});
        offsets.push_back(static_cast<Index>(vertices.size()));
        add_parent(ParentKind::Edge, e);
    }
    // V-faces: the children of v's corners, counter-clockwise about v.
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (!has_vertex_face(parent, v, boundary_rule)) {
            continue;
        }
        const auto vf = parent.vertex_faces(v);
        const auto vc = parent.vertex_face_corners(v);
        for (std::size_t i = 0; i < vf.size(); ++i) {
            vertices.push_back(parent.face_offset(vf[i]) + vc[i]);
        }
        offsets.push_back(static_cast<Index>(vertices.size()));
        add_parent(ParentKind::Vertex, v);
    }
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

Provenance provenance_of_vertices(const Topology& parent, Provenance faces) {
    faces.vertex_parent_kind.assign(at(parent.num_corners()), ParentKind::Face);
    faces.vertex_parent.resize(at(parent.num_corners()));
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index offset = parent.face_offset(f);
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            faces.vertex_parent[at(offset + i)] = f;
        }
    }
    return faces;
}

}  // namespace

Level refine_doo_sabin(const Topology& parent, const SchemeOptions& options) {
    return detail::refine_doo_sabin_step(parent, options, {});
}

Level detail::refine_doo_sabin_step(const Topology& parent, const SchemeOptions& options, const StepRun& run) {
    check_supported(parent);
    const bool boundary_rule = options.boundary != BoundaryInterpolation::None;
    const bool keep_provenance = run.carried == nullptr;
    Provenance face_provenance;
    auto child = detail::concurrently(run.threads, [&]() -> Topology {
        Provenance* provenance = keep_provenance ? &face_provenance : nullptr;
        if (run.faces != nullptr) {  // Doo–Sabin has no sharpness to write
            write_child_faces(parent, boundary_rule, run.faces->face_offsets, run.faces->face_vertices, provenance);
            run.faces->sharpness = {};
            return Topology{};
        }
        std::vector<Index> offsets;
        std::vector<Index> vertices;
        write_child_faces(parent, boundary_rule, offsets, vertices, provenance);
        return detail::refined_topology(parent.num_corners(), offsets, vertices, {});
    });

    detail::SparseRowBuilder rows(parent.num_corners(), parent.num_vertices(),
                                  run.carried == nullptr ? row_nonzeros(parent, boundary_rule) : 0, run.carried);
    add_corner_rows(parent, boundary_rule, rows);
    SparseMatrix S0 = rows.finish();
    Topology topology = child.get();  // face_provenance is complete once the child is
    Provenance provenance = keep_provenance ? provenance_of_vertices(parent, std::move(face_provenance)) : Provenance{};
    return Level{std::move(topology), std::move(S0), std::move(provenance)};
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
