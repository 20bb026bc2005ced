// Kirchhoff–Love thin plates on the limit surface of a planar control mesh (iga-with-catmull-clark
// §5–6; iga-tuned-catmull-clark-weights §4, Table 2): the deflection w is a combination of the limit
// basis functions (C¹, so the fourth-order problem is conforming), the bending energy
//   a(w, v) = ∫ D [(1 − ν) ∇²w : ∇²v + ν Δw Δv] dA,  D = E t³ / (12 (1 − ν²)),
// and the Navier solutions of the simply supported rectangle for checking (Timoshenko and
// Woinowsky-Krieger, Theory of plates and shells, ch. 5). docs/fem.md "Plates".
#pragma once

#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {

/// Material and thickness of a plate (SI units or any consistent set).
struct PlateMaterial {
    double E = 2e11;         ///< Young's modulus, > 0
    double nu = 0.3;         ///< Poisson's ratio, in (−1, 0.5)
    double thickness = 0.1;  ///< t > 0
    /// D = E t³ / (12 (1 − ν²)).
    [[nodiscard]] double bending_rigidity() const noexcept {
        return E * thickness * thickness * thickness / (12.0 * (1.0 - nu * nu));
    }
};

/// Edge conditions on the whole boundary.
enum class PlateSupport {
    SimplySupported,  ///< w = 0 (the boundary control values); the edge moment vanishes naturally
    Clamped           ///< w = 0 and ∂w/∂n = 0 (the boundary control values and the next row)
};

/// @brief The bending stiffness K_ij = a(φ_i, φ_j) on the limit surface of the planar control
///   points @p X (z = 0): second derivatives in x, y through the map's own second derivatives,
///   ∇²φ = J⁻ᵀ (∇²_uv φ − Σ_k ∂φ/∂x_k ∇²_uv x_k) J⁻¹.
/// @throws InputError for a material out of range or a control mesh that is not in the plane z = 0;
///   NumericalError at a degenerate quadrature point
[[nodiscard]] SparseMatrix assemble_plate_bending(const LimitSampler& sampler, const Points& X,
                                                  const PlateMaterial& material);

struct PlateSolution {
    Eigen::VectorXd w;      ///< #V control values of the deflection
    double residual = 0.0;  ///< of the reduced system
    double energy = 0.0;    ///< a(w_h, w_h) = bᵀ w (twice the strain energy)
    std::string solver;
};

/// @brief Solves a(w, v) = ∫ p v dA for all v with the edge conditions of @p support on every
///   boundary vertex (essential conditions through the boundary rows of the basis: exact, since the
///   data are zero and the limit boundary depends on the boundary rows only).
/// @throws InputError for a closed mesh; as assemble_plate_bending and galerkin_load; NumericalError
///   when the reduced stiffness is not positive definite
[[nodiscard]] PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                                        const PlateMaterial& material, PlateSupport support,
                                        const SurfaceFunction& load);

/// @brief The point of a planar limit surface at (x, y): the ptex face and (u, v) whose limit position
///   is (x, y), found by Newton's method on each ptex face whose control points' bounding box holds
///   the point (the limit surface lies in the convex hull of the control points it depends on).
/// @return false when no ptex face contains (x, y) (outside the plate)
[[nodiscard]] bool locate_planar_point(const LimitBasis& basis, const Points& X, double x, double y, SurfacePoint& out);

/// @brief The Navier deflection of the simply supported rectangle [0, a] × [0, b] under the uniform
///   load p: (16 p / (π⁶ D)) Σ_{m,n odd} sin(mπx/a) sin(nπy/b) / (m n (m²/a² + n²/b²)²), the terms
///   bounded by @p tolerance times the first dropped (the tail is about tolerance relative: 1e-13
///   takes about 10⁵ terms, 1e-9 about 10³).
[[nodiscard]] double navier_uniform(double a, double b, double D, double p, double x, double y,
                                    double tolerance = 1e-13);

/// The Navier deflection under p sin(mπx/a) sin(nπy/b): that same shape times
/// p / (π⁴ D (m²/a² + n²/b²)²).
[[nodiscard]] double navier_sine(double a, double b, double D, double p, int m, int n, double x, double y);

}  // namespace limsurf
