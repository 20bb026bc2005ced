// Local complexes for the eigen-analysis (private to src/limsurf/analysis): a mesh holding one
// extraordinary vertex (or face) surrounded by regular rings, and the walks that number its
// neighbourhood (docs/eigen.md).
#pragma once

#include <functional>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// A mesh around one centre: a vertex, or (Doo–Sabin) a face whose corners are the centre.
struct LocalComplex {
    Topology topology;
    std::vector<Index> centre;          ///< the centre vertex, or the central face's corners in order
    Index centre_face = invalid_index;  ///< the central face (Doo–Sabin), else invalid_index
};

/// @brief The complex for @p scheme: `faces` sectors of quads (Catmull–Clark) or triangles (Loop)
///   around a vertex, interior (faces = valence) or on a boundary; a Doo–Sabin n-gon surrounded by
///   quads; for C2g0 a closed mesh (a subdivided tetrahedron at valence 3, a regular torus at 6)
///   whose other extraordinary vertices lie far beyond @p rings. Open complexes have rings + 1
///   rings, so that every vertex of the first `rings` rings has its whole one-ring.
[[nodiscard]] LocalComplex make_local_complex(SchemeKind scheme, int valence, bool boundary, int rings);

/// Face rings around @p seeds: ring[v] = 0 for the seeds, k + 1 for the vertices of faces at a
/// vertex of ring k not already reached, −1 beyond @p max_ring.
[[nodiscard]] std::vector<int> face_rings(const Topology& topology, const std::vector<Index>& seeds, int max_ring);

/// @brief Extends a correspondence between two meshes by walking oriented one-rings: starting
///   from `from_vertex` ↦ `to_vertex` and its neighbour `from_anchor` ↦ `to_anchor`, the one-ring
///   of every mapped vertex for which @p expand holds is mapped in order. Boundary vertices are
///   matched from their first (boundary) edge.
/// @return #V(from): the image of each vertex, or invalid_index where the walk did not reach
/// @throws NumericalError when the structures differ (valences, boundary, a vertex mapped twice)
[[nodiscard]] std::vector<Index> extend_correspondence(const Topology& from, const Topology& to, Index from_vertex,
                                                       Index to_vertex, Index from_anchor, Index to_anchor,
                                                       const std::function<bool(Index)>& expand);

}  // namespace limsurf::detail
