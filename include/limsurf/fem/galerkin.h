// The Galerkin layer: finite elements whose trial and test functions are the limit basis
// functions φ_i of the control vertices (iga-with-catmull-clark §5–6, Bubnov–Galerkin), integrated
// by quadrature on the exact limit surface (quadrature/sampler.h: Gauss rules per ptex face, Stam
// tiles towards extraordinary vertices). Every degree of freedom is a control vertex.
//
// Assembly follows the per-control-face pattern of the SEC layer: each ptex face's samples give a
// dense element matrix over the control vertices its surface depends on (its one-ring, a 2-ring for
// C2g0), computed in parallel and gathered into one CSR matrix. docs/fem.md.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {

/// A function on the surface, evaluated at many points at once: rows of positions (#P × 3) in,
/// one value per row out.
using SurfaceFunction = std::function<Eigen::VectorXd(const Points&)>;

/// Mass and Laplace–Beltrami stiffness of the limit basis (both #V × #V, symmetric).
struct GalerkinMatrices {
    SparseMatrix mass;       ///< M_ij = ∫ φ_i φ_j dA, positive definite
    SparseMatrix stiffness;  ///< K_ij = ∫ ∇φ_i · ∇φ_j dA (surface gradients), semi-definite, K 1 = 0
};

/// @brief Assembles the mass and Laplace–Beltrami stiffness matrices on the limit surface of @p X
///   (the sampler's control points, #V × 3): at each quadrature point the metric g = JᵀJ of the
///   tangents J = [∂u X, ∂v X], ∇φ_i · ∇φ_j = (∂φ_i)ᵀ g⁻¹ ∂φ_j, dA = √det g du dv.
/// @throws InputError when X has the wrong size; NumericalError at a degenerate quadrature point
///   (parallel tangents), naming its ptex face
[[nodiscard]] GalerkinMatrices assemble_laplace_beltrami(const LimitSampler& sampler, const Points& X);

/// @brief The area form of maps to the plane: for (u, v) = Σ (u_i, v_i) φ_i and U = (u; v)
///   stacked (2#V), the symmetric 2#V × 2#V matrix A_s with ½ Uᵀ A_s U = ∫ du ∧ dv, the signed
///   area of the image (by Stokes ½ ∮ u dv − v du along the limit boundary; the integrand per ptex
///   face is u_a v_b − u_b v_a in its own parameters, so no geometry enters). Its u–v block is
///   W_ij = ∫ (∂_a φ_i ∂_b φ_j − ∂_b φ_i ∂_a φ_j) da db, antisymmetric; counter-clockwise images of
///   the surface's orientation have positive area. Exact up to the sampler's rule (polynomial
///   integrands per tile); interior faces cancel, so on a closed surface A_s = 0 to rounding.
///   The Galerkin counterpart of the boundary area form of spectral conformal maps (Mullen et al.).
[[nodiscard]] SparseMatrix assemble_area_form(const LimitSampler& sampler);

/// @brief The load vector b_i = ∫ f φ_i dA, with @p f evaluated at the quadrature points of the
///   limit surface (not at the control points).
/// @throws InputError when f returns the wrong number of values or a non-finite one
[[nodiscard]] Eigen::VectorXd galerkin_load(const LimitSampler& sampler, const Points& X, const SurfaceFunction& f);

/// Errors of a discrete function u_h = Σ u_i φ_i against an exact one, by quadrature on the limit surface.
struct GalerkinErrors {
    double l2 = 0.0;       ///< ‖u_h − u‖_L2
    double h1 = 0.0;       ///< |u_h − u|_H1 (surface gradients)
    double l2_norm = 0.0;  ///< ‖u‖_L2, for relative errors
    double h1_norm = 0.0;  ///< |u|_H1
    double area = 0.0;     ///< ∫ dA
};

/// @brief The errors of @p u (control values, #V) against @p exact, whose gradient in R³ is
///   @p exact_gradient (#P × 3 per call; only its tangential part counts). @p subtract_mean: compare
///   both with their area-weighted means removed (closed surfaces, where u is defined up to a constant).
[[nodiscard]] GalerkinErrors galerkin_errors(const LimitSampler& sampler, const Points& X, const Eigen::VectorXd& u,
                                             const SurfaceFunction& exact,
                                             const std::function<Points(const Points&)>& exact_gradient,
                                             bool subtract_mean);

/// The solution of a Galerkin Poisson problem.
struct GalerkinPoissonSolution {
    Eigen::VectorXd u;          ///< #V control values; closed meshes: ∫ u_h dA = 0
    double residual = 0.0;      ///< ‖K u − b‖ / ‖b‖ over the free vertices
    double mean_removed = 0.0;  ///< closed meshes: the mean ∫ f dA / A removed from the load
    std::string solver;         ///< "cholmod" or "eigen-simplicial-ldlt"
};

/// @brief Solves K u = b (−Δ u = f weakly, b = galerkin_load). Closed meshes: the load is made
///   compatible (its mean removed), one vertex is pinned and u shifted to ∫ u_h dA = 0. Open meshes:
///   the boundary vertices' control values are set to @p boundary_values (essential conditions
///   through the boundary rows of the basis, as iga-with-catmull-clark §5: exact for data the
///   basis reproduces on the boundary, linear functions say; otherwise an O(h²) approximation of
///   the boundary data, docs/fem.md).
/// @throws InputError on size mismatches or missing boundary values on an open mesh;
///   NumericalError when the factorisation fails or the solution is not finite
[[nodiscard]] GalerkinPoissonSolution solve_galerkin_poisson(const Topology& topology, const GalerkinMatrices& matrices,
                                                             const Eigen::VectorXd& load,
                                                             const std::optional<Eigen::VectorXd>& boundary_values);

}  // namespace limsurf
