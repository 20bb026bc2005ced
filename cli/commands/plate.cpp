// limsurf plate MESH [--scheme catmull-clark|loop]
//   (--load uniform|sinusoidal|single-wave|FORMULA [--pressure P] | --load-file FILE)
//   --support simply|clamped [--levels L] [--thickness T] [--E E] [--nu NU] [--degree D] [--threads N] [--json]
//   [--tuned none|cup|saddle|auto [--decide-level K]] [-o deflection.vtk]:
// Kirchhoff–Love bending of the planar plate bounded by the limit surface of a planar Catmull–Clark
// (or, with --scheme loop, Loop) control mesh (fem/plate.h). For each level 0..L (the control mesh refined l times: the
// same plate) it reports the deflection at the centre and at (a/4, b/4) of the bounding box, the largest deflection,
// and, for a simply supported rectangle under the uniform or sine loads, the relative errors against the Navier
// solution (centre, L2 and energy norm). --load-file reads one load value per control vertex, taken as control values
// of the load: p_h = Σ p_i φ_i, so b = M p with the mass matrix M of the limit basis; at level l the values are carried
// by the subdivision matrices, p_l = S0 p_{l−1}, so every level sees the same load p_h. --tuned puts IGA-tuned weights
// at the interior extraordinary vertices of valence >= 5 (iga-tuned-catmull-clark-weights §3.4, §4; auto: two passes
// per level, R per vertex; with --decide-level K one cup pass on level K decides for every level, as the paper's §4).
// Parsing and printing only: the levels and their checks are solve_plate_levels (apps/plate.h).
#include "limsurf/apps/plate.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "formula.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct PlateOptions {
    std::string input;
    std::string scheme = "catmull-clark";
    std::string load = "uniform";
    std::string load_file;  ///< one load value per control vertex (control values of p), or empty
    double pressure = 1e4;
    std::string support = "simply";
    int levels = 0;
    double thickness = 0.1;
    double E = 2e11;
    double nu = 0.3;
    int degree = 6;
    std::string tuned = "none";
    std::optional<int> decide_level;  ///< --tuned auto: decide once on this level (the paper's §4)
    std::string output;
    int threads = 0;
    bool json = false;
};

/// A pass's deflections and, where there is one, its comparison with Navier's solution.
nlohmann::json pass_json(const std::optional<double>& centre, const std::optional<double>& quarter, double largest,
                         const std::optional<PlateNavierComparison>& navier) {
    const auto optional_json = [](const std::optional<double>& x) {
        return x ? nlohmann::json(*x) : nlohmann::json(nullptr);
    };
    nlohmann::json entry{{"centre_deflection", optional_json(centre)},
                         {"quarter_deflection", optional_json(quarter)},
                         {"max_deflection", largest}};
    if (navier) {
        entry["navier"] = {{"centre_deflection", navier->centre_deflection},
                           {"quarter_deflection", navier->quarter_deflection},
                           {"centre_relative_error", optional_json(navier->centre_relative_error)},
                           {"quarter_relative_error", optional_json(navier->quarter_relative_error)},
                           {"l2_relative_error", navier->l2_relative_error},
                           {"energy_relative_error", navier->energy_relative_error}};
    }
    return entry;
}

/// A tuned vertex: its weights and, for --tuned auto, the decomposition that chose them.
nlohmann::json tuned_vertex_json(const PlateTunedVertex& v) {
    nlohmann::json out{{"vertex", v.vertex},
                       {"valence", v.valence},
                       {"shape", to_string(v.shape)},
                       {"lambda", v.weights.lambda},
                       {"alpha", v.weights.weights.alpha},
                       {"beta", v.weights.weights.beta},
                       {"gamma", v.weights.weights.gamma}};
    if (v.decomposition) {
        const ShapeDecomposition& d = *v.decomposition;
        const auto array = [](const Eigen::Vector3d& x) { return nlohmann::json{x(0), x(1), x(2)}; };
        out["decomposition"] = {{"k3", d.k3},
                                {"k4", d.k4},
                                {"k5", d.k5},
                                // R is +inf without a saddle part and NaN without either: JSON has no
                                // such numbers, so null, with the verdict and whether there is a shape
                                {"ratio", std::isfinite(d.ratio) ? nlohmann::json(d.ratio) : nlohmann::json(nullptr)},
                                {"cup_dominates", d.cup_dominates()},
                                {"has_quadratic_part", d.has_quadratic_part},
                                {"position", array(d.position)},
                                {"tangents", {array(d.tangent1), array(d.tangent2)}}};
    }
    return out;
}

int run_plate(const PlateOptions& options) {
    check_output_paths({options.output}, {options.input, options.load_file});
    if (options.load_file.empty() && !plate_load_shape(options.load)) {
        check_formula("--load", options.load);
    }
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.load_file, options.output}, [&] {
        PlateStudyOptions study;
        study.material = PlateMaterial{options.E, options.nu, options.thickness};
        study.support = parse_plate_support(options.support);
        study.scheme = options.scheme == "loop" ? SchemeKind::Loop : SchemeKind::CatmullClark;
        study.levels = options.levels;
        study.quadrature = SamplerOptions{options.degree, 6, options.threads};
        study.tuning_options.num_threads = options.threads;  // the tuned weights' search (--tuned)
        study.tuning = parse_plate_tuning(options.tuned);
        study.decide_level = options.decide_level;
        PlateLoad load;
        load.pressure = options.pressure;
        const bool per_vertex = !options.load_file.empty();
        if (per_vertex) {
            // Control values of the load on the control mesh, carried to each refined level by its S0.
            load.shape = PlateLoadShape::Values;
            load.values = read_vertex_values(options.load_file, built.mesh.topology().num_vertices());
        } else if (const auto shape = plate_load_shape(options.load)) {
            load.shape = *shape;
        } else {
            load.shape = PlateLoadShape::Function;
            load.function = [&](const Points& P) { return evaluate_formula("--load", options.load, P); };
        }
        const PlateStudy result = solve_plate_levels(built.mesh.topology(), built.mesh.positions(), load, study);
        print_warnings(result.warnings);
        nlohmann::json levels = nlohmann::json::array();
        for (const PlateLevel& level : result.levels) {
            nlohmann::json entry{{"level", level.level},
                                 {"vertices", level.topology.num_vertices()},
                                 {"faces", level.topology.num_faces()},
                                 {"residual", level.solution.residual}};
            entry.update(
                pass_json(level.centre_deflection, level.quarter_deflection, level.max_deflection, level.navier));
            if (study.tuning != PlateTuning::None) {
                nlohmann::json vertices = nlohmann::json::array();
                for (const PlateTunedVertex& v : level.tuned_vertices) {
                    vertices.push_back(tuned_vertex_json(v));
                }
                entry["tuned_vertices"] = vertices;
            }
            if (level.first_pass) {
                const PlatePass& first = *level.first_pass;
                entry["first_pass"] =
                    pass_json(first.centre_deflection, first.quarter_deflection, first.max_deflection, first.navier);
            }
            levels.push_back(entry);
        }
        const PlateRectangle& box = result.rectangle;
        const double D = result.bending_rigidity;
        nlohmann::json out{
            {"scheme", options.scheme},
            {"load", per_vertex ? "file" : options.load},
            {"pressure", per_vertex ? nlohmann::json(nullptr) : nlohmann::json(options.pressure)},
            {"support", options.support},
            {"E", options.E},
            {"nu", options.nu},
            {"thickness", options.thickness},
            {"bending_rigidity", D},
            {"tuned", options.tuned},
            {"decide_level", options.decide_level ? nlohmann::json(*options.decide_level) : nlohmann::json(nullptr)},
            {"rectangle", {{"x0", box.x0}, {"y0", box.y0}, {"a", box.a}, {"b", box.b}}},
            {"levels", levels}};
        if (per_vertex) {
            out["load_file"] = options.load_file;
        }
        if (result.navier_load && !result.rectangle_plate) {
            out["navier"] = "not compared: the plate is not its bounding rectangle";
        }
        require_finite(out);
        if (!options.output.empty()) {
            const PlateLevel& finest = result.levels.back();
            ControlMesh mesh(finest.topology, finest.X);
            std::vector<VertexField> fields{{"w", finest.solution.w}};
            if (per_vertex) {
                fields.push_back({"p", finest.load_values});  // the load's control values on the finest level
            }
            write_vertex_data(options.output, to_polygon_soup(mesh), fields);
            out["output"] = options.output;
        }
        if (options.json) {
            print_json(out);
            return exit_ok;
        }
        std::cout << std::setprecision(8) << "plate       " << options.support << ", load "
                  << (per_vertex ? options.load_file : options.load) << ", D = " << D << "\n";
        for (const auto& entry : out["levels"]) {
            std::cout << "level " << entry["level"] << " (" << entry["faces"] << " faces): centre "
                      << entry["centre_deflection"] << ", (a/4, b/4) " << entry["quarter_deflection"] << ", max "
                      << entry["max_deflection"];
            if (entry.contains("navier")) {
                std::cout << std::setprecision(3) << "; vs Navier: centre " << entry["navier"]["centre_relative_error"]
                          << ", L2 " << entry["navier"]["l2_relative_error"] << ", energy "
                          << entry["navier"]["energy_relative_error"] << std::setprecision(8);
            }
            std::cout << '\n';
            if (entry.contains("first_pass") && entry["first_pass"].contains("navier")) {
                const auto& first = entry["first_pass"]["navier"];
                std::cout << std::setprecision(3) << "  first (cup) pass vs Navier: L2 " << first["l2_relative_error"]
                          << ", energy " << first["energy_relative_error"] << std::setprecision(8) << '\n';
            }
            for (const auto& v : entry.value("tuned_vertices", nlohmann::json::array())) {
                std::cout << "  vertex " << v["vertex"] << " (valence " << v["valence"] << "): " << v["shape"]
                          << " weights, lambda " << v["lambda"];
                if (v.contains("decomposition")) {
                    const auto& d = v["decomposition"];
                    if (!d["has_quadratic_part"]) {
                        std::cout << ", flat (no quadratic part: R undefined)";
                    } else if (d["ratio"].is_null()) {
                        std::cout << ", R = inf (no saddle part)";
                    } else {
                        std::cout << ", R = " << d["ratio"];
                    }
                    if (options.decide_level) {
                        std::cout << " (decided on level " << *options.decide_level << ")";
                    }
                }
                std::cout << '\n';
            }
        }
        if (out.contains("navier")) {
            std::cout << "Navier      " << out["navier"].get<std::string>() << '\n';
        }
        return exit_ok;
    });
}

}  // namespace

void add_plate_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<PlateOptions>();
    CLI::App* cmd =
        app.add_subcommand("plate", "Kirchhoff-Love plate bending on the limit surface of a planar control mesh");
    cmd->add_option("input", options->input, "Planar control mesh (z = 0; .obj, .off, .ply)")->required();
    cmd->add_option("--scheme", options->scheme,
                    "catmull-clark (default) or loop (a triangle mesh; tag its square corners with 't corner' to "
                    "keep a rectangle a rectangle)")
        ->check(CLI::IsMember({"catmull-clark", "loop"}));
    auto* load = cmd->add_option(
        "--load", options->load,
        "uniform, sinusoidal (p sin(2pi x/a) sin(2pi y/b), Table 2), single-wave, or a formula in x, y");
    auto* load_file = cmd->add_option("--load-file", options->load_file,
                                      "Load as control values: one value per control vertex of MESH, one per line "
                                      "(as poisson --rhs-file); carried to refined levels by S0");
    load->excludes(load_file);
    auto* pressure = cmd->add_option("--pressure", options->pressure, "Load amplitude p (default 1e4)");
    pressure->excludes(load_file);
    cmd->add_option("--support", options->support, "simply or clamped (default simply)")
        ->check(CLI::IsMember({"simply", "clamped"}));
    cmd->add_option("--levels", options->levels, "Also solve on the control mesh refined 1..L times (0..6)")
        ->check(CLI::Range(0, 6));
    cmd->add_option("--thickness", options->thickness, "Plate thickness t (default 0.1)");
    cmd->add_option("--E", options->E, "Young's modulus (default 2e11)");
    cmd->add_option("--nu", options->nu, "Poisson's ratio (default 0.3)");
    cmd->add_option("--degree", options->degree, "Quadrature degree per tile (1..60, default 6)")
        ->check(CLI::Range(1, 60));
    add_threads_option(cmd, options->threads);
    cmd->add_option("--tuned", options->tuned,
                    "Tuned weights at interior extraordinary vertices of valence >= 5: none (default), cup, "
                    "saddle, or auto (a cup pass, the cup-saddle ratio R per vertex, then a second pass)")
        ->check(CLI::IsMember({"none", "cup", "saddle", "auto"}));
    cmd->add_option("--decide-level", options->decide_level,
                    "With --tuned auto: decide cup or saddle once, from the cup pass on this level (0..6), and "
                    "keep the choice on every level, as the paper's section 4 does (default: every level decides)")
        ->check(CLI::Range(0, 6));
    cmd->add_option("-o,--output", options->output,
                    "Write the finest control mesh with the field w (.ply, .vtk, .vtu)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] {
        if (options->decide_level && options->tuned != "auto") {
            std::cerr << "error: --decide-level needs --tuned auto (see 'limsurf plate --help')\n";
            status.exit_code = exit_usage;
            return;
        }
        status.exit_code = run_guarded([&] { return run_plate(*options); });
    });
}

}  // namespace limsurf::cli
