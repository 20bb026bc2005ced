#include "limsurf/apps/plate.h"

#include <algorithm>
#include <array>
#include <cmath>
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
        return waves == 0 ? navier_uniform(box.a, box.b, D, p, x - box.x0, y - box.y0, 1e-10)
                          : navier_sine(box.a, box.b, D, p, waves, waves, x - box.x0, y - box.y0);
    };
    Topology t = topology;
    Points X = X0;
    Eigen::VectorXd load_values = per_vertex ? load.values : Eigen::VectorXd();
    bool rectangle = true;
    for (int level = 0; level <= options.levels; ++level) {
        if (level > 0) {
            Level next = refine(t, options.scheme);
            X = next.S0 * X;
            if (per_vertex) {
                load_values = next.S0 * load_values;
            }
            t = std::move(next.topology);
        }
        const LimitBasis basis(t, options.scheme);
        const LimitSampler sampler(basis, options.quadrature);
        PlateLevel entry;
        entry.level = level;
        entry.solution = per_vertex ? solve_plate(t, sampler, X, material, options.support, load_values)
                                    : solve_plate(t, sampler, X, material, options.support, f);
        const Eigen::VectorXd& w = entry.solution.w;
        entry.centre_deflection = deflection_at(basis, X, w, box.x0 + box.a / 2, box.y0 + box.b / 2);
        entry.quarter_deflection = deflection_at(basis, X, w, box.x0 + box.a / 4, box.y0 + box.b / 4);
        // Largest deflection and, against Navier, the L2 error and the work ∫ p w dA.
        double largest = 0.0, l2 = 0.0, l2_exact = 0.0, work = 0.0, area = 0.0;
        for (Index s = 0; s < sampler.num_samples(); ++s) {
            const Eigen::Matrix<double, 6, 3> Dx = sampler.evaluate(X, s);
            const double dA = sampler.weight(s) * std::abs(Dx(Du, 0) * Dx(Dv, 1) - Dx(Du, 1) * Dx(Dv, 0));
            double wh = 0.0;
            const auto W = sampler.limit_weights(s);
            const auto verts = sampler.vertices(s);
            for (std::size_t j = 0; j < verts.size(); ++j) {
                wh += W(Value, static_cast<Index>(j)) * w(verts[j]);
            }
            largest = std::max(largest, std::abs(wh));
            area += dA;
            if (navier) {
                const double we = exact(Dx(Value, 0), Dx(Value, 1));
                const Points here = Dx.row(Value);
                l2 += dA * (wh - we) * (wh - we);
                l2_exact += dA * we * we;
                work += dA * f(here)(0) * we;
            }
        }
        entry.max_deflection = largest;
        if (level == 0) {
            rectangle = std::abs(area - box.a * box.b) <= 1e-6 * box.a * box.b;  // quadrature-accurate
            out.rectangle_plate = rectangle;
        }
        if (navier && rectangle) {
            const double wc = exact(box.x0 + box.a / 2, box.y0 + box.b / 2);
            const double wq = exact(box.x0 + box.a / 4, box.y0 + box.b / 4);
            PlateNavierComparison c;
            c.centre_deflection = wc;
            c.quarter_deflection = wq;
            // A node of the exact deflection (the centre under Table 2's load) has no relative error.
            if (entry.centre_deflection && std::abs(wc) > 1e-9 * std::abs(wq)) {
                c.centre_relative_error = *entry.centre_deflection / wc - 1.0;
            }
            if (entry.quarter_deflection && std::abs(wq) > 1e-9 * std::abs(wc)) {
                c.quarter_relative_error = *entry.quarter_deflection / wq - 1.0;
            }
            c.l2_relative_error = std::sqrt(l2 / l2_exact);
            c.energy_relative_error = std::sqrt(std::max(0.0, work - entry.solution.energy) / work);
            entry.navier = c;
        }
        entry.topology = t;
        entry.X = X;
        if (per_vertex) {
            entry.load_values = load_values;
        }
        out.levels.push_back(std::move(entry));
    }
    return out;
}

}  // namespace limsurf
