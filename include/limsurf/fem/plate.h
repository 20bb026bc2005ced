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
    /// w = 0 and ∂w/∂n = 0: the boundary control values and their neighbours are zero. Along a
    /// boundary of regular vertices this is exactly ∂w/∂n = 0 in the limit space (the cross derivative
    /// there reads the first two rows only), not a stronger constraint; the deflection converges only
    /// like h because the space has ∂²w/∂n² = 0 on such a boundary (the boundary rule's phantom points
    /// P₋₁ = 2P₀ − P₁) and cannot carry the clamped edge's moment (docs/fem.md "Plates").
    Clamped,
    /// w = 0 strongly and ∂w/∂n = 0 weakly by Nitsche's method (assemble_plate_clamping, penalty
    /// default_clamping_penalty). On the limit space it tends to Clamped as γ → ∞ and converges at the
    /// same order (h): kept for measurement and for spaces that can carry an edge moment.
    ClampedNitsche
};

/// Penalty factor γ of the Nitsche clamping term γ D / h ∫ ∂w/∂n ∂v/∂n ds. Stability does not fix it
/// on the limit space: the consistency terms vanish on straight edges of regular vertices (M_nn(w) = 0
/// there for w = 0 on the edge) and are small on curved ones (the clamped square and an O-grid disk
/// stay positive definite down to γ = 0.1). The deflection depends on γ like a rotational spring's
/// (docs/fem.md "Plates"); 20 is the usual size for cubics, not a tuned value.
inline constexpr double default_clamping_penalty = 20.0;

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

/// @brief The Nitsche terms that clamp the edge weakly (J. Nitsche, Abh. Math. Sem. Hamburg 36, 1971,
///   carried to the plate's moment), over the limit boundary of the planar control points @p X:
///   N_ij = −∫_Γ [M_nn(φ_i) ∂φ_j/∂n + ∂φ_i/∂n M_nn(φ_j)] ds + γ D ∫_Γ (1/h) ∂φ_i/∂n ∂φ_j/∂n ds,
///   M_nn(φ) = D [(1 − ν) n·∇²φ·n + ν Δφ], n the outward normal in the plane, h = |det J| / |∂x/∂t|
///   the element's extent across the edge (J the map of the ptex face, t the parameter along the side).
///   On functions that vanish on Γ, a(w, v) + N(w, v) is the symmetric Nitsche form of the clamped
///   plate: integrating a by parts once gives the boundary term ∫_Γ M_nn(w) ∂v/∂n ds (the twisting
///   moment multiplies ∂v/∂t = 0), so the exact solution satisfies it with ∂w/∂n = 0.
/// @param rule the Gauss rule per boundary side: ceil((degree + 1) / 2) points per segment, sides
///   split dyadically towards their ends subdivide_near_extraordinary levels deep (as the sampler's)
/// @return #V × #V, symmetric; nonzero only between vertices whose basis functions reach the boundary
/// @throws InputError for a material out of range, X not #V × 3 or off the plane z = 0, a penalty ≤ 0;
///   UnsupportedError for triangle ptex faces (Loop); NumericalError at a degenerate boundary point
[[nodiscard]] SparseMatrix assemble_plate_clamping(const LimitBasis& basis, const Points& X,
                                                   const PlateMaterial& material, const SamplerOptions& rule,
                                                   double penalty = default_clamping_penalty);

/// @brief Solves a(w, v) = ∫ p v dA for all v with the edge conditions of @p support on every
///   boundary vertex. w = 0 is essential through the boundary rows of the basis (exact: the data are
///   zero and the limit boundary depends on the boundary rows only); ClampedNitsche adds the Nitsche terms
///   of assemble_plate_clamping with @p penalty, integrated with @p sampler's options.
/// @pre @p sampler was built on @p basis (checked on its first sample)
/// @throws InputError for a closed mesh or a sampler of another basis; as assemble_plate_bending,
///   assemble_plate_clamping and galerkin_load; NumericalError when the reduced stiffness is not
///   positive definite
[[nodiscard]] PlateSolution solve_plate(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                                        const PlateMaterial& material, PlateSupport support,
                                        const SurfaceFunction& load, double penalty = default_clamping_penalty);

/// @brief solve_plate with any sampler on @p topology; ClampedNitsche builds the Catmull–Clark basis of
///   @p topology with the default SchemeOptions for its edge integrals (penalty default_clamping_penalty).
/// @pre for ClampedNitsche, @p sampler was built on that basis (checked on its first sample)
[[nodiscard]] PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                                        const PlateMaterial& material, PlateSupport support,
                                        const SurfaceFunction& load);

/// @brief solve_plate with the load given by control values p_i (p = Σ p_i φ_i, so b = M p with M the
///   mass matrix): per-vertex data, carried to refined meshes by S0 like positions.
/// @throws InputError when there is not one finite value per control vertex; as solve_plate
[[nodiscard]] PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                                        const PlateMaterial& material, PlateSupport support,
                                        const Eigen::VectorXd& load_values);

/// @brief The point of a planar limit surface at (x, y): the ptex face and (u, v) whose limit position
///   is (x, y), found by Newton's method on each ptex face whose control points' bounding box holds
///   the point (the limit surface lies in the convex hull of the control points it depends on).
/// @return false when no ptex face contains (x, y) (outside the plate)
[[nodiscard]] bool locate_planar_point(const LimitBasis& basis, const Points& X, double x, double y, SurfacePoint& out);

/// @brief The Navier deflection of the simply supported rectangle [0, a] × [0, b] under the uniform
///   load p: (16 p / (π⁶ D)) Σ_{m,n odd} sin(mπx/a) sin(nπy/b) / (m n (m²/a² + n²/b²)²), the terms
///   bounded by @p tolerance times the first dropped (the tail is about tolerance relative: 1e-13
///   takes about 10⁵ terms, 1e-9 about 10³).
/// Tolerances below 1e-17 are taken as 1e-17 (doubles gain nothing beyond).
/// @throws InputError unless 0 < tolerance < 1, a, b, D > 0 and a, b, D, p, x, y finite
[[nodiscard]] double navier_uniform(double a, double b, double D, double p, double x, double y,
                                    double tolerance = 1e-13);

/// @brief The same deflection by Lévy's single series (Timoshenko & Woinowsky-Krieger, *Theory of
///   Plates and Shells*, the simply supported rectangle under uniform load), summed along the shorter
///   side s of the two (x along s, η = 2y/l − 1 across the longer side l, α_m = mπl/(2s)):
///   (4 p s⁴ / (π⁵ D)) Σ_{m odd} sin(mπx/s) / m⁵ · [1 − (α_m tanh α_m + 2)/2 · cosh(α_m η)/cosh α_m
///   + (α_m η / 2) · sinh(α_m η)/cosh α_m], the hyperbolic ratios as decaying exponentials (no
///   overflow at any aspect ratio) and sin(mπx/s) by rotation. Terms stop where the tail is below
///   @p tolerance times 4 p s⁴ / (π⁵ D): about (8 tolerance)^(-1/4) / 2 terms whatever the aspect
///   ratio (300 for 1e-12), where the double series needs 10³–10⁵ and more as a rectangle lengthens.
/// (x, y) belongs in the rectangle: outside it the series continues the formula, not the plate.
/// @throws InputError as navier_uniform
[[nodiscard]] double levy_uniform(double a, double b, double D, double p, double x, double y, double tolerance = 1e-14);

/// The Navier deflection under p sin(mπx/a) sin(nπy/b): that same shape times
/// p / (π⁴ D (m²/a² + n²/b²)²).
/// @throws InputError as navier_uniform, and for m or n below 1
[[nodiscard]] double navier_sine(double a, double b, double D, double p, int m, int n, double x, double y);

}  // namespace limsurf
