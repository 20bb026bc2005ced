// Shape functionals of a closed limit surface and their exact gradients with respect to the
// control points: the quantities of the Canham–Helfrich problem (3.1) and the harmonic energy
// (3.6)–(3.11) of c2g0-sphere-scheme-biomembranes §3 (docs/membrane.md).
//
// For control points X (#V × 3) of a closed surface S = S[X]:
//   area            A = ∫ dA
//   volume          V = 1/3 ∫ x·n dA: exact trilinear forms (EnclosedVolume) for Loop and
//                   Catmull–Clark, the quadrature of that integral for C2g0 (no forms exist)
//   mean curvature  M = ∫ H dA, H = (k1 + k2)/2 (limit/surface_frame.h: H = 1 on the unit sphere)
//   Willmore        W = ∫ H² dA (4π on every round sphere)
//   Gaussian        K = ∫ K dA (2π χ by Gauss–Bonnet; its gradient vanishes up to quadrature error)
//   harmonic        E = ∫ ‖dφ‖² of the parameterisation φ over the conformal structure of the
//                   control mesh (3.6): every triangle an equilateral triangle (the τ map of (3.9):
//                   E_f = 2/√3 ∫_Ω E − F + G), every Catmull–Clark ptex face a unit square
//                   (E_f = ∫ E + G). On C2g0 meshes (valences 3 and 6) this is the Bers structure
//                   of §2.3; on Loop and Catmull–Clark meshes it is the cone structure of the same
//                   equilateral triangles / squares, whose energy is finite (near a vertex of
//                   subdominant eigenvalue λ, |dφ| grows like r^(-log2 λ - 1), square-integrable).
// Each is a sum over quadrature samples (quadrature/sampler.h) of a function of the position
// and derivatives there; the gradient is the exact derivative of that sum (the chain rule through
// the limit weights, (3.10)–(3.11)), so finite differences of the discrete functional converge to
// it at rate h². Derived quantities: reduced volume v = V / ((4π/3)(A/4π)^(3/2)), reduced total
// mean curvature m = M / (4π (A/4π)^(1/2)) (defined under Fig. 1; both 1 on a round sphere) and
// the Helfrich energy ∫ (H − H0)² dA = W − 2 H0 M + H0² A.
//
// Parallel and deterministic: samples are evaluated in parallel over ptex faces into per-face
// local gradients, which are then gathered per control vertex in face order, so the results are
// bit-identical for every thread count.
#pragma once

#include <array>
#include <memory>
#include <span>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// The shape functionals ShapeFunctionals evaluates.
enum class ShapeFunctional { Area = 0, Volume, MeanCurvature, Willmore, Gaussian, Harmonic };
constexpr int num_shape_functionals = 6;

/// The weights c_f of a combination Σ_f c_f F_f of the functionals, indexed by ShapeFunctional.
using ShapeCoefficients = std::array<double, num_shape_functionals>;

/// Options of ShapeFunctionals.
struct ShapeOptions {
    int degree = 8;                        ///< quadrature degree per tile (quadrature/rules.h)
    int subdivide_near_extraordinary = 3;  ///< tile levels towards irregular corners (SamplerOptions)
    int num_threads = 0;                   ///< 0: hardware concurrency; results do not depend on it
    /// Loop and Catmull–Clark: the volume by exact trilinear forms (true) or by the same quadrature
    /// as C2g0 (false). C2g0 always uses quadrature.
    bool exact_volume = true;
    /// Catmull–Clark: the regular patches' elements (a bicubic B-spline on the square rule's grid)
    /// one direction at a time, by sum factorisation (true), or through their dense kernels like
    /// every other element (false). The same values and gradients to rounding (another order of
    /// summation; the tests hold them to 1e-13); false is for checking.
    bool sum_factorisation = true;
};

/// Values of every functional at one X, and the gradients that were asked for.
struct ShapeValues {
    double area = 0.0;
    double volume = 0.0;
    double mean_curvature = 0.0;  ///< M = ∫ H dA
    double willmore = 0.0;        ///< W = ∫ H² dA
    double gaussian = 0.0;        ///< ∫ K dA
    double harmonic = 0.0;        ///< E of (3.6)
    /// ∂value/∂X (#V × 3) per functional, indexed by ShapeFunctional; empty when not asked for.
    std::array<Points, num_shape_functionals> gradient;

    [[nodiscard]] double value(ShapeFunctional f) const noexcept;
    [[nodiscard]] const Points& gradient_of(ShapeFunctional f) const { return gradient[static_cast<std::size_t>(f)]; }
    /// v = V / ((4π/3)(A/4π)^(3/2)); 1 on a round sphere.
    [[nodiscard]] double reduced_volume() const noexcept;
    /// m = M / (4π (A/4π)^(1/2)); 1 on a round sphere.
    [[nodiscard]] double reduced_mean_curvature() const noexcept;
    /// ∫ (H − H0)² dA = W − 2 H0 M + H0² A.
    [[nodiscard]] double helfrich(double spontaneous_curvature) const noexcept;
    /// Its gradient from those of W, M and A.
    /// @throws InputError when one of the three gradients was not computed
    [[nodiscard]] Points helfrich_gradient(double spontaneous_curvature) const;
};

/// @brief Shape functionals of the closed limit surface of one topology, for any control points.
/// @details Built once per topology (a LimitSampler with second derivatives, and EnclosedVolume
///   where exact); evaluate() then costs one pass over the samples. Immutable and thread-safe.
class ShapeFunctionals {
  public:
    /// @param basis a closed surface under Loop, Catmull–Clark or C2g0 (copied what is needed)
    /// @throws InputError for an open surface (names a boundary vertex), or bad options
    /// @throws UnsupportedError for Doo–Sabin, sharpness tags, holes (naming the scheme or vertex)
    explicit ShapeFunctionals(const LimitBasis& basis, const ShapeOptions& options = {});
    ~ShapeFunctionals();
    ShapeFunctionals(ShapeFunctionals&&) noexcept;
    ShapeFunctionals& operator=(ShapeFunctionals&&) noexcept;
    ShapeFunctionals(const ShapeFunctionals&) = delete;
    ShapeFunctionals& operator=(const ShapeFunctionals&) = delete;

    /// @brief Every functional at @p X, and the gradients of those in @p gradients.
    /// Each value and gradient is the same bits whichever others are asked for.
    /// @throws InputError when X does not have num_vertices() rows or has a non-finite entry
    /// @throws NumericalError when the surface is degenerate at a sample (parallel tangents),
    ///   naming the ptex face
    [[nodiscard]] ShapeValues evaluate(const Points& X, std::span<const ShapeFunctional> gradients = {}) const;
    /// evaluate() with the gradients of all six functionals.
    [[nodiscard]] ShapeValues evaluate_all(const Points& X) const;

    /// @brief The Hessian of Σ_f coefficients[f] F_f at @p X: the symmetric (3 #V) × (3 #V) matrix of
    ///   second derivatives, row and column 3 v + c for coordinate c of control point v.
    /// @details The chain rule (3.10)–(3.11) once more: per sample, the 18 × 18 second derivatives of
    ///   the integrand with respect to its position and derivatives (by central differences of their
    ///   exact gradients, relative error ~1e-10: membrane/sample_hessians.h), pulled back through the
    ///   sample's limit weights, summed per element and then in element order (the same bits for any
    ///   thread count). The pattern holds every pair of control points that share an element's
    ///   support, explicit zeros included, and depends on the topology only (the pairs are found
    ///   at the first call and kept). The volume's term is
    ///   that of its quadrature with the centroid held fixed, also where the values and gradients
    ///   use exact trilinear forms (volume_is_exact()): it differs from their Hessian by the
    ///   quadrature's error. Used by minimize_membrane for Newton steps (MembraneHessian::Exact).
    /// @throws InputError as evaluate(), or for a non-finite coefficient
    /// @throws NumericalError when the surface is degenerate at a sample, naming the ptex face
    [[nodiscard]] SparseMatrix hessian(const Points& X, const ShapeCoefficients& coefficients) const;
    /// hessian() into @p H, whose storage is reused when it holds this object's pattern already
    /// (checked entry by entry; its values are overwritten; otherwise it is reshaped): what a solver
    /// calls once per iteration.
    /// @throws as hessian(); H is then left with the pattern and unspecified values
    void hessian(const Points& X, const ShapeCoefficients& coefficients, SparseMatrix& H) const;
    /// hessian()'s pattern with every value 0: the same for any X and coefficients (what a solver
    /// declares before its first iteration, without computing a Hessian).
    [[nodiscard]] SparseMatrix hessian_pattern() const;

    [[nodiscard]] Index num_vertices() const noexcept;
    [[nodiscard]] Index num_samples() const noexcept;
    [[nodiscard]] SchemeKind scheme() const noexcept;
    [[nodiscard]] const ShapeOptions& options() const noexcept;
    /// True when the volume comes from exact trilinear forms, false when from quadrature.
    [[nodiscard]] bool volume_is_exact() const noexcept;
    /// The elements (ptex faces) evaluated by sum factorisation (ShapeOptions::sum_factorisation):
    /// on a closed all-quad mesh, the faces whose four corners have valence 4; 0 for other schemes.
    [[nodiscard]] Index num_sum_factorised_elements() const noexcept;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace limsurf
