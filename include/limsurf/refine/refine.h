// One uniform refinement step for each scheme: child topology + S0 +
// provenance (level.h). The per-scheme rules follow OpenSubdiv's Sdc for
// Catmull–Clark, Loop and bilinear (docs/conventions.md "Refinement").
#pragma once

#include "limsurf/mesh/topology.h"
#include "limsurf/refine/level.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// @brief Catmull–Clark: every face of degree n becomes n quads; triangles by
///   `options.triangles`; boundaries by `options.boundary`; creases, corners and
///   semi-sharp features by the Topology's sharpness and `options.creasing`
///   (OpenSubdiv's rules, including fractional-sharpness blending).
/// @param[in] weights tuned vertex-rule weights at smooth interior vertices
///   (tuned_weights.h); the default reproduces Catmull–Clark exactly.
/// @see iga-with-catmull-clark §3, iga-tuned-catmull-clark-weights Fig. 1
[[nodiscard]] Level refine_catmull_clark(const Topology& parent, const SchemeOptions& options = {},
                                         const TunedWeights& weights = {});

/// @brief Loop: every triangle becomes 4; the same boundary and crease features.
/// @throws UnsupportedError naming the first face that is not a triangle
[[nodiscard]] Level refine_loop(const Topology& parent, const SchemeOptions& options = {});

/// @brief Bilinear: the Catmull–Clark split with linear rules (face point =
///   centroid, edge point = midpoint, vertex point = vertex). Sharpness is carried.
[[nodiscard]] Level refine_bilinear(const Topology& parent);

/// @brief Linear: the Loop split (triangles only) with midpoints.
/// @throws UnsupportedError naming the first face that is not a triangle
[[nodiscard]] Level refine_linear(const Topology& parent);

/// @brief Doo–Sabin with the classic weights (n+5)/(4n) and (3 + 2cos(2πk/n))/(4n);
///   one child vertex per parent face corner (child vertex c = parent corner c).
///   Boundary: child boundary loops are Chaikin's corner cutting of the parent's
///   (quadratic B-spline), one-face corners interpolated; BoundaryInterpolation::None
///   reproduces CGAL (no boundary faces). See docs/doo_sabin.md.
/// @throws UnsupportedError when the topology has creases, corners or holes (no
///   Doo–Sabin crease rules yet), naming the first tagged element, or an interior vertex in
///   fewer than 3 faces (its vertex face would not be a polygon)
[[nodiscard]] Level refine_doo_sabin(const Topology& parent, const SchemeOptions& options = {});

/// @brief C2g0 (c2g0-sphere-scheme-biomembranes §1.2, §2): the triangle split of Loop with the
///   rules of the three-directional box spline (each direction thrice: C⁴, degree 7) and the
///   valence-3 rules of Fig. 3 (scheme/c2g0.h, exact rationals). Vertex rules read the 1-ring (the
///   2-ring at a valence-3 vertex), edge rules the 1-rings of both ends.
/// @throws UnsupportedError as require_c2g0_topology (boundaries, non-triangles, valences other than
///   3 and 6, tags, adjacent valence-3 vertices), naming the element
[[nodiscard]] Level refine_c2g0(const Topology& parent);

/// @brief Dispatches on @p kind (tuned weights apply to Catmull–Clark only).
[[nodiscard]] Level refine(const Topology& parent, SchemeKind kind, const SchemeOptions& options = {},
                           const TunedWeights& weights = {});

}  // namespace limsurf
