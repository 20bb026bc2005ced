// Discrete exterior derivatives of a polygon mesh (Subdivision Exterior Calculus, de Goes,
// Desbrun, Meyer, DeRose 2016, §2): the incidence matrices that take 0-forms (values at
// vertices) to 1-forms (integrals along edges) and 1-forms to 2-forms (integrals over faces).
//
// Conventions (docs/conventions.md, "Edges and incidence"): edge e runs from its lower to its
// higher vertex, so d0(e, ·) is −1 at edge_vertices(e)[0] and +1 at edge_vertices(e)[1]; a face's
// boundary is walked counter-clockwise, so d1(f, e) = face_edge_signs(f) at the edge's position in
// the face. Then d1·d0 = 0 exactly (each face's boundary is a closed loop).
#pragma once

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf {

/// @brief d0: #E × #V, two entries (−1, +1) per row.
[[nodiscard]] SparseMatrix exterior_derivative_0(const Topology& topology);

/// @brief d1: #F × #E, one ±1 entry per face corner (face f's row has face_degree(f) entries).
[[nodiscard]] SparseMatrix exterior_derivative_1(const Topology& topology);

}  // namespace limsurf
