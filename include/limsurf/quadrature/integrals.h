// Integrals over the limit surface by quadrature on a LimitSampler: area, the
// enclosed volume, the centroids of the solid and of the surface, the gradients of
// area and volume with respect to the control points, and an error estimate.
//
// At a sample with weight w (parameter domain) and derivatives x, x_u, x_v, the
// area element is dA = |x_u × x_v| du dv and a = x_u × x_v = n dA/(du dv) points
// outward for faces counter-clockwise seen from outside (docs/conventions.md
// "Orientation"). Then
//   area             A = Σ w |a|
//   enclosed volume  V = 1/3 ∫ x·n dA = 1/3 Σ w x·a      (divergence theorem, div x = 3)
//   solid centroid   c_i = (1/V) ∫_solid x_i dV = (1/V) Σ w (x_i²/2) a_i   (div (x_i²/2 e_i) = x_i)
//   surface centroid s = (1/A) Σ w x |a|
//   inertia          I = ∫_solid (|r|² Id − r rᵀ) dV, r = x − c (unit density, about the centroid),
//                    from the second moments ∫ x_i² dV = ⅓∫ x_i³ n_i dA (div (x_i³/3 e_i) = x_i²) and
//                    ∫ x_i x_j dV = ¼∫ (x_i² x_j n_i + x_j² x_i n_j) dA (the mean of two divergence forms)
//                    about the mean control point, moved to the centroid by the parallel-axis theorem
// V and c are meaningful for closed surfaces only (V > 0 when outward oriented); V is
// translation invariant only for a closed surface.
//
// The gradients are those of the quadrature sums themselves (exact derivatives of the
// discrete values, not of the exact integrals): with W_0, W_u, W_v the stored weight
// rows of a sample and n̂ = a/|a|,
//   ∂A/∂X_k = Σ w (W_u[k] (x_v × n̂) + W_v[k] (n̂ × x_u))
//   ∂V/∂X_k = Σ w/3 (W_0[k] a + W_u[k] (x_v × x) + W_v[k] (x × x_u)).
//
// What is exact and what is not: the samples' limit weights are exact (LimitBasis);
// the integrands are polynomial only per Stam tile and |a| is not polynomial at all,
// so every value here is a quadrature approximation. measure() estimates its error by
// comparing with a finer sampler (see there).
#pragma once

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {

/// @brief Area of the limit surface of @p X (#V × 3). @throws InputError on a row mismatch
[[nodiscard]] double area(const LimitSampler& sampler, const Points& X);
/// @brief Enclosed volume 1/3 ∫ x·n dA (closed surfaces; positive when outward oriented).
[[nodiscard]] double enclosed_volume(const LimitSampler& sampler, const Points& X);
/// @brief Centroid of the solid enclosed by a closed limit surface.
/// @throws NumericalError when the enclosed volume is (nearly) zero
[[nodiscard]] Eigen::Vector3d centroid(const LimitSampler& sampler, const Points& X);
/// @brief Inertia tensor of the solid enclosed by a closed limit surface, about its centroid (unit density).
/// @throws NumericalError when the enclosed volume is (nearly) zero
[[nodiscard]] Eigen::Matrix3d inertia(const LimitSampler& sampler, const Points& X);
/// @brief Area-weighted centroid of the surface. @throws NumericalError when the area is zero
[[nodiscard]] Eigen::Vector3d surface_centroid(const LimitSampler& sampler, const Points& X);
/// @brief ∂area/∂X, #V × 3 (row k: derivative with respect to control point k).
[[nodiscard]] Points area_gradient(const LimitSampler& sampler, const Points& X);
/// @brief ∂(enclosed volume)/∂X, #V × 3.
[[nodiscard]] Points volume_gradient(const LimitSampler& sampler, const Points& X);

/// True when the limit surface of @p basis is closed: no boundary vertex and no ptex face
/// without a limit surface (holes). Volume and solid centroid are defined only then.
[[nodiscard]] bool encloses_volume(const LimitBasis& basis);

/// Area, volume, centroids and the solid's inertia tensor in one pass.
struct SurfaceMeasures {
    double area = 0.0;
    double volume = 0.0;                                         ///< 0 when !closed
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();          ///< solid centroid; zero when !closed
    Eigen::Vector3d surface_centroid = Eigen::Vector3d::Zero();  ///< area-weighted
    Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< of the solid, about its centroid; zero when !closed
};

/// @brief All of SurfaceMeasures from one evaluation of the sampler.
/// @param closed compute volume and centroid (else left 0)
/// @details Computed on the control points scaled to order one by a power of two (exactly), so the
///   verdicts do not depend on the mesh's size; each quantity is scaled back by its dimension.
/// @throws NumericalError for a zero area, or a (nearly) zero volume when @p closed, or when
///   the area, volume or inertia overflows or underflows a double (naming which)
[[nodiscard]] SurfaceMeasures measure(const LimitSampler& sampler, const Points& X, bool closed);

/// Estimated absolute errors of SurfaceMeasures (centroids: Euclidean distance).
struct MeasureErrors {
    double area = 0.0;
    double volume = 0.0;
    double centroid = 0.0;
    double surface_centroid = 0.0;
    double inertia = 0.0;  ///< Frobenius norm of the difference
};

/// Measures with an error estimate.
struct MeasureReport {
    bool closed = false;    ///< encloses_volume(basis)
    SurfaceMeasures value;  ///< with the requested options
    MeasureErrors error;    ///< |value - finer value|
    SamplerOptions finer;   ///< the options of the comparison
};

/// @brief measure() with @p options, and its error estimated as the difference to a finer
///   sampler: degree + 4 (capped at the rule's maximum: 127 on squares, 60 on triangles) and
///   one more tile level near extraordinary vertices when options use tiles.
/// @details The estimate is that of the coarser value (which is reported); the finer value is
///   usually much more accurate, so the estimate is pessimistic where quadrature converges fast
///   and realistic near extraordinary vertices without tiles, where it converges slowly.
[[nodiscard]] MeasureReport measure_with_error(const LimitBasis& basis, const Points& X, const SamplerOptions& options);

}  // namespace limsurf
