// IGA-tuned Catmull–Clark weights (iga-tuned-catmull-clark-weights §3, docs/tuning.md): the
// weights (α, β, γ) of an extraordinary vertex as functions of its subdominant eigenvalue λ
// ((30), or the relaxed (31) where (30) has no real solution), the thin-plate energy-norm error
// (28), (32) of the quadratic shapes u₃ = ξ₁² + ξ₂² (cup) and u₄ = ξ₁² − ξ₂² (saddle) over the
// 2-neighbourhood of the characteristic map, the one-dimensional search in λ, and the local
// cup–saddle decomposition (33)–(38) of a solution at an extraordinary vertex (§3.4).
//
// The eigenvalues the constraints speak of are those of the one-ring's Fourier blocks, in closed
// form (docs/tuning.md derives them): the one-ring is invariant under Catmull–Clark, so its
// eigenvalues are eigenvalues of every larger neighbourhood's S, and the larger rings add only the
// regular rules' own (1/8, 1/16, ...). Frequency 1 gives λ = λ₁ = λ₂, frequency 0 gives λ₃ (the
// largest after 1), frequency 2 gives λ₄ = λ₅ (for valence 3, where frequency 2 is frequency −1,
// the smaller eigenvalue of that block). The energy norm reads eigenvectors off the scheme's own
// refinement of a local complex (analyse_scheme's S), so the two computations check each other.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// The quadratic shapes of (22): u₃ = ξ₁² + ξ₂² and u₄ = ξ₁² − ξ₂² (u₅ = 2ξ₁ξ₂ is u₄ turned by π/4
/// and has the same error).
enum class QuadraticShape { Cup, Saddle };

/// "cup" or "saddle".
[[nodiscard]] const char* to_string(QuadraticShape shape) noexcept;
/// @throws InputError for any other name than "cup" and "saddle"
[[nodiscard]] QuadraticShape parse_quadratic_shape(const std::string& name);

/// Which constraint system fixed the weights.
enum class TuningConstraint {
    Exact,    ///< (30): λ₁ = λ, λ₄ = λ², λ₃ = λ² (β ≠ γ in general)
    Relaxed,  ///< (31): λ₁ = λ, β = γ, λ₃ = λ² (λ₄ free), where (30) has no real solution
    None      ///< Catmull–Clark's own weights (no constraint)
};
[[nodiscard]] const char* to_string(TuningConstraint constraint) noexcept;

/// Weights at one λ and the eigenvalues they give (the one-ring's, closed form).
struct TunedVertex {
    int valence = 0;
    double lambda = 0.0;  ///< λ₁ = λ₂
    VertexRuleWeights weights;
    TuningConstraint constraint = TuningConstraint::None;
    double lambda3 = 0.0;  ///< frequency 0, the largest after 1
    double lambda4 = 0.0;  ///< frequency 2 (λ₄ = λ₅)
};

/// The one-ring eigenvalues of @p weights at an interior vertex of valence @p valence (≥ 3).
/// @throws InputError for a valence below 3 or above max_limit_size, α ≤ 0, β or γ < 0 or not
///   finite; NumericalError when λ₁ or λ₃ is not real (weights no C¹ scheme has)
[[nodiscard]] TunedVertex one_ring_spectrum(int valence, const VertexRuleWeights& weights);

/// The interval of λ for which weights exist at @p valence (α > 0, β, γ ≥ 0, λ₃ = λ² the largest
/// eigenvalue after λ).
struct LambdaRange {
    double low = 0.0;
    double high = 0.0;
};

/// @brief The feasible λ of (31) at @p valence (where (31) has weights; (30) is tried first inside it).
/// @throws InputError for a valence other than 3 and 5..max_limit_size (valence 4 is the regular
///   B-spline: tuning it would change every regular patch)
[[nodiscard]] LambdaRange feasible_subdominant_range(int valence);

/// @brief Solves (30) for β, γ (both swaps of its two solutions are returned when it has real
///   ones with β, γ ≥ 0), else (31), then λ₃ = λ² for α — in closed form (docs/tuning.md).
/// @return one or two candidates, Exact ones first
/// @throws InputError for a valence as feasible_subdominant_range or a λ outside its range
[[nodiscard]] std::vector<TunedVertex> weights_for_subdominant(int valence, double lambda);

/// How the energy norm (28) is integrated.
struct TuningOptions {
    /// Gauss points per direction on each tile (the paper's Fig. 6 varies 2..6, Fig. 7 uses 4).
    int quadrature_points = 4;
    /// Tiles towards the extraordinary vertex (quadrature/sampler.h): each ring of Stam's tiles
    /// gets its own rule down to 2^-levels; the innermost cell's share is below 1e-9 of the norm.
    int tile_levels = 10;
    double poisson_ratio = 0.3;  ///< μ of (28)
    /// Threads over the faces of the 2-neighbourhood (0: all cores); tune_weights runs its curve's λ
    /// on them first, one evaluation each. Each face's integrals are summed alone and then in face
    /// order, so the errors do not depend on it.
    int num_threads = 0;
};

/// Relative energy-norm errors (32) of the cup and the saddle.
struct ShapeErrors {
    double cup = 0.0;
    double saddle = 0.0;
};

/// @brief ‖u_j^h − u_j‖_e / ‖u_j‖_e over the 2-neighbourhood of the characteristic map of
///   @p weights at an interior vertex of valence @p valence, u_j^h the limit of the control values
///   r_j ⟨l_j, u_j(r₁, r₂)⟩ of (25)–(27) (the projection of u_j onto its eigenvector).
/// @param weights Catmull–Clark's own at valence 4 (the regular case: both errors vanish)
/// @throws InputError for a valence outside 3..max_limit_size, tuned weights at valence 4,
///   options out of range (1..10 points, 0..20 levels, μ in (−1, 0.5]); NumericalError when the
///   eigenvalues the shapes need are not simple real ones of their blocks
[[nodiscard]] ShapeErrors quadratic_shape_errors(int valence, const VertexRuleWeights& weights,
                                                 const TuningOptions& options = {});

/// One point of the error curve over λ (Figs. 6, 7).
struct TuningSample {
    TunedVertex vertex;
    ShapeErrors errors;
};

/// What tune_weights() searches.
struct TuningRequest {
    int valence = 5;
    QuadraticShape shape = QuadraticShape::Cup;
    TuningOptions options;
    /// λ interval searched (0, 0: the whole feasible range).
    double lambda_low = 0.0;
    double lambda_high = 0.0;
    int curve_samples = 61;          ///< the grid of the curve, ≥ 3
    double lambda_tolerance = 1e-5;  ///< of the golden-section and bisection searches
    /// §3.3's choice: the other shape's error may not exceed its error under Catmull–Clark's weights
    /// (Fig. 7: "for λ ∈ [0.550, 0.585] the optimised weights lead to a reduction of errors in both
    /// cup- and saddle-like geometries"; its cup and saddle optima are that interval's ends).
    /// false: the shape's error alone (TuningResult::unconstrained either way).
    bool protect_other_shape = true;
};

struct TuningResult {
    TuningRequest request;
    LambdaRange feasible;      ///< feasible_subdominant_range(valence)
    LambdaRange searched;      ///< the interval the grid covered
    TunedVertex tuned;         ///< the minimiser of the requested shape's error (under the protection)
    ShapeErrors tuned_errors;  ///< both shapes' errors with the tuned weights
    /// The minimiser of the shape's error alone (equal to `tuned` when the protection does not bind).
    TuningSample unconstrained;
    bool protection_binds = false;  ///< the tuned λ is where the other shape's error meets Catmull–Clark's
    TunedVertex classical;          ///< Catmull–Clark's weights at this valence
    ShapeErrors classical_errors;
    std::vector<TuningSample> curve;  ///< the grid, increasing λ (both shapes at each λ)
};

/// @brief The one-dimensional search (32): both errors on a grid of λ over the range; the shape's
///   minimum by golden-section search inside the best grid interval; with protect_other_shape, where
///   that minimum raises the other shape's error above Catmull–Clark's, the best of the points where
///   the other error crosses Catmull–Clark's (bisection between grid points). For each λ with two
///   Exact candidates the one with the smaller error of the requested shape counts.
/// @throws InputError as feasible_subdominant_range, a range outside the feasible one, fewer than 3
///   samples; as quadratic_shape_errors
[[nodiscard]] TuningResult tune_weights(const TuningRequest& request);

/// @brief weights_for_subdominant() with both errors of each candidate (quadratic_shape_errors).
/// @throws as weights_for_subdominant and quadratic_shape_errors
[[nodiscard]] std::vector<TuningSample> candidates_at(int valence, double lambda, const TuningOptions& options = {});

/// @brief The weights a user gets for @p shape at @p valence: tune_weights() with the protection,
///   its λ rounded to three decimals as Table 1 prints it, and weights_for_subdominant() there (the
///   candidate with the smaller error of the shape). At valence 5 this is Table 1: cup λ = 0.550,
///   α = 13.4575, β = γ = 0.999938; saddle λ = 0.585, α = 13.9851, β = γ = 0.824886.
/// @throws as tune_weights
[[nodiscard]] TunedVertex tuned_vertex_weights(int valence, QuadraticShape shape, const TuningOptions& options = {});

/// The local cup–saddle decomposition (37), (38) at one extraordinary vertex.
struct ShapeDecomposition {
    Index vertex = invalid_index;
    int valence = 0;
    double k3 = 0.0;  ///< cup coefficient of ξ₁² + ξ₂²
    double k4 = 0.0;  ///< saddle coefficient of ξ₁² − ξ₂²
    double k5 = 0.0;  ///< saddle coefficient of 2ξ₁ξ₂
    /// R = k₃² / (k₄² + k₅²) · (1 + μ)/(1 − μ); +inf when k₄ = k₅ = 0, NaN when k₃ = k₄ = k₅ = 0
    double ratio = 0.0;
    /// False where P is flat at the vertex to rounding (|k| ≤ 2e-15 of the one-ring's size or its
    /// distance from the origin, whichever is larger; a plane in any position stays 30× below):
    /// k₃ = k₄ = k₅ = 0 then, and R is NaN. A part below that floor alone is 0 too (R = +inf or 0).
    bool has_quadratic_part = true;
    /// (34), oriented by the faces' order around the vertex (their area vector): k₃ > 0 for a cup
    /// that opens towards the side the faces face.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    /// The vertex's limit point ⟨l₀, P⟩: where the decomposition holds (for a plate, (x, y, w)).
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    /// ∂P/∂ξ₁ and ∂P/∂ξ₂ of the limit surface at the vertex, in the characteristic coordinates that
    /// k₃, k₄, k₅ refer to (first spoke along +ξ₁, the spoke's control point at ξ = 1). With
    /// J = (tangent1 tangent2) a smooth field with Hessian H in the tangent plane has the ξ-Hessian
    /// JᵀHJ, which a quadratic k₃u₃ + k₄u₄ + k₅u₅ has as 2[[k₃+k₄, k₅], [k₅, k₃−k₄]]: the k's and R
    /// an exact solution has there (a solution's control values give k's that differ from those of
    /// its limit; docs/tuning.md).
    Eigen::Vector3d tangent1 = Eigen::Vector3d::Zero();
    Eigen::Vector3d tangent2 = Eigen::Vector3d::Zero();
    /// R ≥ 1; false at a flat vertex (no quadratic part), where neither shape dominates.
    [[nodiscard]] bool cup_dominates() const noexcept { return ratio >= 1.0; }
};

/// R of (38): k₃² / (k₄² + k₅²) · (1 + μ)/(1 − μ); +inf when k₄ = k₅ = 0.
[[nodiscard]] double cup_saddle_ratio(double k3, double k4, double k5, double poisson_ratio);

/// @brief Decomposes the control points @p P (#V × 3; for a plate, (x, y, w)) at every interior
///   vertex of valence ≥ @p min_valence whose faces are all quads, with that vertex's weights in
///   @p weights: ⟨l_j, P n⟩ / ⟨l_j, u_j(r₁, r₂)⟩ for the one-ring's left eigenvectors l_j (the
///   one-ring is invariant, so the larger neighbourhoods' left eigenvectors vanish outside it) and
///   the characteristic map's r₁, r₂ turned so that the vertex's first edge lies along ξ₁. The
///   factors (λ_j/λ²)^ℓ of (37) are taken at ℓ = 0: the decomposition is that of the level given.
///   Vertices whose one-ring holds another vertex with its own β or γ (the closed form assumes its
///   neighbours weigh 1; refine once and they are apart) are refused.
/// @throws InputError when P is not #V × 3 or not finite, weights no C¹ scheme has, a one-ring with
///   another tuned vertex; NumericalError at a vertex whose tangents (34) are parallel
[[nodiscard]] std::vector<ShapeDecomposition> decompose_shapes(const Topology& topology, const Points& P,
                                                               const TunedWeights& weights, int min_valence = 5,
                                                               double poisson_ratio = 0.3);

}  // namespace limsurf
