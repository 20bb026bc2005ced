// The C2g0 rules as stencil rows (private; scheme/c2g0.h holds the weights): shared by the
// whole-mesh refinement (refine/c2g0.cpp) and the local subdivision of the limit evaluator
// (limit/c2g0_limit.cpp), so that both apply one definition of the rules.
//
// Stencils are read off the one-rings, which are counter-clockwise (docs/conventions.md): around
// a valence-6 vertex p with neighbour q at ring index k, the neighbours at k ± 1 are the edge's
// opposite vertices, k ± 2 its "side" vertices and k + 3 its "far" vertex. Near a valence-3
// vertex two of those may coincide: entries are not merged (the row builders add them up, as the
// rows of matrix (2.2) do).
#pragma once

#include <utility>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf::detail {

/// (vertex, weight) pairs of one refined point; a vertex may appear more than once.
using C2g0Row = std::vector<std::pair<Index, double>>;

/// @brief The vertex rule of @p v (valence 6: the box spline's even mask; valence 3: Fig. 3's z, s, t, u).
/// @pre v and the vertices its rule reads have complete one-rings of valence 3 or 6, with the
///   neighbours of a valence-3 vertex of valence 6 (require_c2g0_topology on whole meshes)
void c2g0_vertex_row(const Topology& t, Index v, C2g0Row& row);

/// @brief The edge rule of edge (p, q) (regular: the odd mask over both one-rings; at a valence-3
///   end: Fig. 3's a, b, c, d, e). @pre as c2g0_vertex_row, for both ends
void c2g0_edge_row(const Topology& t, Index p, Index q, C2g0Row& row);

}  // namespace limsurf::detail
