// The largest face and the largest vertex fan of a topology, and the limit the layers whose
// cost grows faster than linearly with them put on both (docs/io.md "Limits").
//
// Reading, validating, converting and refining a mesh are linear in its corners whatever the
// face degrees and valences. The limit surface is not: the surface near an n-gon or a valence-n
// vertex depends on O(n) control points through dense local matrices (limit basis, SEC ring
// stencils), and an exact volume form of type n has C(2n+8, 3) coefficients. Those layers refuse
// larger elements before doing any work, naming the element.
#pragma once

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf {

/// The largest face degree and valence of a topology, and one face and vertex that have them.
struct LocalSize {
    Index max_face_degree = 0;
    Index face = invalid_index;  ///< the first face of degree max_face_degree
    Index max_valence = 0;
    Index vertex = invalid_index;  ///< the first vertex of valence max_valence
};

/// @brief The largest face and vertex fan of @p topology (O(#F + #V)).
[[nodiscard]] LocalSize local_size(const Topology& topology);

/// @brief Refuses faces of more than @p limit corners and vertices of more than @p limit edges.
/// @param what the work that needs the limit, for the message ("the limit basis")
/// @throws UnsupportedError about the face or vertex (ErrorElement), e.g. "face 0 has 100000
///   corners; the limit basis handles faces and vertices of at most 128 (docs/io.md "Limits")"
void require_local_size(const Topology& topology, Index limit, const char* what);

}  // namespace limsurf
