// Constrained shape optimisation of biomembranes with hard constraints: the Canham and Helfrich
// problems (3.1) and the parameterisation regularisation (3.12) of c2g0-sphere-scheme-biomembranes
// §3, solved by Ipopt (interior point, exact constraint Jacobians, a limited-memory quasi-Newton
// Hessian or the exact one; docs/membrane.md says why Ipopt and not NLopt).
//
//   Canham      min W           s.t. A = A0, V = V0
//   Helfrich    min ∫(H − H0)²  s.t. A = A0, V = V0 [, M = M0]
//   (3.12)      min E (harmonic) s.t. A = A0, V = V0 [, M = M0], W ≤ W_bound
//
// The unknowns are the 3 #V control coordinates. The objective and constraints are invariant under
// the six rigid motions, so their Hessians are singular along them; the limited-memory Hessian
// keeps the KKT system regular (with the exact one, Ipopt's inertia correction does), and the
// rigid motions are left free (the result is defined up to them). Every functional comes from one
// ShapeFunctionals::evaluate() per iterate (and, with the exact Hessian, one hessian()).
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "limsurf/core/types.h"
#include "limsurf/membrane/shape_functionals.h"

namespace limsurf {

/// What a membrane problem minimises.
enum class MembraneObjective {
    Willmore,  ///< W = ∫ H² dA (Canham; Helfrich with H0 = 0)
    Helfrich,  ///< ∫ (H − H0)² dA with H0 = MembraneProblem::spontaneous_curvature
    Harmonic   ///< the harmonic energy E of the parameterisation (3.12)
};

/// "willmore", "helfrich" or "harmonic" (the CLI's and Python's name of the objective).
[[nodiscard]] const char* to_string(MembraneObjective objective) noexcept;

/// The range of the area A0 a problem may ask for: a start scaled to A0 (as solve_membrane_problem scales it), so its
/// coordinates are ~ sqrt(A0) and V ~ A0^(3/2); beyond these the volume, the gradients or the solver's scaled
/// quantities leave double precision (state the problem in other units).
inline constexpr double min_membrane_area = 1e-100;
inline constexpr double max_membrane_area = 1e100;
/// The least reduced volume V0 / volume_from_reduced(1, A0) a problem may ask for: the volume constraint is scaled by
/// V0, and a subnormal V0 made that scale infinite (a crash inside the solver's linear algebra). Far below any shape of
/// the phase diagrams (Fig. 7 of the paper has v0 = 0.18).
inline constexpr double min_reduced_volume = 1e-6;

/// The problem: an objective and hard constraints.
struct MembraneProblem {
    MembraneObjective objective = MembraneObjective::Willmore;
    double spontaneous_curvature = 0.0;    ///< H0 of the Helfrich objective
    double area = 0.0;                     ///< A0 in [min_membrane_area, max_membrane_area] (always constrained)
    std::optional<double> volume;          ///< V0 (reduced volume in [min_reduced_volume, 1]), when constrained
    std::optional<double> mean_curvature;  ///< M0, when constrained
    std::optional<double> willmore_bound;  ///< W ≤ bound, when given (3.12)
};

/// One solver iteration, for progress reports.
struct MembraneIteration {
    int iteration = 0;
    double objective = 0.0;
    double constraint_violation = 0.0;  ///< max |constraint residual| relative to its target (inequality: excess)
    double dual_infeasibility = 0.0;
    double step = 0.0;  ///< the primal step size α
    /// An iteration of Ipopt's feasibility restoration phase, entered when the line search finds no
    /// acceptable step. Its iterations continue the numbering; the regular iteration that leaves it
    /// repeats the number of its last one (Ipopt's own log: "8r", then "8").
    bool restoration = false;
    /// A step of Ipopt's watchdog procedure: after several shortened steps, full steps are taken on
    /// trial without the filter's test (so beyond its cap on the constraint violation); when they
    /// make no progress within a few iterations, Ipopt returns to the point before them.
    bool watchdog = false;
};

/// How the solver takes the second derivatives of the Lagrangian.
enum class MembraneHessian {
    /// Ipopt's limited-memory BFGS from the gradients (20 pairs): cheap per iteration, for any size.
    LimitedMemory,
    /// ShapeFunctionals::hessian of the Lagrangian at every iteration: Newton steps, much fewer
    /// iterations on small meshes where each costs more (docs/membrane.md, "Exact Hessians").
    Exact
};

/// "limited-memory" or "exact" (the CLI's and Python's name).
[[nodiscard]] const char* to_string(MembraneHessian hessian) noexcept;
/// The MembraneHessian named @p name, as to_string() names it.
/// @throws InputError for another name (naming the two)
[[nodiscard]] MembraneHessian parse_membrane_hessian(const std::string& name);

/// Options of minimize_membrane().
struct MembraneOptions {
    MembraneHessian hessian = MembraneHessian::LimitedMemory;
    int max_iterations = 1000;
    double tolerance = 1e-8;             ///< Ipopt's KKT tolerance (tol, on its scaled NLP error)
    double constraint_tolerance = 1e-9;  ///< relative to the constraint's target
    /// When > 0, also stop (converged) once the objective's relative change has stayed below this
    /// for 15 consecutive iterations with the constraints satisfied: the quasi-Newton iteration
    /// reaches W to 1e-6 long before the KKT tolerance, whose last digits move the control
    /// points tangentially (nearly flat directions of W). 0: only the KKT tolerance stops.
    /// A stagnation test, not a bound on the distance to the minimum: with 1e-9, F_tetra,2 at
    /// v0 = 0.6 stops 8e-5 (relative) above the W that 1000 more iterations reach; at v0 = 0.8 on
    /// F_tetra,3, 1e-7 stops 4e-7 above it.
    double objective_tolerance = 0.0;
    /// Called after each iteration (from the calling thread); returning false stops the solver
    /// (converged = false, status "stopped by the caller"); what it throws is rethrown.
    std::function<bool(const MembraneIteration&)> on_iteration;
};

/// The result of minimize_membrane().
struct MembraneResult {
    Points positions;                      ///< the control points reached
    ShapeValues values;                    ///< every functional there (with the gradients of the problem's terms)
    double objective = 0.0;                ///< the objective's value there
    double area_residual = 0.0;            ///< A − A0
    double volume_residual = 0.0;          ///< V − V0 (0 when not constrained)
    double mean_curvature_residual = 0.0;  ///< M − M0 (0 when not constrained)
    double willmore_excess = 0.0;          ///< max(0, W − bound) (0 when not constrained)
    /// Ipopt reached its tolerance (or the objective tolerance, when one was given) and every
    /// constraint holds to constraint_tolerance relative to its target. Ipopt's other
    /// "acceptable level" stops come back with converged = false and say so in status.
    bool converged = false;
    /// Not converged, yet positions hold every constraint to constraint_tolerance: the solve stopped
    /// short (e.g. at max_iterations) and the point of lowest objective it met within 1e-3 of the
    /// constraints (or the point it stopped at, when within 0.1 of them), projected onto them, is
    /// returned instead of its last iterate: a point that holds the constraints, not a minimiser.
    bool projected = false;
    int iterations = 0;
    double seconds = 0.0;
    std::string status;  ///< Ipopt's status, in words
};

/// @brief Solves the membrane problem from the control points @p initial.
/// @details Each constraint reaches Ipopt as (value − target) / |target| (M0 = 0: divided by the
///   M of the sphere of area A0), so constraint_tolerance is relative; W ≤ bound is an inequality.
///   Never returns NaN positions: when the solver fails, the last point where every functional was
///   finite comes back with converged = false and the status saying why — or, when the solve met
///   points near the constraints, the best of them projected onto them (MembraneResult::projected).
///   A trial point where the surface degenerates (NumericalError from ShapeFunctionals) makes Ipopt
///   shorten the step; it is not an error. Ipopt's MUMPS is not reentrant: concurrent calls are
///   serialised.
/// @throws InputError for an infeasible or unrepresentable problem (A0 outside [min_membrane_area,
///   max_membrane_area], V0 <= 0, a reduced volume above 1 (V0 above the volume of the sphere of
///   area A0) or below min_reduced_volume, a Willmore bound <= 0, non-finite data), initial
///   points of the wrong shape or not finite, non-positive tolerances
/// @throws NumericalError when the surface of @p initial is degenerate (or a functional is not finite there)
/// @throws UnsupportedError when limsurf was built without Ipopt (membrane_solver_available())
[[nodiscard]] MembraneResult minimize_membrane(const ShapeFunctionals& functionals, const Points& initial,
                                               const MembraneProblem& problem, const MembraneOptions& options = {});

/// True when limsurf was built with Ipopt (coinor-libipopt-dev).
[[nodiscard]] bool membrane_solver_available() noexcept;

/// V0 of reduced volume @p reduced_volume at area @p area: v (4π/3)(A/4π)^(3/2).
[[nodiscard]] double volume_from_reduced(double reduced_volume, double area) noexcept;
/// M0 of reduced total mean curvature @p reduced: m 4π (A/4π)^(1/2).
[[nodiscard]] double mean_curvature_from_reduced(double reduced, double area) noexcept;

}  // namespace limsurf
