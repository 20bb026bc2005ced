// Line quadrature along the limit boundary (private to src/limsurf/fem): Gauss points on the sides of
// the ptex faces that lie on boundary edges of the control mesh, for edge integrals such as the
// Nitsche terms of the clamped plate (docs/fem.md "Plates").
#pragma once

#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf::detail {

/// A point on a boundary side of a ptex face.
struct BoundarySample {
    SurfacePoint point;
    double weight = 0.0;  ///< parameter weight along the side (the weights of one side sum to 1)
    bool along_u = true;  ///< the side runs along u (v = 0 or 1); otherwise along v (u = 0 or 1)
    double inward = 1.0;  ///< +1 when the other parameter grows into the face (side v = 0 or u = 0), else −1
};

/// @brief Gauss points on every ptex side that lies on a boundary edge of the control mesh
///   (quad domains: Catmull–Clark). A quad face is one ptex face whose side k joins corners k and
///   k + 1 (k = 0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0); a face of another degree splits boundary
///   edge k between sub-face k (side v = 0, from corner k to the edge point) and sub-face k + 1 (side
///   u = 0, from the edge point to corner k + 1); limit_basis.h "Parameterisation".
/// @details Each side gets ceil((rule.degree + 1) / 2) Gauss–Legendre points per segment; with
///   rule.subdivide_near_extraordinary = k > 0 the side is split dyadically towards both of its ends,
///   k levels deep (as the sampler tiles faces towards irregular corners: the boundary curve is
///   polynomial on each ring of Stam's tiles only). Faces without a limit surface and holes are skipped.
/// @throws UnsupportedError for a triangle domain; InputError for a rule the sampler would refuse
[[nodiscard]] std::vector<BoundarySample> boundary_samples(const LimitBasis& basis, const SamplerOptions& rule);

}  // namespace limsurf::detail
