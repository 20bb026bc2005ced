// Differential geometry of a parametric surface at one point, from the position
// and its first and second derivatives (for instance LimitWeights::apply, or the
// patch bases of patch_basis.h applied to control points).
//
// Conventions (faces counter-clockwise seen from outside, docs/conventions.md "Orientation"):
//   - The unit normal is n = (∂u × ∂v) / |∂u × ∂v|: outward for a closed surface whose
//     faces are counter-clockwise seen from outside.
//   - The first fundamental form is (E, F, G) = (∂u·∂u, ∂u·∂v, ∂v·∂v); the second is
//     (L, M, N) = (∂uu·n, ∂uv·n, ∂vv·n), the usual coefficients with respect to n.
//   - Curvatures are positive where the surface bends away from its normal: the unit
//     sphere with the outward normal has k1 = k2 = 1, H = 1, K = 1. They are the
//     eigenvalues of the shape operator W = -I⁻¹ II (so k = -II(x, x) / I(x, x) along a
//     principal direction x), H = (k1 + k2)/2 = -(EN - 2FM + GL) / (2(EG - F²)) and
//     K = k1 k2 = (LN - M²) / (EG - F²).
//   - Reversing the orientation (swapping u and v) flips n, L, M, N and H, keeps K and
//     turns (k1, k2) into (-k2, -k1).
#pragma once

#include <Eigen/Core>

namespace limsurf {

/// First and second fundamental forms, curvatures and principal directions at a point.
struct SurfaceFrame {
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit normal (∂u × ∂v)/|∂u × ∂v|
    double E = 0.0;                                    ///< ∂u·∂u
    double F = 0.0;                                    ///< ∂u·∂v
    double G = 0.0;                                    ///< ∂v·∂v
    double L = 0.0;                                    ///< ∂uu·n
    double M = 0.0;                                    ///< ∂uv·n
    double N = 0.0;                                    ///< ∂vv·n
    double gaussian_curvature = 0.0;                   ///< K = k1 k2
    double mean_curvature = 0.0;                       ///< H = (k1 + k2)/2, 1 on the unit sphere
    double k1 = 0.0;                                   ///< larger principal curvature
    double k2 = 0.0;                                   ///< smaller principal curvature, k2 <= k1
    Eigen::Vector3d d1 = Eigen::Vector3d::Zero();      ///< unit principal direction of k1 (tangent)
    Eigen::Vector3d d2 = Eigen::Vector3d::Zero();      ///< unit principal direction of k2, d1 × d2 = n
};

/// @brief The surface frame at a point from its derivatives.
/// @param derivatives 6 × 3, rows position, ∂u, ∂v, ∂uu, ∂uv, ∂vv (the row order of
///   LimitWeights and patch_basis.h); the position row is not used.
/// @details d1 and d2 are orthonormal tangent vectors with d1 × d2 = n; at an umbilic
///   (k1 = k2) they are an arbitrary such pair. Each principal direction is defined up
///   to sign.
///   The computation runs on the derivatives scaled to order one by a power of two, so the
///   results do not depend on the surface's size (only E, F, G, L, M, N may overflow for
///   derivatives beyond 1e154).
/// @throws NumericalError when an entry is not finite, when the tangents are
///   (nearly) parallel: |∂u × ∂v| <= 1e-14 |∂u| |∂v| (this includes a zero tangent), or when a
///   curvature overflows (a surface smaller than about 1e-300).
/// @see c2g0-sphere-scheme-biomembranes §3.1 (3.4), with the opposite sign convention:
///   there n points inward so that H = 1 on the unit sphere; here n points outward and
///   H = 1 all the same.
[[nodiscard]] SurfaceFrame surface_frame(const Eigen::Matrix<double, 6, 3>& derivatives);

/// @brief False where surface_frame() would find the tangents (nearly) parallel or not finite:
///   the test it applies first, for callers that report such points instead of failing.
[[nodiscard]] bool has_tangent_plane(const Eigen::Matrix<double, 6, 3>& derivatives);

}  // namespace limsurf
