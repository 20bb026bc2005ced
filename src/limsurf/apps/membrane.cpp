#include "limsurf/apps/membrane.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

void require_finite(const std::optional<double>& value, const char* name) {
    LIMSURF_CHECK(!value || std::isfinite(*value), InputError, name, " must be a finite number");
}

/// The stage's options: the request's limits and the progress callback tagged with the stage.
MembraneOptions stage_options(const MembraneRequest& request, MembraneStage stage, const MembraneProgress& progress) {
    MembraneOptions options;
    options.max_iterations = request.max_iterations;
    options.tolerance = request.tolerance;
    options.objective_tolerance = request.objective_tolerance;
    options.hessian = stage == MembraneStage::Regularization ? request.regularization_hessian.value_or(request.hessian)
                                                             : request.hessian;
    if (progress) {
        options.on_iteration = [&progress, stage](const MembraneIteration& it) { return progress(stage, it); };
    }
    return options;
}

/// The continuation's intermediate steps (MembraneRequest::continuation_steps), appended to
/// @p steps; returns the point the last of them reached (@p start when there are none). No step
/// starts once @p stopped (the caller said stop).
Points continue_towards(const ShapeFunctionals& functionals, const Points& start, const MembraneProblem& problem,
                        const MembraneRequest& request, const MembraneProgress& progress, const bool& stopped,
                        std::vector<MembraneContinuationStep>& steps) {
    const int k_steps = request.continuation_steps;
    if (k_steps == 1) {
        return start;
    }
    const ShapeValues from = functionals.evaluate(start);
    LIMSURF_CHECK(std::isfinite(from.volume) && std::isfinite(from.mean_curvature), NumericalError,
                  "a shape functional of the initial guess is not finite: cannot continue from it");
    LIMSURF_CHECK(from.volume > 0.0, InputError, "the initial guess encloses the volume ", from.volume,
                  ": the continuation starts from it and needs it positive (are its faces oriented inwards?)");
    const auto towards = [k_steps](double a, double b, int k) { return a + (b - a) * k / k_steps; };
    // A start whose quadrature volume exceeds the sphere's by rounding must not ask for more.
    const double sphere_volume = volume_from_reduced(1.0, problem.area);
    // A step need only stay near the branch, not finish its minimum: it stops once W settles to
    // continuation_objective_tolerance (or the request's, when looser).
    MembraneOptions options = stage_options(request, MembraneStage::Continuation, progress);
    options.objective_tolerance = std::max(options.objective_tolerance, continuation_objective_tolerance);
    Points at = start;
    for (int k = 1; k < k_steps && !stopped; ++k) {
        MembraneContinuationStep step{problem, {}};
        step.problem.volume = std::min(towards(from.volume, *problem.volume, k), sphere_volume);
        if (problem.mean_curvature) {
            step.problem.mean_curvature = towards(from.mean_curvature, *problem.mean_curvature, k);
        }
        step.result = minimize_membrane(functionals, at, step.problem, options);
        at = step.result.positions;
        steps.push_back(std::move(step));
    }
    return at;
}

}  // namespace

const char* to_string(MembraneStage stage) noexcept {
    switch (stage) {
    case MembraneStage::Continuation:
        return "continuation";
    case MembraneStage::Shape:
        return "shape";
    case MembraneStage::Regularization:
        return "regularization";
    }
    return "unknown";
}

bool MembraneRun::converged(const MembraneRequest& request) const noexcept {
    return shape.converged && (!request.regularize_harmonic || (regularization && regularization->converged));
}

MembraneProblem membrane_problem(const MembraneRequest& request) {
    LIMSURF_CHECK(std::isfinite(request.area) && request.area > 0.0, InputError, "area A0 = ", request.area,
                  ": must be positive");
    // The start is scaled to A0, so its coordinates are ~ sqrt(A0) and V ~ A0^(3/2): outside this range
    // the volume, the gradients or the solver's scaled quantities leave double precision.
    LIMSURF_CHECK(request.area >= min_membrane_area && request.area <= max_membrane_area, InputError,
                  "area A0 = ", request.area, ": must lie in [", min_membrane_area, ", ", max_membrane_area,
                  "] (state the problem in other units)");
    require_finite(request.volume, "volume V0");
    require_finite(request.reduced_volume, "reduced volume v0");
    require_finite(request.mean_curvature, "mean curvature M0");
    require_finite(request.reduced_mean_curvature, "reduced mean curvature m0");
    require_finite(request.spontaneous_curvature, "spontaneous curvature H0");
    require_finite(request.regularize_harmonic, "harmonic regularisation epsilon");
    LIMSURF_CHECK(request.volume.has_value() != request.reduced_volume.has_value(), InputError,
                  "give exactly one of the volume V0 and the reduced volume v0");
    LIMSURF_CHECK(!(request.mean_curvature && request.reduced_mean_curvature), InputError,
                  "give at most one of the mean curvature M0 and the reduced mean curvature m0");
    LIMSURF_CHECK(!request.regularize_harmonic || *request.regularize_harmonic >= 0.0, InputError,
                  "harmonic regularisation epsilon = ", request.regularize_harmonic.value_or(0.0),
                  ": must not be negative");
    LIMSURF_CHECK(request.max_iterations >= 1, InputError, "max iterations = ", request.max_iterations,
                  ": must be at least 1");
    LIMSURF_CHECK(std::isfinite(request.tolerance) && request.tolerance > 0.0, InputError,
                  "tolerance = ", request.tolerance, ": must be positive");
    LIMSURF_CHECK(std::isfinite(request.objective_tolerance) && request.objective_tolerance >= 0.0, InputError,
                  "objective tolerance = ", request.objective_tolerance, ": must not be negative");
    LIMSURF_CHECK(request.continuation_steps >= 1 && request.continuation_steps <= max_continuation_steps, InputError,
                  "continuation steps = ", request.continuation_steps, ": must lie in [1, ", max_continuation_steps,
                  "]");
    MembraneProblem problem;
    problem.area = request.area;
    if (request.reduced_volume) {
        const double v0 = *request.reduced_volume;
        // The isoperimetric inequality: the round sphere encloses the most volume for its area.
        LIMSURF_CHECK(v0 > 0.0 && v0 <= 1.0, InputError, "reduced volume v0 = ", v0,
                      ": must lie in (0, 1] (no closed surface encloses more volume than the sphere of its area)");
        LIMSURF_CHECK(v0 >= min_reduced_volume, InputError, "reduced volume v0 = ", v0, ": must be at least ",
                      min_reduced_volume, " (below it the volume constraint, scaled by V0, is not representable)");
        problem.volume = volume_from_reduced(v0, request.area);
    } else {
        const double v0 = *request.volume / volume_from_reduced(1.0, request.area);
        LIMSURF_CHECK(*request.volume > 0.0 && v0 <= 1.0, InputError, "volume V0 = ", *request.volume,
                      ": must lie in (0, ", volume_from_reduced(1.0, request.area),
                      "], the volume of the sphere of area A0 (reduced volume ", v0, ")");
        LIMSURF_CHECK(v0 >= min_reduced_volume, InputError, "volume V0 = ", *request.volume, ": its reduced volume ",
                      v0, " must be at least ", min_reduced_volume,
                      " (below it the volume constraint, scaled by V0, is not representable)");
        problem.volume = request.volume;
    }
    if (request.reduced_mean_curvature) {
        problem.mean_curvature = mean_curvature_from_reduced(*request.reduced_mean_curvature, request.area);
    } else {
        problem.mean_curvature = request.mean_curvature;
    }
    if (request.spontaneous_curvature) {
        const double h0 = *request.spontaneous_curvature;
        LIMSURF_CHECK(std::isfinite(h0 * h0 * request.area), InputError, "spontaneous curvature H0 = ", h0,
                      ": H0² A0 overflows (give H0 in the units of the mesh: the round sphere of area A0 has H = ",
                      std::sqrt(4.0 * std::numbers::pi / request.area), ")");
        problem.objective = MembraneObjective::Helfrich;
        problem.spontaneous_curvature = *request.spontaneous_curvature;
    }
    return problem;
}

Points scale_to_area(const ShapeFunctionals& functionals, const Points& X, double area, double* factor) {
    LIMSURF_CHECK(std::isfinite(area) && area > 0.0, InputError, "area A0 = ", area, ": must be positive");
    const double current = functionals.evaluate(X).area;
    LIMSURF_CHECK(std::isfinite(current) && current > 0.0, NumericalError, "the initial guess has limit area ", current,
                  ": cannot scale it to area ", area);
    const double s = std::sqrt(area / current);
    if (factor != nullptr) {
        *factor = s;
    }
    const Eigen::RowVector3d centroid = X.colwise().mean();
    Points scaled = (X.rowwise() - centroid) * s;
    scaled.rowwise() += centroid;
    return scaled;
}

double max_relative_residual(const MembraneProblem& problem, const MembraneResult& result) noexcept {
    double worst = std::abs(result.area_residual) / problem.area;
    if (problem.volume) {
        worst = std::max(worst, std::abs(result.volume_residual) / volume_from_reduced(1.0, problem.area));
    }
    if (problem.mean_curvature) {
        worst =
            std::max(worst, std::abs(result.mean_curvature_residual) / mean_curvature_from_reduced(1.0, problem.area));
    }
    if (problem.willmore_bound) {
        worst = std::max(worst, result.willmore_excess / *problem.willmore_bound);
    }
    return worst;
}

MembraneRun solve_membrane_problem(const ShapeFunctionals& functionals, const Points& initial,
                                   const MembraneRequest& request, const MembraneProgress& progress) {
    MembraneRun run;
    run.problem = membrane_problem(request);  // before any work: a bad request fails fast
    LIMSURF_CHECK(membrane_solver_available(), UnsupportedError,
                  "membrane problems need Ipopt: rebuild limsurf with coinor-libipopt-dev installed");
    const Points start = scale_to_area(functionals, initial, request.area, &run.scale);
    run.initial_area = request.area / (run.scale * run.scale);
    // Once the caller said stop, every later stage is stopped at its first iteration without asking
    // again: the caller is not called back after it said stop (or, from Python, raised).
    bool stopped = false;
    MembraneProgress latched;
    if (progress) {
        latched = [&progress, &stopped](MembraneStage stage, const MembraneIteration& it) {
            stopped = stopped || !progress(stage, it);
            return !stopped;
        };
    }
    const Points reached =
        continue_towards(functionals, start, run.problem, request, latched, stopped, run.continuation);
    run.shape =
        minimize_membrane(functionals, reached, run.problem, stage_options(request, MembraneStage::Shape, latched));
    if (!request.regularize_harmonic || !run.shape.converged) {
        return run;  // (3.12) starts from a minimiser of (3.1): not from wherever an unfinished solve stopped
    }
    MembraneProblem harmonic = run.problem;
    harmonic.objective = MembraneObjective::Harmonic;
    harmonic.willmore_bound = run.shape.values.willmore + *request.regularize_harmonic;
    run.regularization_problem = harmonic;
    run.regularization = minimize_membrane(functionals, run.shape.positions, harmonic,
                                           stage_options(request, MembraneStage::Regularization, latched));
    return run;
}

}  // namespace limsurf
