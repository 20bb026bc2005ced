#include "limsurf/apps/plate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

constexpr std::array<std::pair<PlateLoadShape, const char*>, 5> shape_names{
    {{PlateLoadShape::Uniform, "uniform"},
     {PlateLoadShape::Sinusoidal, "sinusoidal"},
     {PlateLoadShape::SingleWave, "single-wave"},
     {PlateLoadShape::Function, "function"},
     {PlateLoadShape::Values, "values"}}};

PlateRectangle bounding_rectangle(const Points& X) {
    PlateRectangle box;
    box.x0 = X.col(0).minCoeff();
    box.y0 = X.col(1).minCoeff();
    box.a = X.col(0).maxCoeff() - box.x0;
    box.b = X.col(1).maxCoeff() - box.y0;
    return box;
}

/// The deflection w_h at the point (x, y) of the plate; empty outside it.
std::optional<double> deflection_at(const LimitBasis& basis, const Points& X, const Eigen::VectorXd& w, double x,
                                    double y) {
    SurfacePoint point;
    if (!locate_planar_point(basis, X, x, y, point)) {
        return std::nullopt;
    }
    const LimitWeights weights = basis.evaluate(point, DerivativeOrder::Value);
    double value = 0.0;
    for (Index i = 0; i < weights.size(); ++i) {
        value += weights.w(Value, i) * w(weights.vertices[static_cast<std::size_t>(i)]);
    }
    return value;
}

}  // namespace

std::optional<PlateLoadShape> plate_load_shape(const std::string& name) {
    for (std::size_t k = 0; k < 3; ++k) {  // the loads known by name
        if (name == shape_names[k].second) {
            return shape_names[k].first;
        }
    }
    return std::nullopt;
}

const char* to_string(PlateLoadShape shape) noexcept {
    for (const auto& [value, name] : shape_names) {
        if (value == shape) {
            return name;
        }
    }
    return "?";
}

const char* to_string(PlateTuning tuning) noexcept {
    switch (tuning) {
    case PlateTuning::None:
        return "none";
    case PlateTuning::Cup:
        return "cup";
    case PlateTuning::Saddle:
        return "saddle";
    case PlateTuning::Auto:
        return "auto";
    }
    return "?";
}

PlateTuning parse_plate_tuning(const std::string& name) {
    for (const PlateTuning t : {PlateTuning::None, PlateTuning::Cup, PlateTuning::Saddle, PlateTuning::Auto}) {
        if (name == to_string(t)) {
            return t;
        }
    }
    throw InputError("unknown tuning '" + name + "' (expected none, cup, saddle or auto)");
}

PlateSupport parse_plate_support(const std::string& name) {
    if (name == "simply") {
        return PlateSupport::SimplySupported;
    }
    if (name == "clamped") {
        return PlateSupport::Clamped;
    }
    throw InputError("unknown plate support '" + name + "' (expected simply or clamped)");
}

PlateStudy solve_plate_levels(const Topology& topology, const Points& X0, const PlateLoad& load,
                              const PlateStudyOptions& options) {
    LIMSURF_CHECK(options.levels >= 0 && options.levels <= 6, InputError, "plate: levels must be in 0..6, got ",
                  options.levels);
    LIMSURF_CHECK(options.support != PlateSupport::ClampedNitsche, InputError,
                  "plate: the study supports simply supported and clamped edges");
    LIMSURF_CHECK(X0.rows() == topology.num_vertices() && X0.cols() == 3, InputError, "plate: ", X0.rows(),
                  " points for ", topology.num_vertices(), " vertices");
    const bool per_vertex = load.shape == PlateLoadShape::Values;
    if (per_vertex) {
        LIMSURF_CHECK(load.values.size() == topology.num_vertices(), InputError, "plate: ", load.values.size(),
                      " load values for ", topology.num_vertices(), " control vertices");
    }
    LIMSURF_CHECK(load.shape != PlateLoadShape::Function || load.function, InputError,
                  "plate: a load function is missing");
    PlateStudy out;
    out.rectangle = bounding_rectangle(X0);
    const PlateRectangle& box = out.rectangle;
    const double pi = std::numbers::pi;
    const double p = load.pressure;
    // With p = 0 the plate does not bend, and the comparison with Navier's solution is 0/0.
    LIMSURF_CHECK(per_vertex || load.shape == PlateLoadShape::Function || std::isnormal(p), InputError,
                  "plate: the pressure p = ", p,
                  " must be a non-zero finite number (with p = 0 the plate does not bend)");
    // The sine loads of the seed's Table 2 (two waves) and the single wave, over the bounding box.
    const auto sine = [&](int waves) {
        return [&, waves](const Points& P) {
            return Eigen::VectorXd(p * (waves * pi * (P.col(0).array() - box.x0) / box.a).sin() *
                                   (waves * pi * (P.col(1).array() - box.y0) / box.b).sin());
        };
    };
    SurfaceFunction f;
    int waves = 0;
    switch (load.shape) {
    case PlateLoadShape::Uniform:
        f = [&](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), p); };
        break;
    case PlateLoadShape::Sinusoidal:
        waves = 2;
        f = sine(2);
        break;
    case PlateLoadShape::SingleWave:
        waves = 1;
        f = sine(1);
        break;
    case PlateLoadShape::Function:
        f = load.function;
        break;
    case PlateLoadShape::Values:
        break;
    }
    const PlateMaterial& material = options.material;
    const double D = material.bending_rigidity();
    out.bending_rigidity = D;
    out.navier_load = options.support == PlateSupport::SimplySupported &&
                      (load.shape == PlateLoadShape::Uniform || waves > 0);  // the rectangle is checked below
    const bool navier = out.navier_load;
    const auto exact = [&](double x, double y) {
        return waves == 0 ? levy_uniform(box.a, box.b, D, p, x - box.x0, y - box.y0, 1e-12)
                          : navier_sine(box.a, box.b, D, p, waves, waves, x - box.x0, y - box.y0);
    };
    const bool tuned = options.tuning != PlateTuning::None;
    LIMSURF_CHECK(!tuned || options.scheme == SchemeKind::CatmullClark, InputError,
                  "plate: tuned weights apply to catmull-clark only, not ", to_string(options.scheme));
    LIMSURF_CHECK(!options.decide_level || options.tuning == PlateTuning::Auto, InputError,
                  "plate: a decision level applies to --tuned auto only");
    LIMSURF_CHECK(!options.decide_level || (*options.decide_level >= 0 && *options.decide_level <= 6), InputError,
                  "plate: the decision level must be in 0..6, got ", options.decide_level.value_or(0));
    // The vertices to tune and each (valence, shape)'s weights, tuned once.
    std::vector<std::pair<Index, int>> candidates;
    if (tuned) {
        for (Index v = 0; v < topology.num_vertices(); ++v) {
            const int n = static_cast<int>(topology.valence(v));
            if (n >= 5 && n <= max_limit_size && !topology.is_boundary_vertex(v)) {
                candidates.emplace_back(v, n);
            }
        }
        if (candidates.empty()) {
            out.warnings.push_back(detail::concat("--tuned ", to_string(options.tuning),
                                                  ": no interior extraordinary vertex of valence 5 or more; "
                                                  "catmull-clark's own weights"));
        }
    }
    std::map<std::pair<int, QuadraticShape>, TunedVertex> tuned_weights;
    const auto choice = [&](Index v, int n, QuadraticShape shape) {
        const auto key = std::make_pair(n, shape);
        auto found = tuned_weights.find(key);
        if (found == tuned_weights.end()) {
            found = tuned_weights.emplace(key, tuned_vertex_weights(n, shape, options.tuning_options)).first;
        }
        PlateTunedVertex c;
        c.vertex = v;
        c.valence = n;
        c.shape = shape;
        c.weights = found->second;
        return c;
    };
    const auto weights_of = [](const std::vector<PlateTunedVertex>& choices) {
        TunedWeights w;
        for (const PlateTunedVertex& c : choices) {
            w.set_vertex(c.vertex, c.weights.weights);
        }
        return w;
    };
    const auto all_with = [&](QuadraticShape shape) {
        std::vector<PlateTunedVertex> choices;
        for (const auto& [v, n] : candidates) {
            choices.push_back(choice(v, n, shape));
        }
        return choices;
    };

    // The control mesh refined `level` times with the weights, and the load's control values there.
    struct Refined {
        Topology t;
        Points X;
        Eigen::VectorXd load_values;
    };
    const auto refined = [&](int level, const TunedWeights& weights) {
        Refined r{topology, X0, per_vertex ? load.values : Eigen::VectorXd()};
        for (int l = 0; l < level; ++l) {
            Level next = refine(r.t, options.scheme, SchemeOptions{}, weights);
            r.X = next.S0 * r.X;
            if (per_vertex) {
                r.load_values = next.S0 * r.load_values;
            }
            r.t = std::move(next.topology);
        }
        return r;
    };
    bool rectangle = true;
    // One solve and its checks.
    const auto solve_pass = [&](const Refined& mesh, const TunedWeights& weights, int level) {
        const LimitBasis basis(mesh.t, options.scheme, SchemeOptions{}, weights);
        const LimitSampler sampler(basis, options.quadrature);
        PlatePass pass;
        pass.solution = per_vertex ? solve_plate(mesh.t, sampler, mesh.X, material, options.support, mesh.load_values)
                                   : solve_plate(basis, sampler, mesh.X, material, options.support, f);
        const Eigen::VectorXd& w = pass.solution.w;
        pass.centre_deflection = deflection_at(basis, mesh.X, w, box.x0 + box.a / 2, box.y0 + box.b / 2);
        pass.quarter_deflection = deflection_at(basis, mesh.X, w, box.x0 + box.a / 4, box.y0 + box.b / 4);
        // Each sample once: its point, the area element of the flat plate and the deflection there.
        struct Sample {
            Eigen::RowVector3d x;
            double dA, wh;
        };
        std::vector<Sample> samples(static_cast<std::size_t>(sampler.num_samples()));
        double largest = 0.0, area = 0.0;
        for (Index s = 0; s < sampler.num_samples(); ++s) {
            const Eigen::Matrix<double, 6, 3> Dx = sampler.evaluate(mesh.X, s);
            Sample& at = samples[static_cast<std::size_t>(s)];
            at.x = Dx.row(Value);
            at.dA = sampler.weight(s) * std::abs(Dx(Du, 0) * Dx(Dv, 1) - Dx(Du, 1) * Dx(Dv, 0));
            at.wh = 0.0;
            const auto W = sampler.limit_weights(s);
            const auto verts = sampler.vertices(s);
            for (std::size_t j = 0; j < verts.size(); ++j) {
                at.wh += W(Value, static_cast<Index>(j)) * w(verts[j]);
            }
            largest = std::max(largest, std::abs(at.wh));
            area += at.dA;
        }
        pass.max_deflection = largest;
        if (level == 0) {
            // Is the plate its bounding rectangle? Decided before Navier's series is summed at the
            // samples: on a plate far from its box (one vertex 8 000 away: found by fuzz/commands.py)
            // the series needs 10⁵ terms a point, a minute in all, for a comparison not made.
            // Quadrature-accurate: 1e-6 with Catmull–Clark's weights; own β, γ make the patches next
            // to a tuned vertex bicubic on quarters only, which the tiles integrate to ~1e-5.
            rectangle = std::abs(area - box.a * box.b) <= 1e-4 * box.a * box.b;
            out.rectangle_plate = rectangle;
        }
        const bool compare = navier && rectangle;
        if (compare) {
            // Against Navier: the L2 error and the work ∫ p w dA.
            double l2 = 0.0, l2_exact = 0.0, work = 0.0;
            for (const Sample& at : samples) {
                const double we = exact(at.x(0), at.x(1));
                l2 += at.dA * (at.wh - we) * (at.wh - we);
                l2_exact += at.dA * we * we;
                work += at.dA * f(Points(at.x))(0) * we;
            }
            const double wc = exact(box.x0 + box.a / 2, box.y0 + box.b / 2);
            const double wq = exact(box.x0 + box.a / 4, box.y0 + box.b / 4);
            PlateNavierComparison c;
            c.centre_deflection = wc;
            c.quarter_deflection = wq;
            // A node of the exact deflection (the centre under Table 2's load) has no relative error.
            if (pass.centre_deflection && std::abs(wc) > 1e-9 * std::abs(wq)) {
                c.centre_relative_error = *pass.centre_deflection / wc - 1.0;
            }
            if (pass.quarter_deflection && std::abs(wq) > 1e-9 * std::abs(wc)) {
                c.quarter_relative_error = *pass.quarter_deflection / wq - 1.0;
            }
            // E = 1e308 gave w ~ 1e-304, whose squares underflow: the relative errors came out 0/0.
            LIMSURF_CHECK(std::isnormal(l2_exact) && std::isnormal(work), NumericalError,
                          "plate: Navier's deflection (largest ", std::max(std::abs(wc), std::abs(wq)),
                          ") is too small or too large for its squares to be doubles: state the problem in other "
                          "units (E, the thickness and the load)");
            c.l2_relative_error = std::sqrt(l2 / l2_exact);
            c.energy_relative_error = std::sqrt(std::max(0.0, work - pass.solution.energy) / work);
            pass.navier = c;
        }
        return pass;
    };
    // §3.4: the cup–saddle decomposition of a pass's solution at each tuned vertex.
    const auto decompose = [&](const Refined& mesh, const Eigen::VectorXd& w, const TunedWeights& weights, int level) {
        Points P = mesh.X;
        P.col(2) = w;
        const double nu = material.nu;  // μ of (38): the plate's own
        if (level > 0) {
            return decompose_shapes(mesh.t, P, weights, 5, nu);
        }
        const Level finer = refine(mesh.t, options.scheme, SchemeOptions{}, weights);
        auto d = decompose_shapes(finer.topology, Points(finer.S0 * P), weights, 5, nu);
        for (ShapeDecomposition& e : d) {  // back to level 0: k_j / λ_j, the tangents / λ
            const TunedVertex s = one_ring_spectrum(e.valence, weights.at(e.vertex, e.valence));
            e.k3 /= s.lambda3;
            e.k4 /= s.lambda4;
            e.k5 /= s.lambda4;
            e.tangent1 /= s.lambda;
            e.tangent2 /= s.lambda;
            e.ratio = cup_saddle_ratio(e.k3, e.k4, e.k5, nu);
        }
        return d;
    };

    // §3.4: the cup pass on one level and the choice it makes at each tuned vertex (refinement keeps
    // the vertices' numbers, so a choice holds on every level).
    const auto choose = [&](int level, std::optional<PlatePass>& first_pass) {
        std::vector<PlateTunedVertex> choices = all_with(QuadraticShape::Cup);
        const TunedWeights cup = weights_of(choices);
        const Refined first = refined(level, cup);
        first_pass = solve_pass(first, cup, level);
        const auto parts = decompose(first, first_pass->solution.w, cup, level);
        for (PlateTunedVertex& c : choices) {
            const auto found = std::find_if(parts.begin(), parts.end(),
                                            [&](const ShapeDecomposition& d) { return d.vertex == c.vertex; });
            LIMSURF_CHECK(found != parts.end(), NumericalError, "plate: no decomposition at vertex ", c.vertex);
            if (found->has_quadratic_part && !found->cup_dominates()) {  // flat: keep the cup pass's weights
                c = choice(c.vertex, c.valence, QuadraticShape::Saddle);
            }
            c.decomposition = *found;
        }
        return choices;
    };
    std::optional<PlatePass> decided_pass;
    const std::vector<PlateTunedVertex> decided =
        options.decide_level ? choose(*options.decide_level, decided_pass) : std::vector<PlateTunedVertex>{};

    for (int level = 0; level <= options.levels; ++level) {
        PlateLevel entry;
        entry.level = level;
        std::vector<PlateTunedVertex> choices;
        switch (options.tuning) {
        case PlateTuning::None:
            break;
        case PlateTuning::Cup:
        case PlateTuning::Saddle:
            choices = all_with(options.tuning == PlateTuning::Cup ? QuadraticShape::Cup : QuadraticShape::Saddle);
            break;
        case PlateTuning::Auto:
            if (!options.decide_level) {
                choices = choose(level, entry.first_pass);
            } else {
                choices = decided;
                if (level == *options.decide_level) {
                    entry.first_pass = decided_pass;
                }
            }
            break;
        }
        const TunedWeights weights = weights_of(choices);
        const Refined mesh = refined(level, weights);
        const PlatePass pass = solve_pass(mesh, weights, level);
        entry.solution = pass.solution;
        entry.centre_deflection = pass.centre_deflection;
        entry.quarter_deflection = pass.quarter_deflection;
        entry.max_deflection = pass.max_deflection;
        entry.navier = pass.navier;
        entry.tuned_vertices = std::move(choices);
        entry.topology = mesh.t;
        entry.X = mesh.X;
        if (per_vertex) {
            entry.load_values = mesh.load_values;
        }
        out.levels.push_back(std::move(entry));
    }
    return out;
}

}  // namespace limsurf
