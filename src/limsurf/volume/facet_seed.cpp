// Seeds for the volume-form generator (facet_seed.h).
#include "limsurf/volume/facet_seed.h"

#include <algorithm>
#include <string>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// A closed n-gonal prism: two n-gon caps and n side quads.
Topology prism(Index n) {
    std::vector<std::vector<Index>> faces;
    std::vector<Index> bottom;
    std::vector<Index> top;
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        faces.push_back({i, j, n + j, n + i});
        bottom.insert(bottom.begin(), i);
        top.push_back(n + i);
    }
    faces.push_back(bottom);
    faces.push_back(top);
    return Topology::from_polygons(2 * n, faces);
}

/// A closed n-gonal bipyramid of triangles: apexes of valence n, equator of valence 4.
Topology bipyramid(Index n) {
    std::vector<std::vector<Index>> faces;
    for (Index i = 0; i < n; ++i) {
        const Index j = (i + 1) % n;
        faces.push_back({i, j, n});
        faces.push_back({j, i, n + 1});
    }
    return Topology::from_polygons(n + 2, faces);
}

Topology refined(Topology t, SchemeKind kind, int times) {
    for (int i = 0; i < times; ++i) {
        t = refine(t, kind).topology;
    }
    return t;
}

/// The seed mesh and the scheme step that refines it.
Topology seed_mesh(SchemeKind scheme, int type) {
    switch (scheme) {
    case SchemeKind::CatmullClark:
        return refined(prism(type), SchemeKind::CatmullClark, 3);
    case SchemeKind::Loop:
        return refined(bipyramid(type), SchemeKind::Loop, 3);
    default:
        return refined(refined(prism(type), SchemeKind::Bilinear, 2), SchemeKind::DooSabin, 2);
    }
}

}  // namespace

Topology reversed(const Topology& topology) {
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const auto verts = topology.face_vertices(f);
        faces.emplace_back(verts.rbegin(), verts.rend());
    }
    return Topology::from_polygons(topology.num_vertices(), faces);
}

ParentCorner doo_sabin_parent_corner(const Topology& parent, Index child_vertex) {
    const auto offsets = parent.face_offsets();
    const auto it = std::upper_bound(offsets.begin(), offsets.end(), child_vertex);
    const auto face = static_cast<Index>(it - offsets.begin()) - 1;
    return {face, child_vertex - offsets[at(face)]};
}

std::vector<Index> child_elements(const Topology& parent, SchemeKind scheme, Index element) {
    std::vector<Index> out;
    switch (scheme) {
    case SchemeKind::CatmullClark:
        for (Index k = 0; k < parent.face_degree(element); ++k) {
            out.push_back(parent.face_offset(element) + k);
        }
        break;
    case SchemeKind::Loop:
        for (Index k = 0; k < 4; ++k) {
            out.push_back(4 * element + k);
        }
        break;
    default: {
        const auto faces = parent.vertex_faces(element);
        const auto corners = parent.vertex_face_corners(element);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            out.push_back(parent.face_offset(faces[i]) + corners[i]);
        }
    }
    }
    return out;
}

FacetSeed make_facet_seed(SchemeKind scheme, int type) {
    LIMSURF_CHECK(scheme == SchemeKind::CatmullClark || scheme == SchemeKind::Loop || scheme == SchemeKind::DooSabin,
                  UnsupportedError, "volume forms exist for Catmull–Clark, Loop and Doo–Sabin only");
    LIMSURF_CHECK(type >= 3, UnsupportedError, "facet type ", type, " (valences and face degrees start at 3)");
    const int regular = regular_facet_type(scheme);
    FacetSeed seed;
    seed.scheme = scheme;
    seed.parent = seed_mesh(scheme, type);
    seed.child = refine(seed.parent, scheme);
    for (Index e = 0; e < num_facet_elements(seed.parent, scheme); ++e) {
        const auto ring = typed_facet(seed.parent, scheme, e);
        if (!ring || ring->type != type) {
            continue;
        }
        std::vector<FacetRing> regular_children;
        std::vector<FacetRing> irregular_children;
        for (const Index c : child_elements(seed.parent, scheme, e)) {
            auto child = typed_facet(seed.child.topology, scheme, c);
            if (!child) {
                break;
            }
            (child->type == regular ? regular_children : irregular_children).push_back(std::move(*child));
        }
        const bool complete = regular_children.size() + irregular_children.size() == 4;
        const bool expected = type == regular ? irregular_children.empty()
                                              : irregular_children.size() == 1 && irregular_children[0].type == type;
        if (!complete || !expected) {
            continue;
        }
        seed.element = e;
        seed.ring = *ring;
        seed.children = std::move(regular_children);
        seed.children.insert(seed.children.end(), irregular_children.begin(), irregular_children.end());
        return seed;
    }
    throw UnsupportedError("no facet of type " + std::to_string(type) + " found in the " + to_string(scheme) +
                           " seed mesh (internal error)");
}

FacetRing rotated_ring(const FacetSeed& seed, int anchor) {
    return *typed_facet(seed.parent, seed.scheme, seed.element, anchor);
}

FacetRing mirrored_ring(const FacetSeed& seed) {
    return *typed_facet(reversed(seed.parent), seed.scheme, seed.element, 0);
}

}  // namespace limsurf::detail
