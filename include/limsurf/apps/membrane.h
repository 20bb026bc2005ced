// Biomembrane shapes end to end: the driver behind `limsurf membrane` and limsurf.minimize_membrane
// in Python (docs/guide/membrane.md), so that both solve the same problem the same way.
//
// A request names the targets as the user gives them (absolute or reduced, c2g0-sphere-scheme-
// biomembranes Fig. 1: v = V / ((4π/3)(A/4π)^(3/2)), m = M / (4π (A/4π)^(1/2))); membrane_problem()
// turns them into the MembraneProblem of (3.1). solve_membrane_problem() then
//   1. scales the initial guess about the centroid of its control points so that its limit area
//      is A0 (A is homogeneous of degree 2 in X, so by sqrt(A0 / A)): the area constraint holds at
//      the start and the solver's steps are measured at the target's scale;
//   2. minimises W (Canham), or the Helfrich energy ∫(H − H0)² dA with H0, under A = A0, V = V0
//      [and M = M0] (problem (3.1)); with continuation_steps = K > 1, first under the targets
//      V_k = V_s + (V0 − V_s) k/K [and M_k likewise], k = 1 … K − 1, V_s and M_s the scaled
//      start's, each solve starting from the previous one's shape;
//   3. with regularize_harmonic = ε, and when step 2 converged, minimises the harmonic energy E of
//      the parameterisation under the same constraints and W ≤ W0 + ε, W0 the W of step 2 — the
//      post-processing (3.12) of §3.3, with the paper's absolute ε (not a factor 1 + ε).
// The library prints nothing: progress comes through the callback.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/membrane/shape_functionals.h"
#include "limsurf/membrane/shape_optimization.h"

namespace limsurf {

/// The most continuation steps a request may ask for (each is a solve).
inline constexpr int max_continuation_steps = 1000;
/// The objective tolerance (MembraneOptions::objective_tolerance) of the continuation's intermediate
/// steps, unless the request's is looser: they need only keep near the branch, not reach its minimum.
inline constexpr double continuation_objective_tolerance = 1e-4;

/// A membrane problem as a user states it.
struct MembraneRequest {
    double area = 0.0;                             ///< A0 in [min_membrane_area, max_membrane_area]
    std::optional<double> volume;                  ///< V0 > 0; exactly one of volume, reduced_volume
    std::optional<double> reduced_volume;          ///< v0 in [min_reduced_volume, 1]
    std::optional<double> mean_curvature;          ///< M0; at most one of mean_curvature, reduced_mean_curvature
    std::optional<double> reduced_mean_curvature;  ///< m0
    std::optional<double> spontaneous_curvature;   ///< H0: the Helfrich energy instead of W
    std::optional<double> regularize_harmonic;     ///< ε >= 0: also solve (3.12) with W <= W0 + ε
    int max_iterations = 1000;                     ///< per stage, >= 1
    double tolerance = 1e-8;                       ///< the solver's relative KKT tolerance, > 0
    /// Also stop, converged, when the objective's relative change stays below this for 15
    /// iterations with the constraints met (MembraneOptions::objective_tolerance); 0: KKT only.
    /// W is flat along tangential slides of the control points, so the KKT tolerance is often
    /// out of reach on fine meshes long after W has settled.
    double objective_tolerance = 1e-7;
    MembraneHessian hessian = MembraneHessian::LimitedMemory;  ///< of the first stage (MembraneOptions::hessian)
    /// Of the regularisation (3.12); none: the first stage's. Newton steps finish (3.12) on coarse
    /// meshes where quasi-Newton ones do not, but crawl on a first stage that starts far from its
    /// shape (docs/membrane.md, "Exact Hessians"): BFGS then Newton is the pair for that.
    std::optional<MembraneHessian> regularization_hessian;
    /// Steps in which the volume (and mean-curvature) targets are reached, >= 1: a homotopy from
    /// the start's V and M, whose intermediate solves keep each step short. A start far from its
    /// targets (a round sphere asked for v0 = 0.5) otherwise takes long first steps that can end
    /// in a shape passing through itself (docs/membrane.md, "Continuation"). 1: at once.
    int continuation_steps = 1;
};

/// Which stage of solve_membrane_problem() an iteration belongs to.
enum class MembraneStage {
    Continuation,   ///< an intermediate step of the continuation (MembraneRequest::continuation_steps)
    Shape,          ///< the Canham or Helfrich problem (3.1)
    Regularization  ///< the harmonic-energy post-processing (3.12)
};

/// "continuation", "shape" or "regularization".
[[nodiscard]] const char* to_string(MembraneStage stage) noexcept;

/// Called after each solver iteration; returning false stops the solve (converged = false).
using MembraneProgress = std::function<bool(MembraneStage, const MembraneIteration&)>;

/// One intermediate step of the continuation: its targets and its result.
struct MembraneContinuationStep {
    MembraneProblem problem;
    MembraneResult result;
};

/// The outcome of solve_membrane_problem().
struct MembraneRun {
    double initial_area = 0.0;  ///< limit area of the initial guess as given
    double scale = 1.0;         ///< factor the initial guess was scaled by (about its centroid)
    /// The continuation's K − 1 intermediate steps, in order (empty for continuation_steps = 1).
    /// A step that stops short hands its point on all the same: the last stage decides convergence.
    std::vector<MembraneContinuationStep> continuation;
    MembraneProblem problem;  ///< the problem (3.1) solved, targets absolute
    MembraneResult shape;     ///< its result
    /// Problem (3.12) and its result, when regularize_harmonic was given and the first stage converged.
    std::optional<MembraneProblem> regularization_problem;
    std::optional<MembraneResult> regularization;

    /// The result of the last stage run (its positions are the answer).
    [[nodiscard]] const MembraneResult& final_result() const noexcept {
        return regularization ? *regularization : shape;
    }
    /// Every stage asked for ran and converged.
    [[nodiscard]] bool converged(const MembraneRequest& request) const noexcept;
};

/// @brief The problem (3.1) of @p request, targets made absolute (v0 → V0 and m0 → M0 at A0).
/// @throws InputError naming the option for A0 outside [min_membrane_area, max_membrane_area], both or
///   neither of volume and reduced volume, V0 <= 0, v0 (given, or V0's) above 1 (no closed surface of
///   area A0 encloses more than the sphere) or below min_reduced_volume,
///   both mean curvature options, a negative ε, max_iterations < 1, tolerance <= 0,
///   continuation_steps outside [1, max_continuation_steps], or a value that is not finite
[[nodiscard]] MembraneProblem membrane_problem(const MembraneRequest& request);

/// @brief @p X scaled about the mean of its rows so that the limit area under @p functionals is
///   @p area; @p factor (when given) receives the factor.
/// @throws InputError for area <= 0; NumericalError when the limit area of X is not positive
[[nodiscard]] Points scale_to_area(const ShapeFunctionals& functionals, const Points& X, double area,
                                   double* factor = nullptr);

/// |residual| of each constraint relative to its value on the round sphere of area A0 (A0, the
/// sphere's volume, its M), the largest of them: the scale-free measure the JSON reports.
[[nodiscard]] double max_relative_residual(const MembraneProblem& problem, const MembraneResult& result) noexcept;

/// @brief Solves @p request from the control points @p initial (#V × 3) of @p functionals' topology:
///   scaling, problem (3.1), and (3.12) when asked for (see the file comment).
/// @throws InputError as membrane_problem() and minimize_membrane(), and with continuation_steps > 1
///   when the scaled start encloses a volume <= 0 (faces oriented inwards); UnsupportedError without
///   Ipopt; NumericalError when the initial guess is degenerate
[[nodiscard]] MembraneRun solve_membrane_problem(const ShapeFunctionals& functionals, const Points& initial,
                                                 const MembraneRequest& request, const MembraneProgress& progress = {});

}  // namespace limsurf
