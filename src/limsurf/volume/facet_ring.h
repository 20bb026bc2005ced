// Facets of the volume formula and their control points in canonical order
// (private to src/limsurf/volume; volume-trilinear-forms §"Applications").
//
// A facet is the piece of limit surface whose enclosed-volume contribution one
// trilinear form computes from the facet's one-ring:
//   Catmull–Clark: a quad face whose corners are regular (valence 4, quads
//     around) except at most one, whose faces are all quads; m = 2τ + 8 points;
//   Loop: a triangle whose corners have valence 6 except at most one; m = τ + 6;
//   Doo–Sabin: a vertex of valence 4 with at most one non-quad face among its
//     four faces (the facet is the quad of its faces' centroids); m = τ + 5.
// τ (the facet's type) is the valence of the irregular corner (Catmull–Clark,
// Loop) or the degree of the irregular face (Doo–Sabin); the regular type is 4
// (Catmull–Clark, Doo–Sabin) or 6 (Loop).
//
// Canonical order (docs/volume.md draws the three layouts):
//   Catmull–Clark: c0 (the irregular corner), then around c0 counter-clockwise
//     from c1 the edge and diagonal neighbours e0 = c1, d0 = c2, e1 = c3, d1, ...,
//     e_{τ-1}, d_{τ-1}, then seven outer points walking round c1, c2, c3;
//   Loop: c0, its neighbours counter-clockwise from r0 = c1, r1 = c2, then five
//     outer points round c1 and c2;
//   Doo–Sabin: the vertex v, then for each of its four faces counter-clockwise,
//     starting with the irregular one, the face's vertices after v except the last.
// The order is found by walking faces (never by sets of vertex indices), so a
// one-ring that wraps round a small torus and meets itself is still numbered right.
#pragma once

#include <optional>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// A facet with its type and control points in canonical order.
struct FacetRing {
    int type = 0;               ///< τ: 4 (Catmull–Clark, Doo–Sabin) or 6 (Loop) when regular
    std::vector<Index> points;  ///< facet_ring_size(scheme, type) vertices of the topology
};

/// The regular type: 4 for Catmull–Clark and Doo–Sabin, 6 for Loop.
[[nodiscard]] int regular_facet_type(SchemeKind scheme);

/// m(τ): 2τ + 8 (Catmull–Clark), τ + 6 (Loop), τ + 5 (Doo–Sabin).
[[nodiscard]] int facet_ring_size(SchemeKind scheme, int type);

/// Number of elements that can be facets: faces (Catmull–Clark, Loop) or vertices (Doo–Sabin).
[[nodiscard]] Index num_facet_elements(const Topology& topology, SchemeKind scheme);

/// @brief The facet of @p element — a face for Catmull–Clark and Loop, a vertex for
///   Doo–Sabin — or nothing when the element is not a facet yet (more than one irregular
///   corner, a non-quad face, a boundary: it must be subdivided first).
/// @param anchor for a regular facet, the corner (face) the numbering starts at:
///   0..3 (Catmull–Clark, Doo–Sabin) or 0..2 (Loop); irregular facets always start
///   at their irregular corner (face)
/// @pre @p scheme is CatmullClark, Loop or DooSabin
[[nodiscard]] std::optional<FacetRing> typed_facet(const Topology& topology, SchemeKind scheme, Index element,
                                                   int anchor = 0);

}  // namespace limsurf::detail
