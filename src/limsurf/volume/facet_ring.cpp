// Canonical facet one-rings (facet_ring.h).
#include "limsurf/volume/facet_ring.h"

#include <array>
#include <cstddef>
#include <span>

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Vertices of face f rotated to start at its corner k, into a fixed-size array (the caller
/// has checked the degree).
template <std::size_t N>
std::array<Index, N> rotated(const Topology& t, Index f, Index k) {
    const auto verts = t.face_vertices(f);
    std::array<Index, N> out{};
    for (std::size_t i = 0; i < N; ++i) {
        out[i] = verts[(at(k) + i) % N];
    }
    return out;
}

/// Interior vertex whose faces all have @p degree, with valence @p valence (any when 0).
bool is_uniform_vertex(const Topology& t, Index v, Index degree, Index valence) {
    if (t.is_boundary_vertex(v) || (valence != 0 && t.valence(v) != valence)) {
        return false;
    }
    for (const Index f : t.vertex_faces(v)) {
        if (t.face_degree(f) != degree) {
            return false;
        }
    }
    return true;
}

/// Position of face f in the one-ring of v (0 when absent: the callers pass a face of v).
std::size_t fan_index(const Topology& t, Index v, Index f) {
    const auto faces = t.vertex_faces(v);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        if (faces[i] == f) {
            return i;
        }
    }
    return 0;
}

/// Calls visit(face, corner) for the faces around c0 counter-clockwise, starting with f.
template <class Visit>
void for_fan(const Topology& t, Index c0, Index f, Visit&& visit) {
    const auto faces = t.vertex_faces(c0);
    const auto corners = t.vertex_face_corners(c0);
    const std::size_t start = fan_index(t, c0, f);
    const auto n = faces.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (start + i) % n;
        visit(faces[j], corners[j]);
    }
}

/// The irregular corner of face f (or -1 when all are regular), -2 when more than one
/// corner is irregular or an irregular corner's faces are not all of @p degree.
int irregular_corner(const Topology& t, Index f, Index degree, Index regular_valence) {
    const auto verts = t.face_vertices(f);
    int found = -1;
    for (std::size_t k = 0; k < verts.size(); ++k) {
        if (is_uniform_vertex(t, verts[k], degree, regular_valence)) {
            continue;
        }
        if (found != -1 || !is_uniform_vertex(t, verts[k], degree, 0)) {
            return -2;
        }
        found = static_cast<int>(k);
    }
    return found;
}

/// The faces (of degree D) around corner c counter-clockwise from f, each rotated to start at c;
/// false when c has not exactly @p Count faces.
template <std::size_t D, std::size_t Count>
bool regular_fan(const Topology& t, Index c, Index f, std::array<std::array<Index, D>, Count>& fan) {
    if (t.vertex_faces(c).size() != Count) {
        return false;
    }
    std::size_t i = 0;
    for_fan(t, c, f, [&](Index face, Index corner) { fan[i++] = rotated<D>(t, face, corner); });
    return true;
}

std::optional<FacetRing> catmull_clark_facet(const Topology& t, Index f, int anchor) {
    if (t.face_degree(f) != 4) {
        return std::nullopt;
    }
    const int irregular = irregular_corner(t, f, 4, 4);
    if (irregular == -2) {
        return std::nullopt;
    }
    const auto c = rotated<4>(t, f, irregular >= 0 ? irregular : anchor);
    FacetRing ring{static_cast<int>(t.valence(c[0])), {}};
    ring.points.reserve(at(2 * ring.type + 8));
    ring.points.push_back(c[0]);
    for_fan(t, c[0], f, [&](Index face, Index corner) {
        const auto q = rotated<4>(t, face, corner);  // [c0, e_i, d_i, e_i+1]
        ring.points.push_back(q[1]);
        ring.points.push_back(q[2]);
    });
    // The fans of the regular corners c1, c2, c3 from f: c1: f, [c1 c0 e d], [c1 d o1 o2], [c1 o2 o3 c2];
    // c2: f, [c2 c1 o2 o3], [c2 o3 o4 o5], [c2 o5 o6 c3]; c3: f, [c3 c2 o5 o6], [c3 o6 o7 d1], [c3 d1 e c0].
    std::array<std::array<Index, 4>, 4> f1{};
    std::array<std::array<Index, 4>, 4> f2{};
    std::array<std::array<Index, 4>, 4> f3{};
    if (!regular_fan(t, c[1], f, f1) || !regular_fan(t, c[2], f, f2) || !regular_fan(t, c[3], f, f3)) {
        return std::nullopt;
    }
    for (const Index p : {f1[2][2], f1[2][3], f1[3][2], f2[2][2], f2[2][3], f2[3][2], f3[2][2]}) {
        ring.points.push_back(p);
    }
    return ring;
}

std::optional<FacetRing> loop_facet(const Topology& t, Index f, int anchor) {
    if (t.face_degree(f) != 3) {
        return std::nullopt;
    }
    const int irregular = irregular_corner(t, f, 3, 6);
    if (irregular == -2) {
        return std::nullopt;
    }
    const auto c = rotated<3>(t, f, irregular >= 0 ? irregular : anchor);
    FacetRing ring{static_cast<int>(t.valence(c[0])), {}};
    ring.points.reserve(at(ring.type + 6));
    ring.points.push_back(c[0]);
    for_fan(t, c[0], f, [&](Index face, Index corner) { ring.points.push_back(rotated<3>(t, face, corner)[1]); });
    // The fans of c1 and c2 from f: c1: f, [c1 c0 r], [c1 r y], [c1 y z], [c1 z x], [c1 x c2];
    // c2: f, [c2 c1 x], [c2 x u], [c2 u w], [c2 w r2], [c2 r2 c0]. Outer points y, z, x, u, w.
    std::array<std::array<Index, 3>, 6> f1{};
    std::array<std::array<Index, 3>, 6> f2{};
    if (!regular_fan(t, c[1], f, f1) || !regular_fan(t, c[2], f, f2)) {
        return std::nullopt;
    }
    for (const Index p : {f1[2][2], f1[3][2], f1[4][2], f2[2][2], f2[3][2]}) {
        ring.points.push_back(p);
    }
    return ring;
}

std::optional<FacetRing> doo_sabin_facet(const Topology& t, Index v, int anchor) {
    if (t.is_boundary_vertex(v) || t.valence(v) != 4) {
        return std::nullopt;
    }
    const auto faces = t.vertex_faces(v);
    int irregular = -1;
    for (std::size_t i = 0; i < faces.size(); ++i) {
        if (t.face_degree(faces[i]) != 4) {
            if (irregular != -1) {
                return std::nullopt;
            }
            irregular = static_cast<int>(i);
        }
    }
    const int start = irregular >= 0 ? irregular : anchor;
    FacetRing ring{irregular >= 0 ? static_cast<int>(t.face_degree(faces[at(start)])) : 4, {v}};
    ring.points.reserve(at(ring.type + 5));
    for_fan(t, v, faces[at(start)], [&](Index face, Index corner) {
        // The face's vertices after v except the last (the next face's first).
        const auto verts = t.face_vertices(face);
        const auto n = verts.size();
        for (std::size_t i = 1; i + 1 < n; ++i) {
            ring.points.push_back(verts[(at(corner) + i) % n]);
        }
    });
    return ring;
}

}  // namespace

int regular_facet_type(SchemeKind scheme) {
    return scheme == SchemeKind::Loop ? 6 : 4;
}

Index num_facet_elements(const Topology& topology, SchemeKind scheme) {
    return scheme == SchemeKind::DooSabin ? topology.num_vertices() : topology.num_faces();
}

int facet_ring_size(SchemeKind scheme, int type) {
    switch (scheme) {
    case SchemeKind::CatmullClark:
        return 2 * type + 8;
    case SchemeKind::Loop:
        return type + 6;
    default:
        return type + 5;
    }
}

std::optional<FacetRing> typed_facet(const Topology& topology, SchemeKind scheme, Index element, int anchor) {
    switch (scheme) {
    case SchemeKind::CatmullClark:
        return catmull_clark_facet(topology, element, anchor);
    case SchemeKind::Loop:
        return loop_facet(topology, element, anchor);
    case SchemeKind::DooSabin:
        return doo_sabin_facet(topology, element, anchor);
    default:
        return std::nullopt;
    }
}

}  // namespace limsurf::detail
