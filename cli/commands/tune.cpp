// limsurf tune --valence V [--shape cup|saddle] [--lambda L] [--quadrature N] [--tile-levels K]
//   [--poisson-ratio MU] [--lambda-range LO,HI] [--samples M] [--no-protect] [--curve FILE.csv]
//   [--threads N] [--json]: IGA-tuned Catmull–Clark weights of an extraordinary vertex (the search
// over the subdominant eigenvalue λ of tune_weights), or, with --lambda, the weights at one λ with
// both quadratic shapes' errors (a row of the paper's Table 1). docs/guide/tune.md.
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/analysis/weight_tuning.h"
#include "limsurf/io/atomic_file.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct TuneOptions {
    int valence = 0;
    std::string shape = "cup";
    double lambda = 0.0;
    bool has_lambda = false;
    int quadrature = TuningOptions{}.quadrature_points;
    int tile_levels = TuningOptions{}.tile_levels;
    double poisson_ratio = TuningOptions{}.poisson_ratio;
    std::string lambda_range;
    int samples = TuningRequest{}.curve_samples;
    bool no_protect = false;
    std::string curve;
    int threads = 0;
    bool json = false;
};

const std::map<std::string, QuadraticShape>& shape_names() {
    static const std::map<std::string, QuadraticShape> names{{"cup", QuadraticShape::Cup},
                                                             {"saddle", QuadraticShape::Saddle}};
    return names;
}

/// "LO,HI" with LO < HI, both finite (the library checks that they lie in the feasible range).
std::pair<double, double> parse_lambda_range(const std::string& text) {
    std::istringstream in(text);
    double low = 0.0, high = 0.0;
    char comma = 0;
    std::string rest;
    LIMSURF_CHECK((in >> low >> comma >> high) && comma == ',' && !(in >> rest), InputError,
                  "--lambda-range: expected LO,HI (e.g. 0.5,0.6), got '", text, "'");
    LIMSURF_CHECK(std::isfinite(low) && std::isfinite(high) && low < high, InputError,
                  "--lambda-range: expected finite LO < HI, got '", text, "'");
    return {low, high};
}

nlohmann::json weights_json(const TunedVertex& v, const ShapeErrors& e) {
    return {{"lambda", v.lambda},
            {"alpha", v.weights.alpha},
            {"beta", v.weights.beta},
            {"gamma", v.weights.gamma},
            {"constraint", to_string(v.constraint)},
            {"lambda3", v.lambda3},
            {"lambda4", v.lambda4},
            {"cup_error", e.cup},
            {"saddle_error", e.saddle}};
}

nlohmann::json range_json(double low, double high) {
    return nlohmann::json::array({low, high});
}

/// The columns of the curve's CSV, in the order of weights_json().
const std::vector<std::string>& curve_columns() {
    static const std::vector<std::string> columns{"lambda",  "alpha",   "beta",      "gamma",       "constraint",
                                                  "lambda3", "lambda4", "cup_error", "saddle_error"};
    return columns;
}

void write_curve(std::ostream& out, const nlohmann::json& curve) {
    const std::vector<std::string>& columns = curve_columns();
    for (std::size_t i = 0; i < columns.size(); ++i) {
        out << (i ? "," : "") << columns[i];
    }
    out << '\n' << std::setprecision(std::numeric_limits<double>::max_digits10);
    for (const nlohmann::json& row : curve) {
        for (std::size_t i = 0; i < columns.size(); ++i) {
            const nlohmann::json& value = row.at(columns[i]);
            out << (i ? "," : "");
            if (value.is_string()) {
                out << value.get<std::string>();
            } else {
                out << value.get<double>();
            }
        }
        out << '\n';
    }
}

void print_header(std::ostream& out) {
    out << std::left << std::setw(14) << "" << std::right << std::setw(11) << "lambda" << std::setw(15) << "alpha"
        << std::setw(12) << "beta" << std::setw(12) << "gamma"
        << "  " << std::left << std::setw(10) << "constraint" << std::right << std::setw(12) << "cup error"
        << std::setw(14) << "saddle error" << '\n';
}

/// One row of the table; every number after a space, so that a wide α (valence 100: ~10⁴) stays apart.
void print_row(std::ostream& out, const std::string& name, const nlohmann::json& w) {
    const auto column = [&](const char* key, int width, int precision) {
        out << ' ' << std::setw(width - 1) << std::setprecision(precision) << w.at(key).get<double>();
    };
    out << std::left << std::setw(14) << name << std::right << std::fixed;
    column("lambda", 11, 6);
    column("alpha", 15, 7);
    column("beta", 12, 7);
    column("gamma", 12, 7);
    out << "  " << std::left << std::setw(10) << w.at("constraint").get<std::string>() << std::right;
    column("cup_error", 12, 6);
    column("saddle_error", 14, 6);
    out << '\n';
    out.unsetf(std::ios::floatfield);
}

void print_settings(std::ostream& out, const nlohmann::json& j) {
    const nlohmann::json& f = j.at("feasible_range");
    out << std::setprecision(6) << "feasible lambda [" << f[0].get<double>() << ", " << f[1].get<double>()
        << "]; energy norm: " << j.at("quadrature_points").get<int>() << "x" << j.at("quadrature_points").get<int>()
        << " Gauss points, " << j.at("tile_levels").get<int>() << " tile levels, Poisson's ratio "
        << j.at("poisson_ratio").get<double>() << '\n';
}

void print_search(const nlohmann::json& j) {
    std::cout << "valence " << j.at("valence").get<int>() << ", tuned for the " << j.at("shape").get<std::string>()
              << '\n';
    print_settings(std::cout, j);
    const nlohmann::json& s = j.at("search_range");
    std::cout << "searched [" << s[0].get<double>() << ", " << s[1].get<double>() << "] on " << j.at("curve").size()
              << " samples, " << std::setprecision(3) << j.at("time_seconds").get<double>() << " s\n";
    print_header(std::cout);
    print_row(std::cout, "tuned", j.at("tuned"));
    print_row(std::cout, "unconstrained", j.at("unconstrained"));
    print_row(std::cout, "catmull-clark", j.at("classical"));
    const bool cup = j.at("shape").get<std::string>() == "cup";
    const char* other = cup ? "saddle" : "cup";
    if (!j.at("protect_other_shape").get<bool>()) {
        std::cout << "protection off: the " << other << " error is not held to Catmull-Clark's\n";
    } else if (j.at("protection_binds").get<bool>()) {
        std::cout << "the protection binds: the tuned lambda is where the " << other
                  << " error meets Catmull-Clark's (the unconstrained minimum would raise it)\n";
    } else {
        std::cout << "the protection does not bind: the " << other << " error stays at or below Catmull-Clark's\n";
    }
}

void print_candidates(const nlohmann::json& j) {
    std::cout << "valence " << j.at("valence").get<int>() << ", lambda " << std::setprecision(6)
              << j.at("lambda").get<double>() << ": " << j.at("candidates").size() << " candidate"
              << (j.at("candidates").size() == 1 ? "" : "s") << '\n';
    print_settings(std::cout, j);
    print_header(std::cout);
    int i = 0;
    for (const nlohmann::json& c : j.at("candidates")) {
        print_row(std::cout, "candidate " + std::to_string(++i), c);
    }
    print_row(std::cout, "catmull-clark", j.at("classical"));
}

TuningOptions tuning_options(const TuneOptions& options) {
    TuningOptions o;
    o.quadrature_points = options.quadrature;
    o.tile_levels = options.tile_levels;
    o.poisson_ratio = options.poisson_ratio;
    o.num_threads = options.threads;
    return o;
}

nlohmann::json common_json(const TuneOptions& options, const LambdaRange& feasible) {
    return {{"command", "tune"},
            {"valence", options.valence},
            {"quadrature_points", options.quadrature},
            {"tile_levels", options.tile_levels},
            {"poisson_ratio", options.poisson_ratio},
            {"feasible_range", range_json(feasible.low, feasible.high)}};
}

/// --lambda: the candidates of weights_for_subdominant() with both errors, and Catmull–Clark's.
nlohmann::json at_lambda(const TuneOptions& options) {
    const TuningOptions o = tuning_options(options);
    const LambdaRange feasible = feasible_subdominant_range(options.valence);
    nlohmann::json candidates = nlohmann::json::array();
    for (const TuningSample& c : candidates_at(options.valence, options.lambda, o)) {
        candidates.push_back(weights_json(c.vertex, c.errors));
    }
    const TunedVertex classical = one_ring_spectrum(options.valence, catmull_clark_weights(options.valence));
    nlohmann::json out = common_json(options, feasible);
    out["lambda"] = options.lambda;
    out["candidates"] = candidates;
    out["classical"] = weights_json(classical, quadratic_shape_errors(options.valence, classical.weights, o));
    return out;
}

/// The search of tune_weights().
nlohmann::json search(const TuneOptions& options) {
    TuningRequest request;
    request.valence = options.valence;
    request.shape = shape_names().at(options.shape);
    request.options = tuning_options(options);
    if (!options.lambda_range.empty()) {
        std::tie(request.lambda_low, request.lambda_high) = parse_lambda_range(options.lambda_range);
    }
    request.curve_samples = options.samples;
    request.protect_other_shape = !options.no_protect;
    const TuningResult r = tune_weights(request);
    nlohmann::json curve = nlohmann::json::array();
    for (const TuningSample& s : r.curve) {
        curve.push_back(weights_json(s.vertex, s.errors));
    }
    nlohmann::json out = common_json(options, r.feasible);
    out["shape"] = to_string(request.shape);
    out["search_range"] = range_json(r.searched.low, r.searched.high);
    out["protect_other_shape"] = request.protect_other_shape;
    out["protection_binds"] = r.protection_binds;
    out["tuned"] = weights_json(r.tuned, r.tuned_errors);
    out["unconstrained"] = weights_json(r.unconstrained.vertex, r.unconstrained.errors);
    out["classical"] = weights_json(r.classical, r.classical_errors);
    out["curve"] = curve;
    return out;
}

int run_tune(const TuneOptions& options) {
    check_output_paths({options.curve}, {});
    const auto start = std::chrono::steady_clock::now();
    nlohmann::json out = options.has_lambda ? at_lambda(options) : search(options);
    out["time_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    require_finite(out);
    if (!options.curve.empty()) {
        write_file_atomically(options.curve, [&](std::ostream& file) { write_curve(file, out.at("curve")); });
    }
    if (options.json) {
        print_json(out);
    } else if (options.has_lambda) {
        print_candidates(out);
    } else {
        print_search(out);
    }
    return exit_ok;
}

}  // namespace

void add_tune_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<TuneOptions>();
    CLI::App* cmd = app.add_subcommand(
        "tune", "IGA-tuned Catmull-Clark weights of an extraordinary vertex (energy-norm errors of cup and saddle)");
    cmd->add_option("--valence", options->valence, "Valence of the extraordinary vertex (3, 5..128)")->required();
    auto* shape = cmd->add_option("--shape", options->shape, "The quadratic shape whose error is minimised")
                      ->check(CLI::IsMember(names_of(shape_names())));
    auto* lambda = cmd->add_option("--lambda", options->lambda,
                                   "No search: the weights at this subdominant eigenvalue, with both errors");
    cmd->add_option("--quadrature", options->quadrature, "Gauss points per direction on each tile (1..10)");
    cmd->add_option("--tile-levels", options->tile_levels, "Tile levels towards the extraordinary vertex (0..20)");
    cmd->add_option("--poisson-ratio", options->poisson_ratio, "Poisson's ratio of the energy norm, in (-1, 0.5]");
    auto* range = cmd->add_option("--lambda-range", options->lambda_range,
                                  "LO,HI: the lambda interval searched (default: the whole feasible range)");
    auto* samples = cmd->add_option("--samples", options->samples, "Samples of the error curve over lambda (>= 3)");
    auto* no_protect = cmd->add_flag("--no-protect", options->no_protect,
                                     "Minimise the shape's error alone (default: the other shape's error may not "
                                     "exceed Catmull-Clark's)");
    auto* curve = cmd->add_option("--curve", options->curve, "Write the error curve as CSV to FILE, atomically");
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--json", options->json, "Print JSON");
    for (CLI::Option* search_only : {shape, range, samples, no_protect, curve}) {
        lambda->excludes(search_only);
    }
    cmd->callback([options, &status, lambda] {
        options->has_lambda = lambda->count() > 0;
        status.exit_code = run_guarded([&] { return run_tune(*options); });
    });
}

}  // namespace limsurf::cli
