// C2g0 refinement (c2g0-sphere-scheme-biomembranes §1.2, §2; scheme/c2g0.h): the triangle split
// of Loop with the rules of the three-directional box spline (each direction thrice) and the
// valence-3 rules of Fig. 3. Stencils are read off the one-rings, which are counter-clockwise
// (docs/conventions.md): around a valence-6 vertex p with neighbour q at ring index k, the
// neighbours at k ± 1 are the edge's opposite vertices, k ± 2 its "side" vertices and k + 3 its
// "far" vertex. Near a valence-3 vertex two of those coincide; the row builder merges them, as the
// rows of matrix (2.2) do.
#include "limsurf/scheme/c2g0.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <utility>

#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Neighbours of v, counter-clockwise (interior vertex: one per one-ring edge).
void ring_of(const Topology& t, Index v, std::array<Index, 6>& ring) {
    const auto edges = t.vertex_edges(v);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        ring[i] = t.other_vertex(edges[i], v);
    }
}

/// Index of @p w in the ring of a vertex of valence @p n.
std::size_t index_in(const std::array<Index, 6>& ring, std::size_t n, Index w) {
    for (std::size_t i = 0; i < n; ++i) {
        if (ring[i] == w) {
            return i;
        }
    }
    return n;  // unreachable on a valid topology: w is a neighbour
}

/// The corner of triangle f that is not an end of edge e.
Index opposite_vertex(const Topology& t, Index f, Index e) {
    const auto edges = t.face_edges(f);
    const auto verts = t.face_vertices(f);
    for (std::size_t k = 0; k < 3; ++k) {
        if (edges[k] == e) {
            return verts[(k + 2) % 3];
        }
    }
    return invalid_index;
}

/// The third corner of the triangle across edge (a, b) from c.
Index across(const Topology& t, Index a, Index b, Index c) {
    const Index e = t.find_edge(a, b);
    for (const Index f : t.edge_faces(e)) {
        const Index o = opposite_vertex(t, f, e);
        if (o != c) {
            return o;
        }
    }
    return invalid_index;
}

/// The valence-3 vertex c's own stencil vertices: ring r, beyond tᵢ, across uᵢ (scheme/c2g0.h).
struct Valence3Stencil {
    std::array<Index, 3> r{};
    std::array<Index, 3> t{};
    std::array<Index, 3> u{};
};

Valence3Stencil valence3_stencil(const Topology& t, Index c) {
    Valence3Stencil s;
    std::array<Index, 6> ring{};
    ring_of(t, c, ring);
    for (std::size_t i = 0; i < 3; ++i) {
        s.r[i] = ring[i];
    }
    for (std::size_t i = 0; i < 3; ++i) {
        std::array<Index, 6> around{};
        ring_of(t, s.r[i], around);  // valence 6: require_c2g0_topology
        s.t[i] = around[(index_in(around, 6, c) + 3) % 6];
        s.u[i] = across(t, s.r[i], s.r[(i + 1) % 3], c);
    }
    return s;
}

void add(detail::SparseRowBuilder& rows, Index v, const Rational& w) {
    rows.add(v, w.value());
}

}  // namespace

Level refine_c2g0(const Topology& parent) {
    require_c2g0_topology(parent);
    const C2g0RegularRules regular;
    const C2g0Valence3Rules ev;
    const Index V = parent.num_vertices();
    const Index E = parent.num_edges();
    detail::SparseRowBuilder rows(V + E, V, 7 * V + 10 * E);

    // Vertex points.
    std::array<Index, 6> ring{};
    for (Index v = 0; v < V; ++v) {
        if (parent.valence(v) == 6) {
            ring_of(parent, v, ring);
            add(rows, v, regular.vertex_self);
            for (const Index w : ring) {
                add(rows, w, regular.vertex_neighbour);
            }
        } else {
            const Valence3Stencil s = valence3_stencil(parent, v);
            add(rows, v, ev.z);
            for (std::size_t i = 0; i < 3; ++i) {
                add(rows, s.r[i], ev.s);
                add(rows, s.t[i], ev.t);
                add(rows, s.u[i], ev.u);
            }
        }
        rows.end_row();
    }

    // Edge points.
    for (Index e = 0; e < E; ++e) {
        const auto ends = parent.edge_vertices(e);
        const Index p = ends[0];
        const Index q = ends[1];
        if (parent.valence(p) == 3 || parent.valence(q) == 3) {
            const Index c = parent.valence(p) == 3 ? p : q;
            const Index other = c == p ? q : p;
            const Valence3Stencil s = valence3_stencil(parent, c);
            const std::size_t i = at(static_cast<Index>(std::find(s.r.begin(), s.r.end(), other) - s.r.begin()));
            add(rows, c, ev.a);
            add(rows, s.r[i], ev.b);
            add(rows, s.r[(i + 1) % 3], ev.c);
            add(rows, s.r[(i + 2) % 3], ev.c);
            add(rows, s.t[i], ev.e);
            add(rows, s.u[i], ev.d);
            add(rows, s.u[(i + 2) % 3], ev.d);
            rows.end_row();
            continue;
        }
        add(rows, p, regular.edge_end);
        add(rows, q, regular.edge_end);
        for (const Index f : parent.edge_faces(e)) {
            add(rows, opposite_vertex(parent, f, e), regular.edge_opposite);
        }
        for (const auto& [end, other] : {std::pair{p, q}, std::pair{q, p}}) {
            ring_of(parent, end, ring);
            const std::size_t k = index_in(ring, 6, other);
            add(rows, ring[(k + 2) % 6], regular.edge_side);
            add(rows, ring[(k + 4) % 6], regular.edge_side);
            add(rows, ring[(k + 3) % 6], regular.edge_far);
        }
        rows.end_row();
    }

    return detail::make_level(V + E, detail::tri_split_faces(parent), SharpnessTags{}, rows.finish(),
                              detail::tri_split_provenance(parent));
}

}  // namespace limsurf
