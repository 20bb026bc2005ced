// IGA-tuned Catmull–Clark weights (analysis/weight_tuning.h, docs/guide/tune.md): the feasible λ, the
// weights of a λ, the one-ring spectrum, the cup and saddle errors, the search of `limsurf tune --json`
// (the same keys, the curve as numpy columns) and the local cup–saddle decomposition of a solution.
// A set of weights is the dict W: lambda, alpha, beta, gamma, constraint, lambda3, lambda4 (and
// cup_error, saddle_error where they were computed).
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/analysis/weight_tuning.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

TuningOptions options_of(int quadrature, int tile_levels, double poisson_ratio, int threads) {
    TuningOptions options;
    options.quadrature_points = quadrature;
    options.tile_levels = tile_levels;
    options.poisson_ratio = poisson_ratio;
    options.num_threads = threads;
    return options;
}

/// W of @p v, with the errors when given.
py::dict weights_dict(const TunedVertex& v, const std::optional<ShapeErrors>& errors = std::nullopt) {
    py::dict out("lambda"_a = v.lambda, "alpha"_a = v.weights.alpha, "beta"_a = v.weights.beta,
                 "gamma"_a = v.weights.gamma, "constraint"_a = to_string(v.constraint), "lambda3"_a = v.lambda3,
                 "lambda4"_a = v.lambda4);
    if (errors) {
        out["cup_error"] = errors->cup;
        out["saddle_error"] = errors->saddle;
    }
    return out;
}

/// The curve as columns: one float64 array per number of W, and 'constraint' a list of names.
py::dict curve_dict(const std::vector<TuningSample>& curve) {
    const auto n = static_cast<py::ssize_t>(curve.size());
    constexpr std::array<const char*, 8> names = {"lambda",  "alpha",   "beta",      "gamma",
                                                  "lambda3", "lambda4", "cup_error", "saddle_error"};
    std::array<py::array_t<double>, names.size()> columns;
    for (auto& column : columns) {
        column = new_vector(n);
    }
    py::list constraint;
    for (py::ssize_t i = 0; i < n; ++i) {
        const TuningSample& s = curve[static_cast<std::size_t>(i)];
        const std::array<double, names.size()> values = {
            s.vertex.lambda,  s.vertex.weights.alpha, s.vertex.weights.beta, s.vertex.weights.gamma,
            s.vertex.lambda3, s.vertex.lambda4,       s.errors.cup,          s.errors.saddle};
        for (std::size_t k = 0; k < names.size(); ++k) {
            columns[k].mutable_at(i) = values[k];
        }
        constraint.append(to_string(s.vertex.constraint));
    }
    py::dict out;
    for (std::size_t k = 0; k < names.size(); ++k) {
        out[names[k]] = columns[k];
    }
    out["constraint"] = constraint;
    return out;
}

/// (α, β, γ): α None is Catmull–Clark's n(n − 2).
VertexRuleWeights rule_weights(int valence, std::optional<double> alpha, double beta, double gamma) {
    VertexRuleWeights w = catmull_clark_weights(valence);
    if (alpha) {
        w.alpha = *alpha;
    }
    w.beta = beta;
    w.gamma = gamma;
    return w;
}

py::dict tune(int valence, const std::string& shape, const TuningOptions& options,
              const std::optional<std::pair<double, double>>& lambda_range, int samples, bool protect) {
    TuningRequest request;
    request.valence = valence;
    request.shape = parse_quadratic_shape(shape);
    request.options = options;
    if (lambda_range) {
        request.lambda_low = lambda_range->first;
        request.lambda_high = lambda_range->second;
    }
    request.curve_samples = samples;
    request.protect_other_shape = protect;
    TuningResult result;
    {
        const py::gil_scoped_release release;
        result = tune_weights(request);
    }
    const LambdaRange& feasible = result.feasible;
    const std::pair<double, double> search(result.searched.low, result.searched.high);
    return py::dict(
        "valence"_a = valence, "shape"_a = to_string(request.shape), "quadrature_points"_a = options.quadrature_points,
        "tile_levels"_a = options.tile_levels, "poisson_ratio"_a = options.poisson_ratio,
        "feasible_range"_a = std::pair(feasible.low, feasible.high), "search_range"_a = search,
        "protect_other_shape"_a = protect, "protection_binds"_a = result.protection_binds,
        "tuned"_a = weights_dict(result.tuned, result.tuned_errors),
        "unconstrained"_a = weights_dict(result.unconstrained.vertex, result.unconstrained.errors),
        "classical"_a = weights_dict(result.classical, result.classical_errors), "curve"_a = curve_dict(result.curve));
}

/// A Python value as a double, InputError naming @p what when it is not a real number.
double real_from(const py::handle& value, const std::string& what) {
    try {
        return py::cast<double>(value);
    } catch (const py::cast_error&) {
        throw InputError(detail::concat(what, ": expected a number, got ",
                                        py::str(py::type::of(value).attr("__name__")).cast<std::string>()));
    }
}

int integer_from(const py::handle& key, const std::string& what) {
    if (!py::isinstance<py::int_>(key) || py::isinstance<py::bool_>(key)) {
        throw InputError(detail::concat(what, ": expected an integer key, got ", py::repr(key).cast<std::string>()));
    }
    return py::cast<int>(key);
}

/// None (Catmull–Clark), a preset name or weights file (as `limsurf subdivide --weights`), or
/// {"valence": {n: w}, "vertex": {i: w}} with w (alpha, beta, gamma) or a W dict.
TunedWeights tuned_weights_from(const py::object& spec) {
    if (spec.is_none()) {
        return {};
    }
    if (py::isinstance<py::str>(spec)) {
        const auto name = spec.cast<std::string>();
        return name == "cup" || name == "saddle" || name == "catmull-clark" ? TunedWeights::preset(name)
                                                                            : TunedWeights::from_file(name);
    }
    if (!py::isinstance<py::dict>(spec)) {
        throw InputError("weights: expected None, a preset name ('cup', 'saddle', 'catmull-clark'), a weights file "
                         "or a dict {'valence': {n: (alpha, beta, gamma)}, 'vertex': {i: (alpha, beta, gamma)}}");
    }
    TunedWeights out;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(spec)) {
        const std::string kind = py::isinstance<py::str>(key) ? key.cast<std::string>() : "";
        if (kind != "valence" && kind != "vertex") {
            throw InputError(detail::concat("weights: unknown key ", py::repr(key).cast<std::string>(),
                                            " (expected 'valence' and/or 'vertex')"));
        }
        if (!py::isinstance<py::dict>(value)) {
            throw InputError(
                detail::concat("weights['", kind, "']: expected a dict {", kind, ": (alpha, beta, gamma)}"));
        }
        for (const auto& [index, w] : py::reinterpret_borrow<py::dict>(value)) {
            const std::string what = detail::concat("weights['", kind, "']");
            const int i = integer_from(index, what);
            const VertexRuleWeights weights = vertex_weights_from(w, detail::concat(what, "[", i, "]"));
            if (kind == "valence") {
                out.set_valence(i, weights);
            } else {
                out.set_vertex(static_cast<Index>(i), weights);
            }
        }
    }
    return out;
}

py::list decompose(const Mesh& mesh, const std::optional<py::object>& P, const py::object& weights, int min_valence,
                   double poisson_ratio) {
    return naming_source(mesh, [&] {
        const Points points = P ? points_from(*P, "P") : mesh.mesh.positions();
        const TunedWeights tuned = tuned_weights_from(weights);
        std::vector<ShapeDecomposition> parts;
        {
            const py::gil_scoped_release release;
            parts = decompose_shapes(mesh.mesh.topology(), points, tuned, min_valence, poisson_ratio);
        }
        py::list out;
        for (const ShapeDecomposition& d : parts) {
            out.append(shape_decomposition_dict(d));
        }
        return out;
    });
}

/// A Mesh from arrays, through limsurf.Mesh (the same validation and warnings).
Mesh mesh_from(const py::handle& V, const py::handle& F) {
    return py::module_::import("limsurf._limsurf").attr("Mesh")(V, F).cast<Mesh>();
}

constexpr const char* range_doc = R"(The interval (low, high) of subdominant eigenvalues λ for which tuned weights
exist at an interior vertex of this valence (α > 0, β, γ ≥ 0, λ₃ = λ² the largest eigenvalue after λ;
iga-tuned-catmull-clark-weights §3.2). It contains Catmull–Clark's own λ. Raises limsurf.InputError for
valence 4 (the regular B-spline: tuning it would change every regular patch), below 3 or too large.)";

constexpr const char* spectrum_doc = R"(The one-ring eigenvalues of the weights (alpha, beta, gamma) at an interior
vertex of this valence, in closed form: a dict W with 'lambda' (λ₁ = λ₂, frequency 1), 'lambda3'
(frequency 0), 'lambda4' (frequency 2), the weights and 'constraint' 'none'. alpha None is Catmull–Clark's
n(n − 2). Raises limsurf.InputError for bad weights, limsurf.NumericalError for complex eigenvalues.)";

constexpr const char* subdominant_doc = R"(The weights whose subdominant eigenvalue is lambda_ (closed form): the
solutions of (30) (λ₄ = λ², both swaps of β, γ), else the relaxed (31) (β = γ, λ₄ free), each with λ₃ = λ².
A list of one or two dicts W ('lambda', 'alpha', 'beta', 'gamma', 'constraint' 'exact' or 'relaxed',
'lambda3', 'lambda4'), exact ones first. At valence 5, λ = 0.550 gives Table 1's cup weights.
Raises limsurf.InputError for a valence as feasible_subdominant_range or λ outside its range.)";

constexpr const char* errors_doc = R"(The relative thin-plate energy-norm errors (32) of the cup ξ₁² + ξ₂² and the
saddle ξ₁² − ξ₂² at an interior vertex of this valence with the weights (alpha, beta, gamma) (alpha None:
Catmull–Clark's), over the 2-neighbourhood of the characteristic map: a dict {'cup', 'saddle'}. quadrature:
Gauss points per direction (1..10), tile_levels: tiles towards the vertex (0..20), poisson_ratio μ of (28),
threads: over the faces (0: all cores; the errors do not depend on it). Catmull–Clark's weights at
valence 4 (8, 1, 1) give zero errors. Raises limsurf.InputError for bad input.)";

constexpr const char* tune_doc = R"(Searches the subdominant eigenvalue λ minimising the error of `shape`
('cup' or 'saddle') — `limsurf tune --json`'s dict: 'valence', 'shape', 'quadrature_points',
'tile_levels', 'poisson_ratio', 'feasible_range', 'search_range', 'protect_other_shape',
'protection_binds', 'tuned', 'unconstrained', 'classical' (dicts W with 'cup_error' and 'saddle_error')
and 'curve': the error curve over λ as columns — float64 arrays 'lambda', 'alpha', 'beta', 'gamma',
'lambda3', 'lambda4', 'cup_error', 'saddle_error' and a list 'constraint' (increasing λ).
With protect=True (§3.3) the other shape's error may not exceed Catmull–Clark's. lambda_range=(lo, hi)
limits the search (default: the feasible range); samples: points of the curve (≥ 3); threads: over the
curve's λ, then over the faces of the 2-neighbourhood (0: all cores; the result does not depend on it).
A call takes about half a second at valence 5, more at high valences (docs/guide/tune.md). Raises
limsurf.InputError for bad input.)";

constexpr const char* tuned_doc = R"(The weights a user gets for `shape` at this valence: the tuned λ (with the
protection) rounded to three decimals as Table 1 prints it, and its weights — a dict W with 'cup_error'
and 'saddle_error'. At valence 5: cup λ 0.550, α 13.4575, β = γ 0.999938; saddle λ 0.585, α 13.9851,
β = γ 0.824886. threads as in tune_weights. Pass it to decompose_shapes as weights={'valence': {5: W}}.)";

constexpr const char* decompose_doc = R"(The local cup–saddle decomposition (§3.4, (33)–(38)) of the control points P
(#V × 3; for a plate (x, y, w)) at every interior vertex of valence ≥ min_valence whose faces are all
quads: decompose_shapes(mesh, P=None, ...) or decompose_shapes(V, F, P=None, ...) (P None: the mesh's
positions). A list of dicts 'vertex', 'valence', 'k3' (cup coefficient of ξ₁² + ξ₂²), 'k4', 'k5' (saddle
coefficients of ξ₁² − ξ₂² and 2ξ₁ξ₂), 'ratio' (R = k₃² / (k₄² + k₅²) · (1 + μ)/(1 − μ), inf without a
saddle part, nan without either), 'has_quadratic_part' (False where P is flat there to rounding: every
k below 2e-15 of the one-ring's size or distance from the origin, set to 0), 'normal' (a 3-array),
'position' (the vertex's limit point), 'tangents' (2 × 3: ∂P/∂ξ₁, ∂P/∂ξ₂ there; with J their in-plane
parts as columns, a smooth field's Hessian H gives the ξ-Hessian JᵀHJ = 2[[k₃+k₄, k₅], [k₅, k₃−k₄]])
and 'cup_dominates' (R ≥ 1; False where flat). weights: None (Catmull–Clark), a preset
'cup', 'saddle', 'catmull-clark' or a weights file (as `limsurf subdivide --weights`), or a dict
{'valence': {n: w}, 'vertex': {i: w}} with w (alpha, beta, gamma) or a dict W. Raises limsurf.InputError
for bad P or weights, or a one-ring holding another tuned vertex.)";

}  // namespace

py::dict shape_decomposition_dict(const ShapeDecomposition& d) {
    Eigen::MatrixXd tangents(2, 3);
    tangents.row(0) = d.tangent1.transpose();
    tangents.row(1) = d.tangent2.transpose();
    return py::dict("vertex"_a = d.vertex, "valence"_a = d.valence, "k3"_a = d.k3, "k4"_a = d.k4, "k5"_a = d.k5,
                    "ratio"_a = d.ratio, "has_quadratic_part"_a = d.has_quadratic_part,
                    "normal"_a = to_numpy(Eigen::VectorXd(d.normal)),
                    "position"_a = to_numpy(Eigen::VectorXd(d.position)), "tangents"_a = to_numpy(tangents),
                    "cup_dominates"_a = d.cup_dominates());
}

VertexRuleWeights vertex_weights_from(const py::handle& value, const std::string& what) {
    std::array<double, 3> w{};
    if (py::isinstance<py::dict>(value)) {
        const auto d = py::reinterpret_borrow<py::dict>(value);
        constexpr std::array<const char*, 3> keys = {"alpha", "beta", "gamma"};
        for (std::size_t k = 0; k < 3; ++k) {
            if (!d.contains(keys[k])) {
                throw InputError(detail::concat(what, ": the weights have no '", keys[k], "'"));
            }
            w[k] = real_from(d[keys[k]], what + "['" + keys[k] + "']");
        }
    } else {
        if (!py::isinstance<py::sequence>(value) || py::isinstance<py::str>(value) || py::len(value) != 3) {
            throw InputError(
                detail::concat(what, ": expected (alpha, beta, gamma) or a dict with 'alpha', 'beta', 'gamma'"));
        }
        const auto s = py::reinterpret_borrow<py::sequence>(value);
        for (std::size_t k = 0; k < 3; ++k) {
            w[k] = real_from(s[k], detail::concat(what, "[", k, "]"));
        }
    }
    LIMSURF_CHECK(std::isfinite(w[0]) && std::isfinite(w[1]) && std::isfinite(w[2]), InputError, what,
                  ": the weights must be finite");
    return {w[0], w[1], w[2]};
}

void bind_tuning(py::module_& m) {
    m.def(
        "feasible_subdominant_range",
        [](int valence) {
            const py::gil_scoped_release release;
            const LambdaRange r = feasible_subdominant_range(valence);
            return std::pair(r.low, r.high);
        },
        "valence"_a, range_doc);
    m.def(
        "one_ring_spectrum",
        [](int valence, std::optional<double> alpha, double beta, double gamma) {
            const VertexRuleWeights w = rule_weights(valence, alpha, beta, gamma);
            return weights_dict(one_ring_spectrum(valence, w));
        },
        "valence"_a, "alpha"_a = py::none(), "beta"_a = 1.0, "gamma"_a = 1.0, spectrum_doc);
    m.def(
        "weights_for_subdominant",
        [](int valence, double lambda) {
            std::vector<TunedVertex> candidates;
            {
                const py::gil_scoped_release release;
                candidates = weights_for_subdominant(valence, lambda);
            }
            py::list out;
            for (const TunedVertex& v : candidates) {
                out.append(weights_dict(v));
            }
            return out;
        },
        "valence"_a, "lambda_"_a, subdominant_doc);
    m.def(
        "quadratic_shape_errors",
        [](int valence, std::optional<double> alpha, double beta, double gamma, int quadrature, int tile_levels,
           double poisson_ratio, int threads) {
            const VertexRuleWeights w = rule_weights(valence, alpha, beta, gamma);
            const TuningOptions options = options_of(quadrature, tile_levels, poisson_ratio, threads);
            ShapeErrors e;
            {
                const py::gil_scoped_release release;
                e = quadratic_shape_errors(valence, w, options);
            }
            return py::dict("cup"_a = e.cup, "saddle"_a = e.saddle);
        },
        "valence"_a, "alpha"_a = py::none(), "beta"_a = 1.0, "gamma"_a = 1.0, py::kw_only(), "quadrature"_a = 4,
        "tile_levels"_a = 10, "poisson_ratio"_a = 0.3, "threads"_a = 0, errors_doc);
    m.def(
        "tune_weights",
        [](int valence, const std::string& shape, int quadrature, int tile_levels, double poisson_ratio,
           std::optional<std::pair<double, double>> lambda_range, int samples, bool protect, int threads) {
            return tune(valence, shape, options_of(quadrature, tile_levels, poisson_ratio, threads), lambda_range,
                        samples, protect);
        },
        "valence"_a, "shape"_a = "cup", py::kw_only(), "quadrature"_a = 4, "tile_levels"_a = 10,
        "poisson_ratio"_a = 0.3, "lambda_range"_a = py::none(), "samples"_a = 61, "protect"_a = true, "threads"_a = 0,
        tune_doc);
    m.def(
        "tuned_vertex_weights",
        [](int valence, const std::string& shape, int quadrature, int tile_levels, double poisson_ratio, int threads) {
            const QuadraticShape which = parse_quadratic_shape(shape);
            const TuningOptions options = options_of(quadrature, tile_levels, poisson_ratio, threads);
            TunedVertex v;
            ShapeErrors e;
            {
                const py::gil_scoped_release release;
                v = tuned_vertex_weights(valence, which, options);
                e = quadratic_shape_errors(valence, v.weights, options);
            }
            return weights_dict(v, e);
        },
        "valence"_a, "shape"_a = "cup", py::kw_only(), "quadrature"_a = 4, "tile_levels"_a = 10,
        "poisson_ratio"_a = 0.3, "threads"_a = 0, tuned_doc);
    m.def("decompose_shapes", &decompose, "mesh"_a, "P"_a = py::none(), py::kw_only(), "weights"_a = py::none(),
          "min_valence"_a = 5, "poisson_ratio"_a = 0.3, decompose_doc);
    m.def(
        "decompose_shapes",
        [](const py::object& V, const py::object& F, const std::optional<py::object>& P, const py::object& weights,
           int min_valence,
           double poisson_ratio) { return decompose(mesh_from(V, F), P, weights, min_valence, poisson_ratio); },
        "V"_a, "F"_a, "P"_a = py::none(), py::kw_only(), "weights"_a = py::none(), "min_valence"_a = 5,
        "poisson_ratio"_a = 0.3);
}

}  // namespace limsurf::python
