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

}  // namespace

const char* to_string(MembraneStage stage) noexcept {
    return stage == MembraneStage::Shape ? "shape" : "regularization";
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
    run.shape =
        minimize_membrane(functionals, start, run.problem, stage_options(request, MembraneStage::Shape, progress));
    if (!request.regularize_harmonic || !run.shape.converged) {
        return run;  // (3.12) starts from a minimiser of (3.1): not from wherever an unfinished solve stopped
    }
    MembraneProblem harmonic = run.problem;
    harmonic.objective = MembraneObjective::Harmonic;
    harmonic.willmore_bound = run.shape.values.willmore + *request.regularize_harmonic;
    run.regularization_problem = harmonic;
    run.regularization = minimize_membrane(functionals, run.shape.positions, harmonic,
                                           stage_options(request, MembraneStage::Regularization, progress));
    return run;
}

}  // namespace limsurf
