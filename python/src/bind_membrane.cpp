// Biomembrane shapes (membrane/, apps/membrane.h): limsurf.shape_functionals (the functionals of
// c2g0-sphere-scheme-biomembranes §3 and their exact gradients), limsurf.shape_hessian (the Hessian
// of a combination of them, scipy.sparse), limsurf.minimize_membrane (the
// dict of `limsurf membrane --json` plus the positions) and limsurf.self_intersections (whether a
// limit surface passes through itself, apps/self_intersection.h). Each takes a Mesh, or arrays V, F.
#include <cmath>
#include <exception>
#include <optional>
#include <string>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/membrane.h"
#include "limsurf/apps/self_intersection.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

/// The keyword arguments both functions share.
struct ShapeArguments {
    int degree = 8;
    int subdivide_near_extraordinary = 3;
    int threads = 0;
    bool sum_factorisation = true;  ///< ShapeOptions::sum_factorisation
};

/// The limit basis of @p mesh under @p scheme, with the file's rules (built with the GIL released).
LimitBasis basis_of(const Mesh& mesh, const std::string& scheme) {
    const SchemeKind kind = scheme_from(scheme);
    const SchemeOptions rules = rules_for(mesh.mesh, {});
    const py::gil_scoped_release release;
    return LimitBasis(mesh.mesh.topology(), kind, rules);
}

/// The functionals of @p basis (built with the GIL released).
ShapeFunctionals functionals_of(const LimitBasis& basis, const ShapeArguments& args) {
    ShapeOptions options;
    options.degree = args.degree;
    options.subdivide_near_extraordinary = args.subdivide_near_extraordinary;
    options.num_threads = args.threads;
    options.sum_factorisation = args.sum_factorisation;
    const py::gil_scoped_release release;
    return ShapeFunctionals(basis, options);
}

/// `limsurf membrane --json`'s "self_intersection" for the limit surface of @p X.
py::dict self_intersection_dict(const LimitBasis& basis, const Points& X, int resolution, int threads) {
    check_threads(threads);
    SelfIntersectionOptions options;
    options.resolution = resolution;
    options.num_threads = threads;
    SelfIntersections found;
    {
        const py::gil_scoped_release release;
        found = limit_self_intersections(basis, X, options);
    }
    return py::dict("intersects"_a = found.intersects(), "intersecting_pairs"_a = found.intersecting_pairs,
                    "control_faces"_a = found.control_faces, "resolution"_a = found.resolution,
                    "triangles"_a = found.triangles);
}

/// A Mesh from arrays, through limsurf.Mesh (the same validation and warnings).
Mesh mesh_from(const py::handle& V, const py::handle& F) {
    return py::module_::import("limsurf._limsurf").attr("Mesh")(V, F).cast<Mesh>();
}

/// X (#V × 3 for the mesh's faces), or the mesh's own positions.
/// @throws InputError naming X for another shape or a non-finite entry
Points positions_for(const Mesh& mesh, const std::optional<py::object>& X) {
    if (!X) {
        return mesh.mesh.positions();
    }
    Points points = points_from(*X, "X");
    LIMSURF_CHECK(points.rows() == mesh.mesh.num_vertices(), InputError, "X: ", points.rows(), " rows, the mesh has ",
                  mesh.mesh.num_vertices(), " vertices (X is #V × 3)");
    return points;
}

const char* name_of(ShapeFunctional f) {
    constexpr const char* names[] = {"area", "volume", "mean_curvature", "willmore", "gaussian", "harmonic"};
    return names[static_cast<int>(f)];
}

/// The values under the names of `limsurf membrane --json` (helfrich when H0 is given).
py::dict values_dict(const ShapeValues& values, const std::optional<double>& spontaneous_curvature) {
    py::dict out("area"_a = values.area, "volume"_a = values.volume, "mean_curvature"_a = values.mean_curvature,
                 "willmore"_a = values.willmore, "gaussian"_a = values.gaussian, "harmonic"_a = values.harmonic,
                 "reduced_volume"_a = values.reduced_volume(),
                 "reduced_mean_curvature"_a = values.reduced_mean_curvature());
    if (spontaneous_curvature) {
        const double helfrich = values.helfrich(*spontaneous_curvature);
        LIMSURF_CHECK(std::isfinite(helfrich), NumericalError, "the Helfrich energy with H0 = ", *spontaneous_curvature,
                      " is not finite (H0² A overflows): give H0 in the units of the mesh");
        out["helfrich"] = helfrich;
    }
    return out;
}

void check_spontaneous_curvature(const std::optional<double>& spontaneous_curvature) {
    LIMSURF_CHECK(!spontaneous_curvature || std::isfinite(*spontaneous_curvature), InputError,
                  "spontaneous_curvature: H0 must be a finite number, not ", spontaneous_curvature.value_or(0.0));
}

/// shape_functionals()'s dict from built functionals at @p positions.
py::dict evaluation_dict(const ShapeFunctionals& functionals, const Points& positions, bool gradients,
                         const std::optional<double>& spontaneous_curvature) {
    ShapeValues values;
    {
        const py::gil_scoped_release release;
        values = gradients ? functionals.evaluate_all(positions) : functionals.evaluate(positions);
    }
    py::dict out = values_dict(values, spontaneous_curvature);
    out["volume_is_exact"] = functionals.volume_is_exact();
    out["samples"] = functionals.num_samples();
    out["sum_factorised_elements"] = functionals.num_sum_factorised_elements();
    if (gradients) {
        py::dict gradient;
        for (int f = 0; f < num_shape_functionals; ++f) {
            const auto which = static_cast<ShapeFunctional>(f);
            gradient[name_of(which)] = to_numpy(values.gradient_of(which));
        }
        if (spontaneous_curvature) {
            const Points helfrich = values.helfrich_gradient(*spontaneous_curvature);
            LIMSURF_CHECK(helfrich.allFinite(), NumericalError,
                          "the Helfrich gradient with H0 = ", *spontaneous_curvature,
                          " is not finite (H0² ∇A overflows)");
            gradient["helfrich"] = to_numpy(helfrich);
        }
        out["gradient"] = gradient;
    }
    return out;
}

py::dict shape_functionals(const Mesh& mesh, const std::string& scheme, const std::optional<py::object>& X,
                           bool gradients, std::optional<double> spontaneous_curvature, const ShapeArguments& args) {
    check_spontaneous_curvature(spontaneous_curvature);
    return naming_source(mesh, [&] {
        const Points positions = positions_for(mesh, X);
        const ShapeFunctionals functionals = functionals_of(basis_of(mesh, scheme), args);
        return evaluation_dict(functionals, positions, gradients, spontaneous_curvature);
    });
}

/// {name: weight} → the weights of ShapeFunctionals::hessian; names as shape_functionals returns them.
ShapeCoefficients coefficients_from(const py::dict& weights) {
    ShapeCoefficients out{};
    for (const auto& [key, value] : weights) {
        const auto name = cast_as<std::string>(key, "coefficients: a key", "a str");
        int index = -1;
        for (int f = 0; f < num_shape_functionals; ++f) {
            if (name == name_of(static_cast<ShapeFunctional>(f))) {
                index = f;
            }
        }
        LIMSURF_CHECK(index >= 0, InputError, "coefficients: '", name,
                      "' is not a shape functional (area, volume, mean_curvature, willmore, gaussian, harmonic)");
        const auto weight = cast_as<double>(value, "coefficients['" + name + "']", "a float");
        LIMSURF_CHECK(std::isfinite(weight), InputError, "coefficients['", name, "'] must be finite, not ", weight);
        out[static_cast<std::size_t>(index)] = weight;
    }
    return out;
}

/// shape_hessian()'s matrix from built functionals at @p positions.
py::object hessian_matrix(const ShapeFunctionals& functionals, const Points& positions,
                          const ShapeCoefficients& coefficients) {
    SparseMatrix H;
    {
        const py::gil_scoped_release release;
        H = functionals.hessian(positions, coefficients);
    }
    return to_scipy(H);
}

py::object shape_hessian(const Mesh& mesh, const std::string& scheme, const py::dict& weights,
                         const std::optional<py::object>& X, const ShapeArguments& args) {
    const ShapeCoefficients coefficients = coefficients_from(weights);
    return naming_source(mesh, [&] {
        const Points positions = positions_for(mesh, X);
        return hessian_matrix(functionals_of(basis_of(mesh, scheme), args), positions, coefficients);
    });
}

/// limsurf.ShapeEvaluator: the limit basis and the functionals of one mesh built once, for any
/// positions after (what a Python optimiser calls at every iterate).
struct ShapeEvaluator {
    Mesh mesh;
    std::string scheme;
    ShapeArguments args;
    LimitBasis basis;
    ShapeFunctionals functionals;

    /// Positions @p X (#V × 3), or the mesh's own, with the mesh's file and line on a bad row.
    [[nodiscard]] Points positions(const std::optional<py::object>& X) const {
        return naming_source(mesh, [&] { return positions_for(mesh, X); });
    }
};

ShapeEvaluator make_shape_evaluator(const Mesh& mesh, const std::string& scheme, const ShapeArguments& args) {
    return naming_source(mesh, [&] {
        LimitBasis basis = basis_of(mesh, scheme);
        ShapeFunctionals functionals = functionals_of(basis, args);
        return ShapeEvaluator{mesh, scheme, args, std::move(basis), std::move(functionals)};
    });
}

py::object optional_value(const std::optional<double>& value) {
    return value ? py::object(py::float_(*value)) : py::object(py::none());
}

/// One stage as `limsurf membrane --json` reports it (cli/commands/membrane.cpp, stage_json).
py::dict stage_dict(const MembraneProblem& problem, const MembraneResult& result,
                    const std::optional<double>& spontaneous_curvature) {
    py::dict out = values_dict(result.values, spontaneous_curvature);
    const std::optional<double>& volume = problem.volume;
    const std::optional<double>& mean = problem.mean_curvature;
    out["objective"] = to_string(problem.objective);
    out["objective_value"] = result.objective;
    py::dict targets("area"_a = problem.area, "volume"_a = optional_value(volume),
                     "reduced_volume"_a = optional_value(
                         volume ? std::optional(*volume / volume_from_reduced(1.0, problem.area)) : std::nullopt),
                     "mean_curvature"_a = optional_value(mean),
                     "reduced_mean_curvature"_a = optional_value(
                         mean ? std::optional(*mean / mean_curvature_from_reduced(1.0, problem.area)) : std::nullopt));
    py::dict residuals("area"_a = result.area_residual,
                       "volume"_a = optional_value(volume ? std::optional(result.volume_residual) : std::nullopt),
                       "mean_curvature"_a =
                           optional_value(mean ? std::optional(result.mean_curvature_residual) : std::nullopt));
    if (problem.willmore_bound) {
        targets["willmore_bound"] = *problem.willmore_bound;
        residuals["willmore_excess"] = result.willmore_excess;
    }
    out["targets"] = targets;
    out["residuals"] = residuals;
    out["max_relative_residual"] = max_relative_residual(problem, result);
    out["iterations"] = result.iterations;
    out["seconds"] = result.seconds;
    out["converged"] = result.converged;
    out["projected"] = result.projected;
    out["status"] = result.status;
    return out;
}

py::dict run_dict(const std::string& scheme, const Mesh& mesh, const ShapeFunctionals& functionals,
                  const ShapeArguments& args, const MembraneRequest& request, const MembraneRun& run) {
    py::dict out("scheme"_a = scheme, "vertices"_a = mesh.mesh.num_vertices(),
                 "unknowns"_a = 3 * mesh.mesh.num_vertices(), "samples"_a = functionals.num_samples(),
                 "degree"_a = args.degree, "sum_factorised_elements"_a = functionals.num_sum_factorised_elements(),
                 "volume_is_exact"_a = functionals.volume_is_exact(), "hessian"_a = to_string(request.hessian),
                 "initial_area"_a = run.initial_area, "scale"_a = run.scale,
                 "spontaneous_curvature"_a = optional_value(request.spontaneous_curvature));
    for (const auto& [key, value] : stage_dict(run.problem, run.shape, request.spontaneous_curvature)) {
        out[key] = value;
    }
    py::list continuation;
    for (const MembraneContinuationStep& step : run.continuation) {
        continuation.append(stage_dict(step.problem, step.result, request.spontaneous_curvature));
    }
    out["continuation"] = continuation;
    out["regularization"] = py::none();
    if (run.regularization) {
        py::dict stage = stage_dict(*run.regularization_problem, *run.regularization, request.spontaneous_curvature);
        stage["epsilon"] = *request.regularize_harmonic;
        stage["hessian"] = to_string(request.regularization_hessian.value_or(request.hessian));
        out["regularization"] = stage;
    }
    out["positions"] = to_numpy(run.final_result().positions);
    return out;
}

/// The progress callback: @p callback(dict) with the GIL held; False stops the solve. A Python
/// exception is kept in @p error (and stops the solve) to be raised once the solver has returned:
/// it must not unwind through Ipopt.
MembraneProgress progress_of(const std::optional<py::function>& callback, std::exception_ptr& error) {
    if (!callback) {
        return {};
    }
    return [&callback, &error](MembraneStage stage, const MembraneIteration& it) {
        const py::gil_scoped_acquire acquire;
        try {
            const py::object answer = (*callback)(py::dict(
                "stage"_a = to_string(stage), "iteration"_a = it.iteration, "objective"_a = it.objective,
                "constraint_violation"_a = it.constraint_violation, "dual_infeasibility"_a = it.dual_infeasibility,
                "step"_a = it.step, "restoration"_a = it.restoration, "watchdog"_a = it.watchdog));
            return answer.is_none() || static_cast<bool>(py::bool_(answer));
        } catch (...) {
            error = std::current_exception();
            return false;
        }
    };
}

py::dict minimize_membrane(const Mesh& mesh, const std::string& scheme, const MembraneRequest& request,
                           const std::optional<py::function>& callback, const ShapeArguments& args) {
    return naming_source(mesh, [&] {
        (void)membrane_problem(request);  // a bad request fails before the functionals are built
        const LimitBasis basis = basis_of(mesh, scheme);
        const ShapeFunctionals functionals = functionals_of(basis, args);
        std::exception_ptr error;
        const MembraneProgress progress = progress_of(callback, error);
        MembraneRun run;
        {
            const py::gil_scoped_release release;
            run = solve_membrane_problem(functionals, mesh.mesh.positions(), request, progress);
        }
        if (error) {
            std::rethrow_exception(error);
        }
        py::dict out = run_dict(scheme, mesh, functionals, args, request, run);
        out["self_intersection"] = self_intersection_dict(basis, run.final_result().positions, 0, args.threads);
        return out;
    });
}

MembraneRequest request_of(double area, std::optional<double> volume, std::optional<double> reduced_volume,
                           std::optional<double> mean_curvature, std::optional<double> reduced_mean_curvature,
                           std::optional<double> spontaneous_curvature, std::optional<double> regularize_harmonic,
                           int max_iterations, double tolerance, double objective_tolerance, const std::string& hessian,
                           const std::optional<std::string>& regularization_hessian, int continuation_steps) {
    const auto parse = [](const std::string& name, const char* argument) {
        LIMSURF_CHECK(name == "limited-memory" || name == "exact", InputError, argument,
                      ": 'limited-memory' or 'exact', not '", name, "'");
        return parse_membrane_hessian(name);
    };
    MembraneRequest request;
    request.area = area;
    request.volume = volume;
    request.reduced_volume = reduced_volume;
    request.mean_curvature = mean_curvature;
    request.reduced_mean_curvature = reduced_mean_curvature;
    request.spontaneous_curvature = spontaneous_curvature;
    request.regularize_harmonic = regularize_harmonic;
    request.max_iterations = max_iterations;
    request.tolerance = tolerance;
    request.objective_tolerance = objective_tolerance;
    request.hessian = parse(hessian, "hessian");
    request.continuation_steps = continuation_steps;
    if (regularization_hessian) {
        LIMSURF_CHECK(regularize_harmonic.has_value(), InputError,
                      "regularization_hessian needs regularize_harmonic (there is no regularisation to solve)");
        request.regularization_hessian = parse(*regularization_hessian, "regularization_hessian");
    }
    return request;
}

constexpr const char* shape_doc = R"(The shape functionals of the closed limit surface and their exact gradients
with respect to the control points (c2g0-sphere-scheme-biomembranes §3; docs/guide/membrane.md):
shape_functionals(mesh, scheme, ...) or shape_functionals(V, F, scheme, ...), scheme 'c2g0', 'loop' or
'catmull-clark'. A dict with 'area', 'volume', 'mean_curvature' (∫H dA, H = 1 on the unit sphere),
'willmore' (∫H² dA, 4π on a sphere), 'gaussian' (∫K dA = 2πχ), 'harmonic' (the harmonic energy (3.6)),
'reduced_volume', 'reduced_mean_curvature', 'helfrich' (∫(H − H0)² dA, with spontaneous_curvature=H0),
'volume_is_exact' (trilinear forms for Loop/Catmull–Clark, quadrature for C2g0), 'samples' and
'sum_factorised_elements' (regular Catmull–Clark faces evaluated one direction at a time; with
sum_factorisation=False every face goes through its dense kernel, the same values to rounding: for
checking); with gradients=True also 'gradient': name → (#V, 3) array. X: other positions (#V × 3)
for the same faces.
Raises limsurf.InputError for an open mesh, limsurf.UnsupportedError for Doo–Sabin or tags.)";

constexpr const char* minimize_doc = R"(Solves the Canham problem (min W s.t. A = area, V = volume) or, with
mean_curvature / reduced_mean_curvature and spontaneous_curvature, the Helfrich problem (3.1) with hard
constraints (Ipopt), from the mesh as initial guess scaled about its centroid to limit area `area`; with
regularize_harmonic=ε then (3.12): min harmonic energy s.t. the same constraints and W ≤ W0 + ε.
minimize_membrane(mesh, scheme, area=..., ...) or minimize_membrane(V, F, scheme, area=..., ...).
Returns the dict of `limsurf membrane --json` plus 'positions' (#V × 3, the last stage's control points).
hessian: 'limited-memory' (BFGS from the gradients, the default) or 'exact' (Newton steps with
shape_hessian's matrices; fewer iterations, each dearer: docs/guide/membrane.md);
regularization_hessian: the same for (3.12) only (None: hessian's); continuation_steps=K: reach the
volume (and mean-curvature) targets in K steps from the start's, each a solve from the last
(`--continuation`; 'continuation' lists the K − 1 intermediate stages); sum_factorisation=False: every face
through its dense kernel (`--no-sum-factorisation`; for checking).
callback(dict) is called after every iteration with 'stage' ('continuation', 'shape' or 'regularization'),
'iteration', 'objective', 'constraint_violation', 'dual_infeasibility', 'step', 'restoration' and
'watchdog' (a trial step of Ipopt's watchdog, outside the filter's test); returning False stops the
solve (converged False) and no later stage calls it again;
an exception in it stops the solve and is raised. A stage that stops short otherwise (max_iterations)
has 'projected' True when the points returned hold the constraints: the lowest objective met near them,
or its last iterate, projected onto them (a feasible point, not a minimiser; 'status' says which). Raises limsurf.InputError for an infeasible request
(area outside [1e-100, 1e100], reduced volume outside [1e-6, 1], both or neither volume options) or an open mesh,
limsurf.UnsupportedError for Doo–Sabin or without Ipopt.)";

constexpr const char* hessian_doc = R"(The Hessian of a combination of the shape functionals with respect to
the control points: shape_hessian(mesh, scheme, coefficients, ...) or shape_hessian(V, F, scheme,
coefficients, ...), coefficients a dict {name: weight} with names as shape_functionals returns them
('area', 'volume', 'mean_curvature', 'willmore', 'gaussian', 'harmonic'; missing ones weigh 0).
Returns a symmetric scipy.sparse.csr_matrix (3 #V × 3 #V), row and column 3 v + c for coordinate c of
control point v; its pattern (explicit zeros included) holds every pair of control points that share
a limit patch's support and depends on the faces only. Per sample the integrand's second derivatives
are central differences of its exact gradients (relative error ~1e-10); the volume's term is its
quadrature's with the centroid held fixed (docs/guide/membrane.md). X: other positions (#V × 3).
Raises limsurf.InputError for an unknown name, a weight that is not finite or an open mesh,
limsurf.NumericalError where the surface is degenerate.)";

constexpr const char* self_intersections_doc = R"(Whether the limit surface passes through itself
(c2g0-sphere-scheme-biomembranes Fig. 7): self_intersections(mesh, scheme, ...) or
self_intersections(V, F, scheme, ...), any scheme. The exact limit surface is tessellated (`resolution`
segments per ptex face edge; 0: about 40 000 points), the copies of shared points welded, and the
triangle pairs that meet other than where the surface's connectivity joins them counted (CGAL's rule).
A dict with 'intersects', 'intersecting_pairs', 'control_faces' (sorted: the control faces whose limit
patches take part), 'resolution' and 'triangles' — the "self_intersection" of `limsurf membrane --json`.
X: other positions (#V × 3) for the same faces. Raises limsurf.InputError for a resolution outside 0..256.)";

}  // namespace

constexpr const char* evaluator_doc = R"(The shape functionals of one closed mesh under a scheme, set up once:
ShapeEvaluator(mesh, scheme, ...) or ShapeEvaluator(V, F, scheme, ...), with shape_functionals()'s degree,
subdivide_near_extraordinary, threads and sum_factorisation. The set-up (the limit basis, the quadrature
samples and their shared kernels) is what a call of shape_functionals() spends most of its time on:
for a C2g0 sphere of 8 194 control vertices about 1.5 s against 30–50 ms per evaluation. evaluate(X)
and hessian(coefficients, X) then cost one pass each, for any positions X (#V × 3) of the same faces —
what an optimiser of one's own (scipy.optimize and the like) calls at every iterate. The same numbers
as shape_functionals() and shape_hessian() to the last bit. Thread-safe: several Python threads may
evaluate at once (the GIL is released while C++ works).)";

void bind_shape_evaluator(py::module_& m) {
    const auto arguments = [](int degree, int subdivide_near_extraordinary, int threads, bool sum_factorisation) {
        check_threads(threads);
        return ShapeArguments{degree, subdivide_near_extraordinary, threads, sum_factorisation};
    };
    py::class_<ShapeEvaluator>(m, "ShapeEvaluator", evaluator_doc)
        .def(py::init([arguments](const Mesh& mesh, const std::string& scheme, int degree,
                                  int subdivide_near_extraordinary, int threads, bool sum_factorisation) {
                 return make_shape_evaluator(
                     mesh, scheme, arguments(degree, subdivide_near_extraordinary, threads, sum_factorisation));
             }),
             "mesh"_a, "scheme"_a, py::kw_only(), "degree"_a = 8, "subdivide_near_extraordinary"_a = 3, "threads"_a = 0,
             "sum_factorisation"_a = true)
        .def(py::init([arguments](const py::object& V, const py::object& F, const std::string& scheme, int degree,
                                  int subdivide_near_extraordinary, int threads, bool sum_factorisation) {
                 return make_shape_evaluator(
                     mesh_from(V, F), scheme,
                     arguments(degree, subdivide_near_extraordinary, threads, sum_factorisation));
             }),
             "V"_a, "F"_a, "scheme"_a, py::kw_only(), "degree"_a = 8, "subdivide_near_extraordinary"_a = 3,
             "threads"_a = 0, "sum_factorisation"_a = true)
        .def(
            "evaluate",
            [](const ShapeEvaluator& self, const std::optional<py::object>& X, bool gradients,
               std::optional<double> spontaneous_curvature) {
                check_spontaneous_curvature(spontaneous_curvature);
                const Points positions = self.positions(X);
                return naming_source(self.mesh, [&] {
                    return evaluation_dict(self.functionals, positions, gradients, spontaneous_curvature);
                });
            },
            "X"_a = py::none(), py::kw_only(), "gradients"_a = true, "spontaneous_curvature"_a = py::none(),
            "shape_functionals()'s dict at the positions X (None: the mesh's own).")
        .def(
            "hessian",
            [](const ShapeEvaluator& self, const py::dict& coefficients, const std::optional<py::object>& X) {
                const ShapeCoefficients weights = coefficients_from(coefficients);
                const Points positions = self.positions(X);
                return naming_source(self.mesh, [&] { return hessian_matrix(self.functionals, positions, weights); });
            },
            "coefficients"_a, "X"_a = py::none(),
            "shape_hessian()'s matrix of Σ coefficients[name] F_name at the positions X (None: the mesh's own).")
        .def(
            "self_intersections",
            [](const ShapeEvaluator& self, const std::optional<py::object>& X, int resolution) {
                const Points positions = self.positions(X);
                return naming_source(self.mesh, [&] {
                    return self_intersection_dict(self.basis, positions, resolution, self.args.threads);
                });
            },
            "X"_a = py::none(), py::kw_only(), "resolution"_a = 0,
            "self_intersections()'s dict for the limit surface of the positions X (None: the mesh's own).")
        .def_property_readonly("scheme", [](const ShapeEvaluator& self) { return self.scheme; })
        .def_property_readonly("num_vertices",
                               [](const ShapeEvaluator& self) { return self.functionals.num_vertices(); })
        .def_property_readonly("num_samples", [](const ShapeEvaluator& self) { return self.functionals.num_samples(); })
        .def_property_readonly("volume_is_exact",
                               [](const ShapeEvaluator& self) { return self.functionals.volume_is_exact(); })
        .def_property_readonly("sum_factorised_elements", [](const ShapeEvaluator& self) {
            return self.functionals.num_sum_factorised_elements();
        });
}

void bind_membrane(py::module_& m) {
    const auto intersections = [](const Mesh& mesh, const std::string& scheme, std::optional<py::object> X,
                                  int resolution, int threads) {
        return naming_source(mesh, [&] {
            const Points positions = positions_for(mesh, X);
            return self_intersection_dict(basis_of(mesh, scheme), positions, resolution, threads);
        });
    };
    m.def("self_intersections", intersections, "mesh"_a, "scheme"_a, py::kw_only(), "X"_a = py::none(),
          "resolution"_a = 0, "threads"_a = 0, self_intersections_doc);
    m.def(
        "self_intersections",
        [intersections](const py::object& V, const py::object& F, const std::string& scheme,
                        std::optional<py::object> X, int resolution, int threads) {
            return intersections(mesh_from(V, F), scheme, std::move(X), resolution, threads);
        },
        "V"_a, "F"_a, "scheme"_a, py::kw_only(), "X"_a = py::none(), "resolution"_a = 0, "threads"_a = 0);

    const auto shape = [](const Mesh& mesh, const std::string& scheme, std::optional<py::object> X, bool gradients,
                          std::optional<double> spontaneous_curvature, int degree, int subdivide_near_extraordinary,
                          int threads, bool sum_factorisation) {
        return shape_functionals(mesh, scheme, X, gradients, spontaneous_curvature,
                                 {degree, subdivide_near_extraordinary, threads, sum_factorisation});
    };
    m.def("shape_functionals", shape, "mesh"_a, "scheme"_a, py::kw_only(), "X"_a = py::none(), "gradients"_a = true,
          "spontaneous_curvature"_a = py::none(), "degree"_a = 8, "subdivide_near_extraordinary"_a = 3, "threads"_a = 0,
          "sum_factorisation"_a = true, shape_doc);
    m.def(
        "shape_functionals",
        [shape](const py::object& V, const py::object& F, const std::string& scheme, std::optional<py::object> X,
                bool gradients, std::optional<double> spontaneous_curvature, int degree,
                int subdivide_near_extraordinary, int threads, bool sum_factorisation) {
            return shape(mesh_from(V, F), scheme, std::move(X), gradients, spontaneous_curvature, degree,
                         subdivide_near_extraordinary, threads, sum_factorisation);
        },
        "V"_a, "F"_a, "scheme"_a, py::kw_only(), "X"_a = py::none(), "gradients"_a = true,
        "spontaneous_curvature"_a = py::none(), "degree"_a = 8, "subdivide_near_extraordinary"_a = 3, "threads"_a = 0,
        "sum_factorisation"_a = true);

    const auto minimize = [](const Mesh& mesh, const std::string& scheme, double area, std::optional<double> volume,
                             std::optional<double> reduced_volume, std::optional<double> mean_curvature,
                             std::optional<double> reduced_mean_curvature, std::optional<double> spontaneous_curvature,
                             std::optional<double> regularize_harmonic, int max_iterations, double tolerance,
                             double objective_tolerance, const std::string& hessian,
                             const std::optional<std::string>& regularization_hessian, int continuation_steps,
                             std::optional<py::function> callback, int degree, int subdivide_near_extraordinary,
                             int threads, bool sum_factorisation) {
        const MembraneRequest request =
            request_of(area, volume, reduced_volume, mean_curvature, reduced_mean_curvature, spontaneous_curvature,
                       regularize_harmonic, max_iterations, tolerance, objective_tolerance, hessian,
                       regularization_hessian, continuation_steps);
        return minimize_membrane(mesh, scheme, request, callback,
                                 {degree, subdivide_near_extraordinary, threads, sum_factorisation});
    };
    m.def("minimize_membrane", minimize, "mesh"_a, "scheme"_a, py::kw_only(), "area"_a, "volume"_a = py::none(),
          "reduced_volume"_a = py::none(), "mean_curvature"_a = py::none(), "reduced_mean_curvature"_a = py::none(),
          "spontaneous_curvature"_a = py::none(), "regularize_harmonic"_a = py::none(), "max_iterations"_a = 1000,
          "tolerance"_a = 1e-8, "objective_tolerance"_a = 1e-7, "hessian"_a = "limited-memory",
          "regularization_hessian"_a = py::none(), "continuation_steps"_a = 1, "callback"_a = py::none(),
          "degree"_a = 8, "subdivide_near_extraordinary"_a = 3, "threads"_a = 0, "sum_factorisation"_a = true,
          minimize_doc);
    m.def(
        "minimize_membrane",
        [minimize](const py::object& V, const py::object& F, const std::string& scheme, double area,
                   std::optional<double> volume, std::optional<double> reduced_volume,
                   std::optional<double> mean_curvature, std::optional<double> reduced_mean_curvature,
                   std::optional<double> spontaneous_curvature, std::optional<double> regularize_harmonic,
                   int max_iterations, double tolerance, double objective_tolerance, const std::string& hessian,
                   const std::optional<std::string>& regularization_hessian, int continuation_steps,
                   std::optional<py::function> callback, int degree, int subdivide_near_extraordinary, int threads,
                   bool sum_factorisation) {
            return minimize(mesh_from(V, F), scheme, area, volume, reduced_volume, mean_curvature,
                            reduced_mean_curvature, spontaneous_curvature, regularize_harmonic, max_iterations,
                            tolerance, objective_tolerance, hessian, regularization_hessian, continuation_steps,
                            std::move(callback), degree, subdivide_near_extraordinary, threads, sum_factorisation);
        },
        "V"_a, "F"_a, "scheme"_a, py::kw_only(), "area"_a, "volume"_a = py::none(), "reduced_volume"_a = py::none(),
        "mean_curvature"_a = py::none(), "reduced_mean_curvature"_a = py::none(),
        "spontaneous_curvature"_a = py::none(), "regularize_harmonic"_a = py::none(), "max_iterations"_a = 1000,
        "tolerance"_a = 1e-8, "objective_tolerance"_a = 1e-7, "hessian"_a = "limited-memory",
        "regularization_hessian"_a = py::none(), "continuation_steps"_a = 1, "callback"_a = py::none(), "degree"_a = 8,
        "subdivide_near_extraordinary"_a = 3, "threads"_a = 0, "sum_factorisation"_a = true);

    const auto hessian = [](const Mesh& mesh, const std::string& scheme, const py::dict& coefficients,
                            std::optional<py::object> X, int degree, int subdivide_near_extraordinary, int threads) {
        return shape_hessian(mesh, scheme, coefficients, X, {degree, subdivide_near_extraordinary, threads});
    };
    m.def("shape_hessian", hessian, "mesh"_a, "scheme"_a, "coefficients"_a, py::kw_only(), "X"_a = py::none(),
          "degree"_a = 8, "subdivide_near_extraordinary"_a = 3, "threads"_a = 0, hessian_doc);
    m.def(
        "shape_hessian",
        [hessian](const py::object& V, const py::object& F, const std::string& scheme, const py::dict& coefficients,
                  std::optional<py::object> X, int degree, int subdivide_near_extraordinary, int threads) {
            return hessian(mesh_from(V, F), scheme, coefficients, std::move(X), degree, subdivide_near_extraordinary,
                           threads);
        },
        "V"_a, "F"_a, "scheme"_a, "coefficients"_a, py::kw_only(), "X"_a = py::none(), "degree"_a = 8,
        "subdivide_near_extraordinary"_a = 3, "threads"_a = 0);

    bind_shape_evaluator(m);
}

}  // namespace limsurf::python
