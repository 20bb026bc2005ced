// Canonical facet one-rings (facet_ring.h).
#include "limsurf/volume/facet_ring.h"

#include <cstddef>
#include <span>

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Vertices of face f rotated to start at its corner k.
std::vector<Index> rotated(const Topology& t, Index f, Index k) {
    const auto verts = t.face_vertices(f);
    const auto n = verts.size();
    std::vector<Index> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = verts[(at(k) + i) % n];
    }
    return out;
}

/// The face across edge {a, b} that runs b -> a, rotated to start at a: [a, ..., b].
/// Empty when there is none (a boundary edge).
std::vector<Index> across(const Topology& t, Index a, Index b) {
    const Index e = t.find_edge(a, b);
    if (e == invalid_index) {
        return {};
    }
    for (const Index f : t.edge_faces(e)) {
        const auto verts = t.face_vertices(f);
        const auto n = verts.size();
        for (std::size_t k = 0; k < n; ++k) {
            if (verts[k] == b && verts[(k + 1) % n] == a) {
                return rotated(t, f, static_cast<Index>((k + 1) % n));
            }
        }
    }
    return {};
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

/// Position of face f in the one-ring of v, or -1.
int fan_index(const Topology& t, Index v, Index f) {
    const auto faces = t.vertex_faces(v);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        if (faces[i] == f) {
            return static_cast<int>(i);
        }
    }
    return -1;
}

/// Faces around c0 counter-clockwise starting with f, each rotated to start at c0.
std::vector<std::vector<Index>> fan_from(const Topology& t, Index c0, Index f) {
    const auto faces = t.vertex_faces(c0);
    const auto corners = t.vertex_face_corners(c0);
    const int start = fan_index(t, c0, f);
    std::vector<std::vector<Index>> fan;
    const auto n = faces.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t j = (at(start) + i) % n;
        fan.push_back(rotated(t, faces[j], corners[j]));
    }
    return fan;
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

std::optional<FacetRing> catmull_clark_facet(const Topology& t, Index f, int anchor) {
    if (t.face_degree(f) != 4) {
        return std::nullopt;
    }
    const int irregular = irregular_corner(t, f, 4, 4);
    if (irregular == -2) {
        return std::nullopt;
    }
    const Index k0 = irregular >= 0 ? irregular : anchor;
    const std::vector<Index> c = rotated(t, f, k0);
    const auto fan = fan_from(t, c[0], f);
    const auto n = fan.size();
    FacetRing ring{static_cast<int>(n), {c[0]}};
    for (const auto& face : fan) {
        ring.points.push_back(face[1]);  // e_i
        ring.points.push_back(face[2]);  // d_i
    }
    const Index d_last = fan[n - 1][2];
    const Index d_1 = fan[1][2];
    const auto g1 = across(t, d_last, c[1]);
    const auto g2 = across(t, c[1], c[2]);
    const auto g4 = across(t, c[2], c[3]);
    const auto g5 = across(t, c[3], d_1);
    if (g1.size() != 4 || g2.size() != 4 || g4.size() != 4 || g5.size() != 4) {
        return std::nullopt;
    }
    const auto g3 = across(t, g2[2], c[2]);
    if (g3.size() != 4 || g1[2] != g2[1] || g3[2] != g4[1] || g4[2] != g5[1]) {
        return std::nullopt;
    }
    for (const Index p : {g1[1], g1[2], g2[2], g3[1], g3[2], g4[2], g5[2]}) {
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
    const Index k0 = irregular >= 0 ? irregular : anchor;
    const std::vector<Index> c = rotated(t, f, k0);
    const auto fan = fan_from(t, c[0], f);
    const auto n = fan.size();
    FacetRing ring{static_cast<int>(n), {c[0]}};
    for (const auto& face : fan) {
        ring.points.push_back(face[1]);  // r_i
    }
    const auto fy = across(t, fan[n - 1][1], c[1]);  // [r_{n-1}, y, c1]
    if (fy.size() != 3) {
        return std::nullopt;
    }
    const auto fz = across(t, fy[1], c[1]);  // [y, z, c1]
    const auto fx = across(t, c[1], c[2]);   // [c1, x, c2]
    if (fz.size() != 3 || fx.size() != 3) {
        return std::nullopt;
    }
    const auto fu = across(t, fx[1], c[2]);  // [x, u, c2]
    if (fu.size() != 3) {
        return std::nullopt;
    }
    const auto fw = across(t, fu[1], c[2]);  // [u, w, c2]
    if (fw.size() != 3) {
        return std::nullopt;
    }
    for (const Index p : {fy[1], fz[1], fx[1], fu[1], fw[1]}) {
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
    const auto fan = fan_from(t, v, faces[at(start)]);
    FacetRing ring{irregular >= 0 ? static_cast<int>(t.face_degree(faces[at(irregular)])) : 4, {v}};
    for (const auto& face : fan) {
        ring.points.insert(ring.points.end(), face.begin() + 1, face.end() - 1);
    }
    return ring;
}

}  // namespace

int regular_facet_type(SchemeKind scheme) {
    return scheme == SchemeKind::Loop ? 6 : 4;
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
