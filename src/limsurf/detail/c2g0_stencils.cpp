#include "limsurf/detail/c2g0_stencils.h"

#include <algorithm>
#include <array>
#include <cstddef>

#include "limsurf/detail/refine_face_split.h"
#include "limsurf/scheme/c2g0.h"

namespace limsurf::detail {
namespace {

/// Neighbours of v, counter-clockwise (interior vertex: one per one-ring edge); valence ≤ 6.
std::size_t ring_of(const Topology& t, Index v, std::array<Index, 6>& ring) {
    const auto edges = t.vertex_edges(v);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        ring[i] = t.other_vertex(edges[i], v);
    }
    return edges.size();
}

/// Index of @p w in a ring of @p n vertices (n when absent: not on a valid stencil).
std::size_t index_in(const std::array<Index, 6>& ring, std::size_t n, Index w) {
    return static_cast<std::size_t>(std::find(ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(n), w) -
                                    ring.begin());
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
        ring_of(t, s.r[i], around);  // valence 6
        s.t[i] = around[(index_in(around, 6, c) + 3) % 6];
        s.u[i] = across(t, s.r[i], s.r[(i + 1) % 3], c);
    }
    return s;
}

void add(C2g0Row& row, Index v, const Rational& w) {
    row.emplace_back(v, w.value());
}

}  // namespace

void c2g0_vertex_row(const Topology& t, Index v, C2g0Row& row) {
    row.clear();
    if (t.valence(v) == 6) {
        const C2g0RegularRules regular;
        std::array<Index, 6> ring{};
        ring_of(t, v, ring);
        add(row, v, regular.vertex_self);
        for (const Index w : ring) {
            add(row, w, regular.vertex_neighbour);
        }
        return;
    }
    const C2g0Valence3Rules ev;
    const Valence3Stencil s = valence3_stencil(t, v);
    add(row, v, ev.z);
    for (std::size_t i = 0; i < 3; ++i) {
        add(row, s.r[i], ev.s);
        add(row, s.t[i], ev.t);
        add(row, s.u[i], ev.u);
    }
}

void c2g0_edge_row(const Topology& t, Index p, Index q, C2g0Row& row) {
    row.clear();
    if (t.valence(p) == 3 || t.valence(q) == 3) {
        const C2g0Valence3Rules ev;
        const Index c = t.valence(p) == 3 ? p : q;
        const Index other = c == p ? q : p;
        const Valence3Stencil s = valence3_stencil(t, c);
        const auto i = static_cast<std::size_t>(std::find(s.r.begin(), s.r.end(), other) - s.r.begin());
        add(row, c, ev.a);
        add(row, s.r[i], ev.b);
        add(row, s.r[(i + 1) % 3], ev.c);
        add(row, s.r[(i + 2) % 3], ev.c);
        add(row, s.t[i], ev.e);
        add(row, s.u[i], ev.d);
        add(row, s.u[(i + 2) % 3], ev.d);
        return;
    }
    const C2g0RegularRules regular;
    const Index e = t.find_edge(p, q);
    add(row, p, regular.edge_end);
    add(row, q, regular.edge_end);
    for (const Index f : t.edge_faces(e)) {
        add(row, opposite_vertex(t, f, e), regular.edge_opposite);
    }
    for (const auto& [end, other] : {std::pair{p, q}, std::pair{q, p}}) {
        std::array<Index, 6> ring{};
        ring_of(t, end, ring);
        const std::size_t k = index_in(ring, 6, other);
        add(row, ring[(k + 2) % 6], regular.edge_side);
        add(row, ring[(k + 4) % 6], regular.edge_side);
        add(row, ring[(k + 3) % 6], regular.edge_far);
    }
}

}  // namespace limsurf::detail
