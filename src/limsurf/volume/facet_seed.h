// A facet of every type inside a closed mesh, with its children one refinement
// step later: the raw material of the volume-form generator (form_generator.h).
// Private to src/limsurf/volume.
#pragma once

#include <array>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/refine/level.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/volume/facet_ring.h"

namespace limsurf::detail {

/// A facet f of type τ in a closed mesh and its four children in the refined mesh.
struct FacetSeed {
    SchemeKind scheme = SchemeKind::CatmullClark;
    Topology parent;                  ///< the mesh holding f
    Level child;                      ///< one refinement step of parent
    Index element = invalid_index;    ///< f: a face (Catmull–Clark, Loop) or a vertex (Doo–Sabin) of parent
    FacetRing ring;                   ///< f's control points in parent
    std::vector<FacetRing> children;  ///< the four children: regular ones first; an irregular one last
};

/// @brief The seed of facet type @p type (3 ≤ type; the regular type gives a regular facet
///   whose children are regular).
/// @details Catmull–Clark: a type-gonal prism refined three times (the cap's face point has
///   valence type); Loop: a type-gonal bipyramid refined three times (apex valence type);
///   Doo–Sabin: the prism refined bilinearly twice, then twice by Doo–Sabin (the vertex face of
///   the cap centre is a type-gon).
/// @throws UnsupportedError when type < 3 or the scheme has no volume forms
[[nodiscard]] FacetSeed make_facet_seed(SchemeKind scheme, int type);

/// The same facet numbered from another anchor (regular facets: a rotation of the numbering).
[[nodiscard]] FacetRing rotated_ring(const FacetSeed& seed, int anchor);

/// The same facet numbered in the mesh with every face reversed (a mirror of the numbering).
[[nodiscard]] FacetRing mirrored_ring(const FacetSeed& seed);

/// The topology with every face reversed.
[[nodiscard]] Topology reversed(const Topology& topology);

/// The parent face and corner that child vertex @p child_vertex of a Doo–Sabin step comes from.
struct ParentCorner {
    Index face = invalid_index;
    Index corner = 0;
};
[[nodiscard]] ParentCorner doo_sabin_parent_corner(const Topology& parent, Index child_vertex);

/// The child elements of @p element one refinement step later: the faces split from face
/// @p element (Catmull–Clark: child k at corner k; Loop: the three corner triangles, then the
/// middle one) or, for Doo–Sabin, the child vertices at the corners of vertex @p element (in the
/// order of its faces). Follows the child order of level.h.
[[nodiscard]] std::vector<Index> child_elements(const Topology& parent, SchemeKind scheme, Index element);

}  // namespace limsurf::detail
