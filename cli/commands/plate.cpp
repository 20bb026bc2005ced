// limsurf plate MESH (--load uniform|sinusoidal|single-wave|FORMULA [--pressure P] | --load-file FILE)
//   --support simply|clamped [--levels L] [--thickness T] [--E E] [--nu NU] [--degree D] [--json]
//   [-o deflection.vtk]:
// Kirchhoff–Love bending of the planar plate bounded by the limit surface of a planar Catmull–Clark
// control mesh (fem/plate.h). For each level 0..L (the control mesh refined l times: the same
// plate) it reports the deflection at the centre and at (a/4, b/4) of the bounding box, the largest
// deflection, and, for a simply supported rectangle under the uniform or sine loads, the relative
// errors against the Navier solution (centre, L2 and energy norm). --load-file reads one load value
// per control vertex, taken as control values of the load: p_h = Σ p_i φ_i, so b = M p with the
// mass matrix M of the limit basis; at level l the values are carried by the subdivision matrices,
// p_l = S0 p_{l−1}, so every level sees the same load p_h.
#include "limsurf/fem/plate.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "formula.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/refine/refine.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct PlateOptions {
    std::string input;
    std::string load = "uniform";
    std::string load_file;  ///< one load value per control vertex (control values of p), or empty
    double pressure = 1e4;
    std::string support = "simply";
    int levels = 0;
    double thickness = 0.1;
    double E = 2e11;
    double nu = 0.3;
    int degree = 6;
    std::string output;
    bool json = false;
};

/// The plate's bounding rectangle [x0, x0 + a] × [y0, y0 + b].
struct Rectangle {
    double x0 = 0, y0 = 0, a = 0, b = 0;
};

int run_plate(const PlateOptions& options) {
    if (!options.output.empty()) {
        refuse_overwriting_inputs(options.output, {options.input, options.load_file});
    }
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.load_file, options.output}, [&] {
        const PlateMaterial material{options.E, options.nu, options.thickness};
        const PlateSupport support =
            options.support == "clamped" ? PlateSupport::Clamped : PlateSupport::SimplySupported;
        const Points& X0 = built.mesh.positions();
        Rectangle box;
        box.x0 = X0.col(0).minCoeff();
        box.y0 = X0.col(1).minCoeff();
        box.a = X0.col(0).maxCoeff() - box.x0;
        box.b = X0.col(1).maxCoeff() - box.y0;
        const double pi = std::numbers::pi;
        const double p = options.pressure;
        // The sine loads of the seed's Table 2 (two waves) and the single wave, over the bounding box.
        const auto sine = [&](int waves) {
            return [&, waves](const Points& P) {
                return Eigen::VectorXd(p * (waves * pi * (P.col(0).array() - box.x0) / box.a).sin() *
                                       (waves * pi * (P.col(1).array() - box.y0) / box.b).sin());
            };
        };
        SurfaceFunction load;
        int waves = 0;
        const bool per_vertex = !options.load_file.empty();
        // Control values of the load on the current level (--load-file): read for the control mesh,
        // carried to each refined level by its S0.
        Eigen::VectorXd load_values;
        if (per_vertex) {
            load_values = read_vertex_values(options.load_file, built.mesh.topology().num_vertices());
        } else if (options.load == "uniform") {
            load = [&](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), p); };
        } else if (options.load == "sinusoidal") {
            waves = 2;
            load = sine(2);
        } else if (options.load == "single-wave") {
            waves = 1;
            load = sine(1);
        } else {
            load = [&](const Points& P) { return evaluate_formula("--load", options.load, P); };
        }
        const double D = material.bending_rigidity();
        const bool navier = !per_vertex && support == PlateSupport::SimplySupported &&
                            (options.load == "uniform" || waves > 0);  // the rectangle is checked below
        const auto exact = [&](double x, double y) {
            return waves == 0 ? navier_uniform(box.a, box.b, D, p, x - box.x0, y - box.y0, 1e-10)
                              : navier_sine(box.a, box.b, D, p, waves, waves, x - box.x0, y - box.y0);
        };
        nlohmann::json levels = nlohmann::json::array();
        Topology t = built.mesh.topology();
        Points X = X0;
        Eigen::VectorXd last_w;
        bool rectangle = true;
        for (int level = 0; level <= options.levels; ++level) {
            if (level > 0) {
                Level next = refine(t, SchemeKind::CatmullClark);
                X = next.S0 * X;
                if (per_vertex) {
                    load_values = next.S0 * load_values;
                }
                t = std::move(next.topology);
            }
            const LimitBasis basis(t, SchemeKind::CatmullClark);
            const LimitSampler sampler(basis, SamplerOptions{options.degree, 6, 0});
            const PlateSolution solution =
                per_vertex ? solve_plate(t, sampler, X, material, support, load_values)
                           : solve_plate(t, sampler, X, material, support, load);
            const auto deflection_at = [&](double x, double y) -> std::optional<double> {
                SurfacePoint point;
                if (!locate_planar_point(basis, X, x, y, point)) {
                    return std::nullopt;
                }
                const LimitWeights w = basis.evaluate(point, DerivativeOrder::Value);
                double value = 0.0;
                for (Index i = 0; i < w.size(); ++i) {
                    value += w.w(Value, i) * solution.w(w.vertices[static_cast<std::size_t>(i)]);
                }
                return value;
            };
            const auto centre = deflection_at(box.x0 + box.a / 2, box.y0 + box.b / 2);
            const auto quarter = deflection_at(box.x0 + box.a / 4, box.y0 + box.b / 4);
            // Largest deflection and, against Navier, the L2 error and the work ∫ p w dA.
            double largest = 0.0, l2 = 0.0, l2_exact = 0.0, work = 0.0, area = 0.0;
            for (Index s = 0; s < sampler.num_samples(); ++s) {
                const Eigen::Matrix<double, 6, 3> Dx = sampler.evaluate(X, s);
                const double dA = sampler.weight(s) * std::abs(Dx(Du, 0) * Dx(Dv, 1) - Dx(Du, 1) * Dx(Dv, 0));
                double wh = 0.0;
                const auto W = sampler.limit_weights(s);
                const auto verts = sampler.vertices(s);
                for (std::size_t j = 0; j < verts.size(); ++j) {
                    wh += W(Value, static_cast<Index>(j)) * solution.w(verts[j]);
                }
                largest = std::max(largest, std::abs(wh));
                area += dA;
                if (navier) {
                    const double we = exact(Dx(Value, 0), Dx(Value, 1));
                    const Points here = Dx.row(Value);
                    l2 += dA * (wh - we) * (wh - we);
                    l2_exact += dA * we * we;
                    work += dA * load(here)(0) * we;
                }
            }
            if (level == 0) {
                rectangle = std::abs(area - box.a * box.b) <= 1e-6 * box.a * box.b;  // quadrature-accurate
            }
            nlohmann::json entry{{"level", level},
                                 {"vertices", t.num_vertices()},
                                 {"faces", t.num_faces()},
                                 {"centre_deflection", centre ? nlohmann::json(*centre) : nlohmann::json(nullptr)},
                                 {"quarter_deflection", quarter ? nlohmann::json(*quarter) : nlohmann::json(nullptr)},
                                 {"max_deflection", largest},
                                 {"residual", solution.residual}};
            if (navier && rectangle) {
                const double wc = exact(box.x0 + box.a / 2, box.y0 + box.b / 2);
                const double wq = exact(box.x0 + box.a / 4, box.y0 + box.b / 4);
                entry["navier"] = {
                    {"centre_deflection", wc},
                    {"quarter_deflection", wq},
                    // A node of the exact deflection (the centre under Table 2's load) has no relative error.
                    {"centre_relative_error", centre && std::abs(wc) > 1e-9 * std::abs(wq)
                                                  ? nlohmann::json(*centre / wc - 1.0)
                                                  : nlohmann::json(nullptr)},
                    {"quarter_relative_error", quarter && std::abs(wq) > 1e-9 * std::abs(wc)
                                                   ? nlohmann::json(*quarter / wq - 1.0)
                                                   : nlohmann::json(nullptr)},
                    {"l2_relative_error", std::sqrt(l2 / l2_exact)},
                    {"energy_relative_error", std::sqrt(std::max(0.0, work - solution.energy) / work)}};
            }
            levels.push_back(entry);
            last_w = solution.w;
        }
        nlohmann::json out{{"load", per_vertex ? "file" : options.load},
                           {"pressure", per_vertex ? nlohmann::json(nullptr) : nlohmann::json(p)},
                           {"support", options.support},
                           {"E", options.E},
                           {"nu", options.nu},
                           {"thickness", options.thickness},
                           {"bending_rigidity", D},
                           {"rectangle", {{"x0", box.x0}, {"y0", box.y0}, {"a", box.a}, {"b", box.b}}},
                           {"levels", levels}};
        if (per_vertex) {
            out["load_file"] = options.load_file;
        }
        if (navier && !rectangle) {
            out["navier"] = "not compared: the plate is not its bounding rectangle";
        }
        require_finite(out);
        if (!options.output.empty()) {
            ControlMesh finest(t, X);
            std::vector<VertexField> fields{{"w", last_w}};
            if (per_vertex) {
                fields.push_back({"p", load_values});  // the load's control values on the finest level
            }
            write_vertex_data(options.output, to_polygon_soup(finest), fields);
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
        }
        return exit_ok;
    });
}

}  // namespace

void add_plate_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<PlateOptions>();
    CLI::App* cmd = app.add_subcommand(
        "plate", "Kirchhoff-Love plate bending on the limit surface of a planar catmull-clark control mesh");
    cmd->add_option("input", options->input, "Planar control mesh (z = 0; .obj, .off, .ply)")->required();
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
    cmd->add_option("-o,--output", options->output,
                    "Write the finest control mesh with the field w (.ply, .vtk, .vtu)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_plate(*options); }); });
}

}  // namespace limsurf::cli
