// The membrane problems (3.1) and (3.12) of c2g0-sphere-scheme-biomembranes §3 as Ipopt NLPs
// (the header states the problems). The unknowns are the control coordinates, x[3 i + c] = X(i, c).
// Ipopt sees every constraint as its residual divided by a scale, (value − target) / scale, with
// scale = |target| (for M0 = 0: the M of the sphere of area A0), so that its absolute
// constr_viol_tol is MembraneOptions::constraint_tolerance relative to the target. One
// ShapeFunctionals::evaluate() per new x serves the objective, the constraints and both
// derivatives.
#include "limsurf/membrane/shape_optimization.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <exception>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#ifdef LIMSURF_HAVE_IPOPT
#include <coin/IpIpoptApplication.hpp>
#include <coin/IpIpoptData.hpp>
#include <coin/IpTNLP.hpp>
#endif

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

void validate(const ShapeFunctionals& functionals, const Points& initial, const MembraneProblem& problem,
              const MembraneOptions& options) {
    LIMSURF_CHECK(std::isfinite(problem.area) && problem.area > 0.0, InputError,
                  "the area A0 must be positive and finite, not ", problem.area);
    LIMSURF_CHECK(problem.area >= min_membrane_area && problem.area <= max_membrane_area, InputError,
                  "the area A0 = ", problem.area, " must lie in [", min_membrane_area, ", ", max_membrane_area,
                  "] (state the problem in other units)");
    if (problem.volume) {
        const double v0 = *problem.volume;
        const double sphere = volume_from_reduced(1.0, problem.area);
        LIMSURF_CHECK(std::isfinite(v0) && v0 > 0.0, InputError, "the volume V0 must be positive and finite, not ", v0);
        LIMSURF_CHECK(v0 <= sphere, InputError, "the volume V0 = ", v0,
                      " exceeds that of the sphere of area A0 = ", problem.area, " (", sphere, "): reduced volume ",
                      v0 / sphere, " > 1 violates the isoperimetric inequality");
        LIMSURF_CHECK(v0 / sphere >= min_reduced_volume, InputError, "the volume V0 = ", v0, " is below ",
                      min_reduced_volume, " times that of the sphere of area A0 (reduced volume ", v0 / sphere,
                      "): the volume constraint, scaled by V0, is not representable");
    }
    if (problem.mean_curvature) {
        LIMSURF_CHECK(std::isfinite(*problem.mean_curvature), InputError, "the mean curvature M0 must be finite");
    }
    if (problem.willmore_bound) {
        const double bound = *problem.willmore_bound;
        LIMSURF_CHECK(std::isfinite(bound) && bound > 0.0, InputError,
                      "the Willmore bound must be positive and finite, not ", bound);
    }
    LIMSURF_CHECK(std::isfinite(problem.spontaneous_curvature), InputError, "the spontaneous curvature must be finite");
    LIMSURF_CHECK(initial.rows() == functionals.num_vertices(), InputError, "the initial control points have ",
                  initial.rows(), " rows, the mesh has ", functionals.num_vertices(), " vertices");
    LIMSURF_CHECK(initial.allFinite(), InputError, "the initial control points have a non-finite coordinate");
    LIMSURF_CHECK(options.max_iterations >= 0, InputError, "max_iterations must be >= 0, not ", options.max_iterations);
    LIMSURF_CHECK(options.tolerance > 0.0 && options.constraint_tolerance > 0.0 && options.objective_tolerance >= 0.0,
                  InputError, "the tolerances must be positive (the objective tolerance >= 0), not ", options.tolerance,
                  ", ", options.constraint_tolerance, " and ", options.objective_tolerance);
}

#ifdef LIMSURF_HAVE_IPOPT

/// One hard constraint: (value − target) / scale, = 0 or (upper_only) <= 0.
struct Constraint {
    ShapeFunctional functional = ShapeFunctional::Area;
    double target = 0.0;
    double scale = 1.0;
    bool upper_only = false;
};

/// The constraints of @p problem. The Willmore bound of (3.12) is scaled by its margin at the start,
/// W0 + ε − W(X0) = ε when the start is the solution of (3.1), not by the bound: relative to W0 the
/// margin is ~1e-4 (ε = 0.003, W0 ≈ 28), below Ipopt's bound_push (1e-2) that places the slack
/// inside the bound, and Ipopt then started outside the feasible set and lost the other constraints
/// for good (the (3.12) of Fig. 13: A, V, M violated by O(1) after 1500 iterations). Without a
/// start (only the functionals are asked for) the scale is the bound.
std::vector<Constraint> constraints_of(const MembraneProblem& problem, const ShapeValues* start = nullptr) {
    std::vector<Constraint> out{{ShapeFunctional::Area, problem.area, problem.area, false}};
    if (problem.volume) {
        out.push_back({ShapeFunctional::Volume, *problem.volume, *problem.volume, false});
    }
    if (problem.mean_curvature) {
        const double m0 = *problem.mean_curvature;
        // |M0|, unless it is so small next to the sphere's M that 1/|M0| leaves double precision
        // (a subnormal M0 crashed the solver's linear algebra); M0 = 0 has the sphere's scale.
        const double sphere = mean_curvature_from_reduced(1.0, problem.area);
        const double scale = std::abs(m0) >= 1e-6 * sphere ? std::abs(m0) : sphere;
        out.push_back({ShapeFunctional::MeanCurvature, m0, scale, false});
    }
    if (problem.willmore_bound) {
        const double bound = *problem.willmore_bound;
        const double margin = start ? bound - start->willmore : 0.0;
        out.push_back(
            {ShapeFunctional::Willmore, bound, margin > 1e-6 * std::abs(bound) ? margin : std::abs(bound), true});
    }
    return out;
}

/// The functionals whose gradients the problem needs: the objective's and the constraints'.
std::vector<ShapeFunctional> gradients_of(const MembraneProblem& problem, const std::vector<Constraint>& constraints) {
    std::vector<ShapeFunctional> out;
    auto add = [&out](ShapeFunctional f) {
        if (std::find(out.begin(), out.end(), f) == out.end()) {
            out.push_back(f);
        }
    };
    switch (problem.objective) {
    case MembraneObjective::Willmore:
        add(ShapeFunctional::Willmore);
        break;
    case MembraneObjective::Helfrich:
        add(ShapeFunctional::Willmore);
        add(ShapeFunctional::MeanCurvature);
        add(ShapeFunctional::Area);
        break;
    case MembraneObjective::Harmonic:
        add(ShapeFunctional::Harmonic);
        break;
    }
    for (const Constraint& c : constraints) {
        add(c.functional);
    }
    return out;
}

double objective_of(const MembraneProblem& problem, const ShapeValues& values) {
    switch (problem.objective) {
    case MembraneObjective::Willmore:
        return values.willmore;
    case MembraneObjective::Helfrich:
        return values.helfrich(problem.spontaneous_curvature);
    case MembraneObjective::Harmonic:
        return values.harmonic;
    }
    return 0.0;
}

Points objective_gradient(const MembraneProblem& problem, const ShapeValues& values) {
    switch (problem.objective) {
    case MembraneObjective::Willmore:
        return values.gradient_of(ShapeFunctional::Willmore);
    case MembraneObjective::Helfrich:
        return values.helfrich_gradient(problem.spontaneous_curvature);
    case MembraneObjective::Harmonic:
        return values.gradient_of(ShapeFunctional::Harmonic);
    }
    return {};
}

bool all_finite(const ShapeValues& values) {
    for (int f = 0; f < num_shape_functionals; ++f) {
        const auto functional = static_cast<ShapeFunctional>(f);
        if (!std::isfinite(values.value(functional)) || !values.gradient_of(functional).allFinite()) {
            return false;
        }
    }
    return true;
}

/// The result's residuals and objective from its values.
void fill_residuals(const MembraneProblem& problem, MembraneResult& result) {
    const ShapeValues& v = result.values;
    result.objective = objective_of(problem, v);
    result.area_residual = v.area - problem.area;
    result.volume_residual = problem.volume ? v.volume - *problem.volume : 0.0;
    result.mean_curvature_residual = problem.mean_curvature ? v.mean_curvature - *problem.mean_curvature : 0.0;
    result.willmore_excess = problem.willmore_bound ? std::max(0.0, v.willmore - *problem.willmore_bound) : 0.0;
}

/// How close to the constraints (relative, as Ipopt sees them) a point must be to be worth
/// projecting onto them when a solve stops short: (3.12) on F_tetra,4 (Fig. 13) keeps its iterates
/// within 1e-4..4e-3 for thousands of iterations while the objective falls, and from there the
/// Gauss–Newton projection takes one or two steps.
constexpr double nearly_feasible = 1e-3;
/// How close the point a solve stopped at must be to be projected: further out, the projection
/// would answer a different question (one iteration from a self-intersecting start is 0.95 away).
constexpr double near_enough_to_project = 0.1;

/// True when every constraint holds to @p tolerance relative to its scale.
bool constraints_hold(const std::vector<Constraint>& constraints, const ShapeValues& values, double tolerance) {
    return std::all_of(constraints.begin(), constraints.end(), [&](const Constraint& c) {
        const double residual = (values.value(c.functional) - c.target) / c.scale;
        return c.upper_only ? residual <= tolerance : std::abs(residual) <= tolerance;
    });
}

std::string describe(Ipopt::ApplicationReturnStatus status) {
    switch (status) {
    case Ipopt::Solve_Succeeded:
        return "solved";
    case Ipopt::Solved_To_Acceptable_Level:
        return "stopped at an acceptable point (Ipopt's acceptable_tol), short of the tolerance";
    case Ipopt::Infeasible_Problem_Detected:
        return "the constraints look infeasible (Ipopt)";
    case Ipopt::Search_Direction_Becomes_Too_Small:
        return "the search direction became too small (Ipopt)";
    case Ipopt::Diverging_Iterates:
        return "the iterates diverge (Ipopt)";
    case Ipopt::User_Requested_Stop:
        return "stopped by the caller";
    case Ipopt::Feasible_Point_Found:
        return "a feasible point was found (Ipopt)";
    case Ipopt::Maximum_Iterations_Exceeded:
        return "the maximum number of iterations was reached";
    case Ipopt::Restoration_Failed:
        return "Ipopt's feasibility restoration failed";
    case Ipopt::Error_In_Step_Computation:
        return "Ipopt could not compute a step";
    case Ipopt::Maximum_CpuTime_Exceeded:
        return "Ipopt's CPU time limit was reached";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
        return "not enough degrees of freedom (Ipopt)";
    case Ipopt::Invalid_Problem_Definition:
        return "invalid problem definition (Ipopt)";
    case Ipopt::Invalid_Option:
        return "invalid Ipopt option";
    case Ipopt::Invalid_Number_Detected:
        return "Ipopt met a non-finite number";
    case Ipopt::Unrecoverable_Exception:
        return "Ipopt failed with an unrecoverable exception";
    case Ipopt::NonIpopt_Exception_Thrown:
        return "an exception escaped into Ipopt";
    case Ipopt::Insufficient_Memory:
        return "Ipopt ran out of memory";
    case Ipopt::Internal_Error:
        return "Ipopt internal error";
    }
    return "unknown Ipopt status";
}

/// The NLP Ipopt solves. Callbacks never throw: an exception from ShapeFunctionals at a trial
/// point is kept and the callback returns false, which makes Ipopt shorten the step; any other
/// exception (and one from on_iteration) stops the solver and is rethrown after Solve.
class MembraneNlp final : public Ipopt::TNLP {
  public:
    MembraneNlp(const ShapeFunctionals& functionals, const Points& initial, ShapeValues initial_values,
                const MembraneProblem& problem, const MembraneOptions& options)
        : functionals_(functionals), problem_(problem), options_(options),
          constraints_(constraints_of(problem, &initial_values)), gradients_(gradients_of(problem, constraints_)),
          initial_(initial), current_(initial), values_(std::move(initial_values)), good_(initial),
          good_values_(values_) {}

    bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g, Ipopt::Index& nnz_h_lag,
                      IndexStyleEnum& index_style) override {
        n = num_variables();
        m = static_cast<Ipopt::Index>(constraints_.size());
        nnz_jac_g = n * m;  // dense rows: every functional depends on every control point
        nnz_h_lag = 0;      // limited-memory quasi-Newton Hessian, or the exact one's lower triangle
        if (options_.hessian == MembraneHessian::Exact) {
            try {
                hessian_ = functionals_.hessian_pattern();
            } catch (...) {
                fatal_ = std::current_exception();
                return false;
            }
            nnz_h_lag = lower_triangle_size();
        }
        index_style = C_STYLE;
        return true;
    }

    bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m, Ipopt::Number* g_l,
                         Ipopt::Number* g_u) override {
        std::fill(x_l, x_l + n, -2e19);  // below nlp_lower_bound_inf: free
        std::fill(x_u, x_u + n, 2e19);
        for (Ipopt::Index k = 0; k < m; ++k) {
            g_l[k] = constraints_[static_cast<std::size_t>(k)].upper_only ? -2e19 : 0.0;
            g_u[k] = 0.0;
        }
        return true;
    }

    bool get_starting_point(Ipopt::Index, bool init_x, Ipopt::Number* x, bool init_z, Ipopt::Number*, Ipopt::Number*,
                            Ipopt::Index, bool init_lambda, Ipopt::Number*) override {
        if (init_z || init_lambda || !init_x) {
            return false;
        }
        to_x(initial_, x);
        return true;
    }

    bool eval_f(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Number& obj_value) override {
        if (!update(x, new_x)) {
            return false;
        }
        obj_value = objective_of(problem_, values_);
        return true;
    }

    bool eval_grad_f(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Number* grad_f) override {
        if (!update(x, new_x)) {
            return false;
        }
        try {
            to_x(objective_gradient(problem_, values_), grad_f);
        } catch (...) {
            fatal_ = std::current_exception();
            return false;
        }
        return true;
    }

    bool eval_g(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Index m, Ipopt::Number* g) override {
        if (!update(x, new_x)) {
            return false;
        }
        for (Ipopt::Index k = 0; k < m; ++k) {
            const Constraint& c = constraints_[static_cast<std::size_t>(k)];
            g[k] = (values_.value(c.functional) - c.target) / c.scale;
        }
        return true;
    }

    bool eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m, Ipopt::Index,
                    Ipopt::Index* i_row, Ipopt::Index* j_col, Ipopt::Number* values) override {
        if (values == nullptr) {  // the structure: row k, column j at k n + j
            for (Ipopt::Index k = 0; k < m; ++k) {
                for (Ipopt::Index j = 0; j < n; ++j) {
                    i_row[k * n + j] = k;
                    j_col[k * n + j] = j;
                }
            }
            return true;
        }
        if (!update(x, new_x)) {
            return false;
        }
        for (Ipopt::Index k = 0; k < m; ++k) {
            const Constraint& c = constraints_[static_cast<std::size_t>(k)];
            to_x(values_.gradient_of(c.functional) / c.scale, values + static_cast<std::ptrdiff_t>(k) * n);
        }
        return true;
    }

    bool eval_h(Ipopt::Index, const Ipopt::Number* x, bool new_x, Ipopt::Number obj_factor, Ipopt::Index m,
                const Ipopt::Number* lambda, bool, Ipopt::Index, Ipopt::Index* i_row, Ipopt::Index* j_col,
                Ipopt::Number* values) override {
        if (values == nullptr) {  // the structure: the pattern's lower triangle, row by row
            Ipopt::Index k = 0;
            for_lower_triangle(hessian_, [&](Ipopt::Index row, Ipopt::Index col, double) {
                i_row[k] = row;
                j_col[k] = col;
                ++k;
            });
            return true;
        }
        if (!update(x, new_x)) {
            return false;
        }
        return guarded([&] {
            functionals_.hessian(current_, lagrangian_coefficients(obj_factor, lambda, m), hessian_);
            Ipopt::Index k = 0;
            for_lower_triangle(hessian_, [&](Ipopt::Index, Ipopt::Index, double value) { values[k++] = value; });
        });
    }

    bool intermediate_callback(Ipopt::AlgorithmMode mode, Ipopt::Index iter, Ipopt::Number obj_value,
                               Ipopt::Number inf_pr, Ipopt::Number inf_du, Ipopt::Number, Ipopt::Number, Ipopt::Number,
                               Ipopt::Number, Ipopt::Number alpha_pr, Ipopt::Index, const Ipopt::IpoptData* ip_data,
                               Ipopt::IpoptCalculatedQuantities*) override {
        iterations_ = iter;
        if (fatal_) {
            return false;
        }
        if (!options_.on_iteration) {
            return true;
        }
        try {
            // Ipopt marks the step of each iteration by a character (its log's alpha_pr column): 'w'
            // for a step taken by the watchdog procedure.
            const bool watchdog = ip_data != nullptr && ip_data->info_alpha_primal_char() == 'w';
            const bool go_on = options_.on_iteration(MembraneIteration{iter, obj_value, inf_pr, inf_du, alpha_pr,
                                                                       mode == Ipopt::RestorationPhaseMode, watchdog});
            stopped_by_caller_ = stopped_by_caller_ || !go_on;
            return go_on;
        } catch (...) {
            fatal_ = std::current_exception();
            return false;
        }
    }

    void finalize_solution(Ipopt::SolverReturn, Ipopt::Index, const Ipopt::Number* x, const Ipopt::Number*,
                           const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*, const Ipopt::Number*,
                           Ipopt::Number, const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) override {
        if (x == nullptr) {
            return;
        }
        Points X(functionals_.num_vertices(), 3);
        from_x(x, X);
        if (X.allFinite()) {
            final_ = std::move(X);
        }
    }

    /// The control points to return and their values: Ipopt's final point when every functional
    /// is finite there, else the last point where they were.
    [[nodiscard]] std::pair<Points, ShapeValues> result_point() const {
        if (final_.size() > 0 && final_ != good_) {
            try {
                ShapeValues values = functionals_.evaluate(final_, gradients_);
                if (all_finite(values)) {
                    return {final_, std::move(values)};
                }
            } catch (const NumericalError&) {  // degenerate there: fall back to the last good point
            }
        }
        return {good_, good_values_};
    }

    /// Points evaluated within nearly_feasible of every constraint (scaled as Ipopt sees them),
    /// lowest objective first: the lowest of all, then up to 16 earlier ones, about 1 % apart — a
    /// projection that fails from the last of a run's points (a surface on its way to degenerate)
    /// can fall back on an earlier one. Empty when there was none.
    [[nodiscard]] std::vector<const Points*> nearly_feasible_points() const {
        std::vector<const Points*> out;
        for (auto record = records_.rbegin(); record != records_.rend(); ++record) {
            out.push_back(&record->second);
        }
        return out;
    }
    [[nodiscard]] const std::exception_ptr& fatal() const noexcept { return fatal_; }
    [[nodiscard]] const std::exception_ptr& trial_failure() const noexcept { return trial_failure_; }
    [[nodiscard]] bool stopped_by_caller() const noexcept { return stopped_by_caller_; }
    [[nodiscard]] int iterations() const noexcept { return iterations_; }
    [[nodiscard]] const std::vector<Constraint>& constraints() const noexcept { return constraints_; }

  private:
    [[nodiscard]] Ipopt::Index num_variables() const {
        return static_cast<Ipopt::Index>(3 * functionals_.num_vertices());
    }

    /// The weights of the functionals in the Lagrangian σ f + Σ λ_k g_k (g_k = (F_k − target) / scale).
    [[nodiscard]] ShapeCoefficients lagrangian_coefficients(double sigma, const Ipopt::Number* lambda,
                                                            Ipopt::Index m) const {
        ShapeCoefficients c{};
        const auto add = [&c](ShapeFunctional f, double weight) { c[static_cast<std::size_t>(f)] += weight; };
        const double h0 = problem_.spontaneous_curvature;
        switch (problem_.objective) {
        case MembraneObjective::Willmore:
            add(ShapeFunctional::Willmore, sigma);
            break;
        case MembraneObjective::Helfrich:  // W − 2 H0 M + H0² A
            add(ShapeFunctional::Willmore, sigma);
            add(ShapeFunctional::MeanCurvature, -2.0 * h0 * sigma);
            add(ShapeFunctional::Area, h0 * h0 * sigma);
            break;
        case MembraneObjective::Harmonic:
            add(ShapeFunctional::Harmonic, sigma);
            break;
        }
        for (Ipopt::Index k = 0; k < m; ++k) {
            const Constraint& constraint = constraints_[static_cast<std::size_t>(k)];
            add(constraint.functional, lambda[k] / constraint.scale);
        }
        return c;
    }

    /// Calls @p visit(row, column, value) for the entries of @p H on and below its diagonal, row by row.
    template <class Visit>
    static void for_lower_triangle(const SparseMatrix& H, Visit&& visit) {
        for (Eigen::Index row = 0; row < H.outerSize(); ++row) {
            for (SparseMatrix::InnerIterator it(H, row); it && it.col() <= row; ++it) {
                visit(static_cast<Ipopt::Index>(row), static_cast<Ipopt::Index>(it.col()), it.value());
            }
        }
    }

    [[nodiscard]] Ipopt::Index lower_triangle_size() const {
        Ipopt::Index count = 0;
        for_lower_triangle(hessian_, [&count](Ipopt::Index, Ipopt::Index, double) { ++count; });
        return count;
    }

    static void to_x(const Points& X, Ipopt::Number* x) {
        for (Index i = 0; i < X.rows(); ++i) {
            for (int c = 0; c < 3; ++c) {
                x[3 * i + c] = X(i, c);
            }
        }
    }

    static void from_x(const Ipopt::Number* x, Points& X) {
        for (Index i = 0; i < X.rows(); ++i) {
            for (int c = 0; c < 3; ++c) {
                X(i, c) = x[3 * i + c];
            }
        }
    }

    /// Keeps current_ when @p objective is the lowest so far: the last record is always the lowest;
    /// it replaces its predecessor unless that one lies 1 % above the record before it.
    void record(double objective) {
        if (!records_.empty() && objective >= records_.back().first) {
            return;
        }
        const std::size_t n = records_.size();
        if (n >= 2 && objective >= 0.99 * records_[n - 2].first) {
            records_.back() = {objective, current_};
            return;
        }
        records_.emplace_back(objective, current_);
        if (records_.size() > 17) {  // the lowest and 16 earlier ones
            records_.pop_front();
        }
    }

    /// Runs @p work; false when it threw: a NumericalError (a degenerate trial point, which makes
    /// Ipopt cut the step) is kept in trial_failure_, anything else in fatal_ (rethrown after Solve).
    template <class Work>
    bool guarded(Work&& work) {
        try {
            work();
        } catch (const NumericalError&) {
            trial_failure_ = std::current_exception();
            return false;
        } catch (...) {
            fatal_ = std::current_exception();
            return false;
        }
        return true;
    }

    /// Evaluates at @p x unless the cache holds it. False when the surface is degenerate there or
    /// a value is not finite (Ipopt then cuts the step), or on a fatal exception.
    bool update(const Ipopt::Number* x, bool new_x) {
        if (!new_x && valid_) {
            return true;
        }
        from_x(x, current_);
        if (valid_ && current_ == good_) {  // e.g. the initial point, evaluated before Solve
            return true;
        }
        valid_ = false;
        if (!guarded([&] { values_ = functionals_.evaluate(current_, gradients_); }) || !all_finite(values_)) {
            return false;
        }
        valid_ = true;
        good_ = current_;
        good_values_ = values_;
        if (constraints_hold(constraints_, values_, nearly_feasible)) {
            record(objective_of(problem_, values_));
        }
        return true;
    }

    const ShapeFunctionals& functionals_;
    const MembraneProblem& problem_;
    const MembraneOptions& options_;
    std::vector<Constraint> constraints_;
    std::vector<ShapeFunctional> gradients_;
    Points initial_;
    Points current_;      // the point of values_
    ShapeValues values_;  // the cache, valid_ when it belongs to current_
    bool valid_ = true;
    Points good_;  // the last point where every functional was finite, and its values
    ShapeValues good_values_;
    Points final_;                                   // Ipopt's final point (empty until finalize_solution)
    std::deque<std::pair<double, Points>> records_;  // (objective, point): nearly_feasible_points()
    SparseMatrix hessian_;  // MembraneHessian::Exact: the last Hessian (its pattern, fixed, is Ipopt's structure)
    std::exception_ptr trial_failure_;
    std::exception_ptr fatal_;
    bool stopped_by_caller_ = false;
    int iterations_ = 0;
};

void set_options(Ipopt::IpoptApplication& app, const MembraneProblem& problem, const MembraneOptions& options) {
    const Ipopt::SmartPtr<Ipopt::OptionsList> o = app.Options();
    o->SetIntegerValue("print_level", 0);
    o->SetStringValue("sb", "yes");
    o->SetStringValue("hessian_approximation", to_string(options.hessian));  // Ipopt's names
    o->SetNumericValue("tol", options.tolerance);
    // The constraints are scaled to their targets (MembraneNlp), so this is relative.
    o->SetNumericValue("constr_viol_tol", options.constraint_tolerance);
    o->SetIntegerValue("max_iter", options.max_iterations);
    // The default scalar1 start of the quasi-Newton matrix stalls at a dual infeasibility of ~1e-4 on
    // the Canham problem (the Willmore Hessian is a fourth-order operator); scalar2 with 20 pairs
    // reaches tol = 1e-8 (F_tetra,2, v0 = 0.9: 286 iterations instead of > 3000).
    o->SetStringValue("limited_memory_initialization", "scalar2");
    o->SetIntegerValue("limited_memory_max_history", 20);
    // Ipopt relaxes inequality bounds by bound_relax_factor (default 1e-8, relative here): keep
    // the Willmore bound's relaxation within the constraint tolerance.
    o->SetNumericValue("bound_relax_factor", 0.1 * options.constraint_tolerance);
    // Ipopt may stop at an "acceptable" point. Its iterates' constraint violation wanders between
    // 1e-13 and 1e-8 once W has settled (measured on F_tetra,3), so the acceptable test allows 100×
    // the tolerance and project_onto_constraints() then restores it.
    o->SetNumericValue("acceptable_constr_viol_tol", 100.0 * options.constraint_tolerance);
    if (options.objective_tolerance > 0.0) {
        // Stop once the objective's relative change stays below it for 15 iterations.
        o->SetNumericValue("acceptable_obj_change_tol", options.objective_tolerance);
        o->SetNumericValue("acceptable_tol", 1e20);
        o->SetNumericValue("acceptable_dual_inf_tol", 1e20);
        o->SetIntegerValue("acceptable_iter", 15);
    } else {
        o->SetIntegerValue("acceptable_iter", 0);
    }
    if (problem.objective == MembraneObjective::Harmonic) {
        // Ipopt's filter accepts trial points with a scaled constraint violation up to
        // theta_max = theta_max_fact max(1, θ(x0)), by default 1e4. (3.12) starts at a minimiser of
        // (3.1), θ(x0) ~ 1e-10, and E falls far faster off the constraints than on them (towards the
        // round sphere's 8π): with the default, the iterates of Fig. 13's problem on F_tetra,3 left
        // the constraints at the first iteration (violation 263; up to 5e5 later) and the lowest
        // point within 1e-3 of them in 3000 iterations was E0 − 2 %. Capped at 1e-1 they stay
        // within the cap and E falls (80.86 -> 48.3 in those 3000 iterations); 1e-2 pinned
        // F_tetra,4's iterates at the cap with steps of 1e-5 until Ipopt's restoration phase took
        // over (docs/membrane.md). The watchdog's trial steps are the exception: taken without the
        // filter's test, they may leave the cap (violation 9e4 on F_tetra,2), and when the next
        // ones make no progress Ipopt goes back to the point before them (MembraneIteration::watchdog).
        o->SetNumericValue("theta_max_fact", 1e-1);
    }
}

/// Gauss–Newton steps X ← X − Jᵀ(JJᵀ)⁻¹c onto the violated constraints (at most 4 rows, so JJᵀ is
/// tiny): the minimum-norm correction, which moves the objective only by O(|c|). Returns the
/// number of steps taken; stops when every constraint holds to @p tolerance or after 8 steps.
int project_onto_constraints(const ShapeFunctionals& functionals, const std::vector<Constraint>& constraints,
                             const std::vector<ShapeFunctional>& gradients, double tolerance, Points& X,
                             ShapeValues& values) {
    for (const Constraint& c : constraints) {
        if (values.gradient_of(c.functional).rows() != X.rows()) {  // the point came without them
            values = functionals.evaluate(X, gradients);
            break;
        }
    }
    for (int step = 0; step < 8; ++step) {
        if (constraints_hold(constraints, values, tolerance)) {
            return step;
        }
        std::vector<const Constraint*> active;
        for (const Constraint& c : constraints) {
            if (!c.upper_only || values.value(c.functional) > c.target) {
                active.push_back(&c);
            }
        }
        const auto m = static_cast<Eigen::Index>(active.size());
        Eigen::MatrixXd J(m, X.size());
        Eigen::VectorXd residual(m);
        for (Eigen::Index i = 0; i < m; ++i) {
            const Constraint& c = *active[static_cast<std::size_t>(i)];
            const Points& g = values.gradient_of(c.functional);
            J.row(i) = Eigen::Map<const Eigen::RowVectorXd>(g.data(), g.size()) / c.scale;
            residual[i] = (values.value(c.functional) - c.target) / c.scale;
        }
        const Eigen::VectorXd multipliers = (J * J.transpose()).ldlt().solve(residual);
        const Eigen::VectorXd delta = -J.transpose() * multipliers;
        Points next = X + Eigen::Map<const Points>(delta.data(), X.rows(), 3);
        ShapeValues next_values = functionals.evaluate(next, gradients);
        if (!all_finite(next_values) || !next.allFinite()) {
            return step;
        }
        X = std::move(next);
        values = std::move(next_values);
    }
    return 8;
}

/// @p start projected onto the constraints, when it lies within near_enough_to_project of them and
/// the projection meets the tolerance.
std::optional<std::pair<Points, ShapeValues>> projected(const ShapeFunctionals& functionals, const MembraneNlp& nlp,
                                                        const std::vector<ShapeFunctional>& gradients,
                                                        const MembraneOptions& options, const Points& start) {
    Points X = start;
    ShapeValues values;
    try {
        values = functionals.evaluate(X, gradients);
        if (!all_finite(values) || !constraints_hold(nlp.constraints(), values, near_enough_to_project)) {
            return std::nullopt;
        }
        (void)project_onto_constraints(functionals, nlp.constraints(), gradients, options.constraint_tolerance, X,
                                       values);
    } catch (const NumericalError&) {  // degenerate on the way
        return std::nullopt;
    }
    if (!constraints_hold(nlp.constraints(), values, options.constraint_tolerance)) {
        return std::nullopt;
    }
    return std::pair{std::move(X), std::move(values)};
}

/// A solve that stopped short (no convergence, not stopped by the caller) still returns a feasible
/// point when it can: the first of its nearly feasible points (lowest objective first) that projects
/// onto the constraints, and the point Ipopt left projected likewise; the one with the lower
/// objective replaces the result (projected = true; converged stays false). Returns what was
/// projected, in words (empty when nothing could be).
std::string salvage(const ShapeFunctionals& functionals, const MembraneNlp& nlp, const MembraneProblem& problem,
                    const MembraneOptions& options, MembraneResult& result) {
    const auto gradients = gradients_of(problem, nlp.constraints());
    std::optional<std::pair<Points, ShapeValues>> chosen;
    std::string which;
    const auto candidates = nlp.nearly_feasible_points();
    for (std::size_t k = 0; k < candidates.size() && !chosen; ++k) {
        chosen = projected(functionals, nlp, gradients, options, *candidates[k]);
        if (chosen) {
            which = k == 0 ? "the point of lowest objective met within 1e-3 of the constraints"
                           : "a point met within 1e-3 of the constraints (the lower ones did not project)";
        }
    }
    if (auto last = projected(functionals, nlp, gradients, options, result.positions);
        last && (!chosen || objective_of(problem, last->second) < objective_of(problem, chosen->second))) {
        chosen = std::move(last);
        which = "the last iterate";
    }
    if (chosen) {
        std::tie(result.positions, result.values) = std::move(*chosen);
        fill_residuals(problem, result);
        result.projected = true;
    }
    return which;
}

/// The result at the point Ipopt left, with the status in words.
MembraneResult collect(const ShapeFunctionals& functionals, const MembraneNlp& nlp,
                       Ipopt::ApplicationReturnStatus status, const MembraneProblem& problem,
                       const MembraneOptions& options) {
    MembraneResult result;
    std::tie(result.positions, result.values) = nlp.result_point();
    fill_residuals(problem, result);
    result.iterations = nlp.iterations();
    const bool by_objective = status == Ipopt::Solved_To_Acceptable_Level && options.objective_tolerance > 0.0;
    const bool solved = (status == Ipopt::Solve_Succeeded || by_objective) && !nlp.stopped_by_caller();
    int projections = 0;
    if (solved) {
        projections = project_onto_constraints(functionals, nlp.constraints(), gradients_of(problem, nlp.constraints()),
                                               options.constraint_tolerance, result.positions, result.values);
        fill_residuals(problem, result);
    }
    const std::string salvaged =
        !solved && !nlp.stopped_by_caller() ? salvage(functionals, nlp, problem, options, result) : std::string();
    const bool feasible = constraints_hold(nlp.constraints(), result.values, options.constraint_tolerance);
    result.converged = solved && feasible;
    result.status = nlp.stopped_by_caller() ? "stopped by the caller"
                    : by_objective          ? "solved to the objective tolerance (KKT tolerance not reached)"
                                            : describe(status);
    if (projections > 0) {
        result.status += " (constraints restored by " + std::to_string(projections) + " projection step" +
                         (projections > 1 ? "s)" : ")");
    }
    if (result.projected) {
        result.status += "; returned " + salvaged + ", projected onto the constraints";
    }
    if (solved && !feasible) {
        result.status += ", but a constraint misses its tolerance";
    }
    if (!result.converged && nlp.trial_failure()) {
        try {
            std::rethrow_exception(nlp.trial_failure());
        } catch (const std::exception& e) {
            result.status += std::string("; the last degenerate trial point: ") + e.what();
        }
    }
    return result;
}

/// Runs Ipopt; throws what a callback could not handle, or what failed at the initial point.
MembraneResult solve(const ShapeFunctionals& functionals, const Points& initial, const MembraneProblem& problem,
                     const MembraneOptions& options) {
    const auto constraints = constraints_of(problem);
    const auto gradients = gradients_of(problem, constraints);
    // The initial point outside Ipopt: a degenerate or non-finite start is the caller's error.
    ShapeValues start = functionals.evaluate(initial, gradients);
    LIMSURF_CHECK(all_finite(start), NumericalError, "a shape functional is not finite at the initial control points");

    Ipopt::SmartPtr<MembraneNlp> nlp = new MembraneNlp(functionals, initial, std::move(start), problem, options);
    Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
    set_options(*app, problem, options);
    Ipopt::ApplicationReturnStatus status = app->Initialize("");  // no ipopt.opt from the working directory
    LIMSURF_CHECK(status == Ipopt::Solve_Succeeded, NumericalError, "Ipopt did not initialise: ", describe(status));
    {
        // Ipopt's MUMPS keeps global state: one solve at a time in this process.
        static std::mutex ipopt_mutex;
        const std::lock_guard<std::mutex> lock(ipopt_mutex);
        status = app->OptimizeTNLP(Ipopt::SmartPtr<Ipopt::TNLP>(Ipopt::GetRawPtr(nlp)));
    }
    if (nlp->fatal()) {
        std::rethrow_exception(nlp->fatal());
    }

    return collect(functionals, *nlp, status, problem, options);
}

#endif

}  // namespace

double volume_from_reduced(double reduced_volume, double area) noexcept {
    return reduced_volume * (4.0 * std::numbers::pi / 3.0) * std::pow(area / (4.0 * std::numbers::pi), 1.5);
}

double mean_curvature_from_reduced(double reduced, double area) noexcept {
    return reduced * 4.0 * std::numbers::pi * std::sqrt(area / (4.0 * std::numbers::pi));
}

const char* to_string(MembraneHessian hessian) noexcept {
    return hessian == MembraneHessian::Exact ? "exact" : "limited-memory";
}

MembraneHessian parse_membrane_hessian(const std::string& name) {
    for (const MembraneHessian h : {MembraneHessian::LimitedMemory, MembraneHessian::Exact}) {
        if (name == to_string(h)) {
            return h;
        }
    }
    throw InputError("unknown Hessian '" + name + "' (limited-memory, exact)");
}

const char* to_string(MembraneObjective objective) noexcept {
    switch (objective) {
    case MembraneObjective::Willmore:
        return "willmore";
    case MembraneObjective::Helfrich:
        return "helfrich";
    case MembraneObjective::Harmonic:
        return "harmonic";
    }
    return "unknown";
}

bool membrane_solver_available() noexcept {
#ifdef LIMSURF_HAVE_IPOPT
    return true;
#else
    return false;
#endif
}

MembraneResult minimize_membrane(const ShapeFunctionals& functionals, const Points& initial,
                                 const MembraneProblem& problem, const MembraneOptions& options) {
    validate(functionals, initial, problem, options);
#ifdef LIMSURF_HAVE_IPOPT
    const auto start = std::chrono::steady_clock::now();
    MembraneResult result = solve(functionals, initial, problem, options);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
#else
    throw UnsupportedError("minimize_membrane needs Ipopt: limsurf was built without it (install coinor-libipopt-dev "
                           "and reconfigure)");
#endif
}

}  // namespace limsurf
