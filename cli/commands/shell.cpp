// limsurf shell MESH [--scheme catmull-clark|loop] [--levels L] [--E E --nu NU --thickness T]
//   [--gravity G] [--pressure P] [--point-load 'x,y,z:fx,fy,fz']... [--fix 'FORMULA:xyz']...
//   [--probe 'x,y,z']... [--interpolate] [--surface 'F(x,y,z)'] [--degree D --tiles K] [--threads N]
//   [--json] [-o out.vtk]:
// linear Kirchhoff–Love shells on the limit surface (fem/shell.h). For each level 0..L it reports the
// displacement at the probes (vector and normal component), the strain energy and the solve's
// residual. Parsing and printing only: the problem is shell_problem (apps/shell.h), the levels
// solve_shell_levels.
#include "limsurf/apps/shell.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/threads_option.h"
#include "formula.h"
#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct ShellOptions {
    std::string input;
    std::string scheme = "catmull-clark";
    int levels = 0;
    double E = 1.0;
    double nu = 0.3;
    double thickness = 0.1;
    double gravity = 0.0;
    double pressure = 0.0;
    std::vector<std::string> point_loads;
    std::vector<std::string> fixes;
    std::vector<std::string> probes;
    bool interpolate = false;
    std::string surface;
    int degree = 6;
    int tiles = 4;
    std::string output;
    int threads = 0;
    bool json = false;
};

/// "a,b,c" as a vector; @p what names the option in the error.
Eigen::Vector3d parse_triple(const std::string& what, const std::string& text) {
    std::stringstream in(text);
    Eigen::Vector3d out;
    char comma = 0;
    const bool ok = (in >> out.x() >> comma) && comma == ',' && (in >> out.y() >> comma) && comma == ',' &&
                    (in >> out.z()) && (in >> std::ws).eof();
    LIMSURF_CHECK(ok && out.allFinite(), InputError, what, " '", text, "': expected three finite numbers x,y,z");
    return out;
}

ShellPointLoad parse_point_load(const std::string& text) {
    const auto colon = text.find(':');
    LIMSURF_CHECK(colon != std::string::npos, InputError, "--point-load '", text, "': expected x,y,z:fx,fy,fz");
    return {parse_triple("--point-load", text.substr(0, colon)), parse_triple("--point-load", text.substr(colon + 1))};
}

/// 'FORMULA:COMPONENTS': the boundary control vertices where the formula is non-zero get the listed
/// components (letters x, y, z) fixed.
ShellSupport parse_fix(const std::string& text) {
    const auto colon = text.rfind(':');
    LIMSURF_CHECK(colon != std::string::npos && colon > 0, InputError, "--fix '", text,
                  "': expected FORMULA:COMPONENTS, e.g. 'abs(y) > 24.99:xz'");
    const std::string formula = text.substr(0, colon), letters = text.substr(colon + 1);
    ShellSupport support;
    support.components = {false, false, false};
    for (const char c : letters) {
        LIMSURF_CHECK(c == 'x' || c == 'y' || c == 'z', InputError, "--fix '", text,
                      "': the components are letters among x, y, z");
        support.components[static_cast<std::size_t>(c - 'x')] = true;
    }
    LIMSURF_CHECK(!letters.empty(), InputError, "--fix '", text, "': no components after ':'");
    (void)evaluate_formula("--fix", formula, Points::Zero(1, 3));  // a syntax error is named now, not per vertex
    support.where = [formula](const Eigen::Vector3d& x) {
        return evaluate_formula("--fix", formula, Points(x.transpose()))(0) != 0.0;
    };
    return support;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
    return nlohmann::json::array({v.x(), v.y(), v.z()});
}

int run_shell(const ShellOptions& options) {
    check_output_paths({options.output}, {options.input});
    if (!options.surface.empty()) {
        check_formula("--surface", options.surface);
    }
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.output}, [&] {
        ShellStudyOptions study;
        study.material = ShellMaterial{options.E, options.nu, options.thickness};
        study.scheme = options.scheme == "loop" ? SchemeKind::Loop : SchemeKind::CatmullClark;
        study.levels = options.levels;
        study.quadrature = SamplerOptions{options.degree, options.tiles, options.threads};
        study.interpolate = options.interpolate;
        if (!options.surface.empty()) {
            const std::string F = options.surface;
            study.surface = [F](const Points& Q) { return evaluate_formula("--surface", F, Q); };
        }
        for (const std::string& f : options.fixes) {
            study.supports.push_back(parse_fix(f));
        }
        for (const std::string& p : options.point_loads) {
            study.point_loads.push_back(parse_point_load(p));
        }
        for (const std::string& p : options.probes) {
            study.probes.push_back(parse_triple("--probe", p));
        }
        study.gravity = options.gravity;
        study.pressure = options.pressure;
        LIMSURF_CHECK(study.gravity != 0.0 || study.pressure != 0.0 || !study.point_loads.empty(), InputError,
                      "shell: no load (give --gravity, --pressure or --point-load)");
        const ShellProblem problem = shell_problem(built.mesh.topology(), built.mesh.positions(), study);
        const std::vector<ShellLevel> levels =
            solve_shell_levels(built.mesh.topology(), built.mesh.positions(), problem, options.levels);
        nlohmann::json rows = nlohmann::json::array();
        for (const ShellLevel& l : levels) {
            nlohmann::json probes = nlohmann::json::array();
            for (const ShellProbe& p : l.probes) {
                probes.push_back({{"vertex", p.vertex},
                                  {"position", vector_json(p.position)},
                                  {"normal", vector_json(p.normal)},
                                  {"displacement", vector_json(p.displacement)},
                                  {"normal_displacement", p.displacement.dot(p.normal)}});
            }
            rows.push_back({{"level", l.level},
                            {"vertices", l.topology.num_vertices()},
                            {"faces", l.topology.num_faces()},
                            {"unknowns", l.solution.u.size()},
                            {"area", l.area},
                            {"strain_energy", 0.5 * l.solution.energy},
                            {"residual", l.solution.residual},
                            {"rigid_motions_removed", l.solution.free_rigid_motions},
                            {"probes", probes}});
        }
        nlohmann::json out{
            {"scheme", options.scheme},
            {"E", options.E},
            {"nu", options.nu},
            {"thickness", options.thickness},
            {"interpolate", problem.interpolate},
            {"surface", options.surface.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.surface)},
            {"solver", levels.back().solution.solver},
            {"levels", rows}};
        require_finite(out);
        if (!options.output.empty()) {
            // The finest control topology at its vertices' limit points, with the limit displacement there.
            const ShellLevel& finest = levels.back();
            const ShellVertexLimits limits = shell_vertex_limits(finest, problem.scheme);
            const Points& U = limits.displacements;
            ControlMesh surface(finest.topology, limits.positions);
            const std::vector<VertexField> fields{{"displacement", U}, {"displacement_magnitude", U.rowwise().norm()}};
            write_vertex_data(options.output, to_polygon_soup(surface), fields);
            out["output"] = options.output;
        }
        if (options.json) {
            print_json(out);
            return exit_ok;
        }
        std::cout << std::setprecision(7) << "shell       " << options.scheme << ", E = " << options.E
                  << ", nu = " << options.nu << ", t = " << options.thickness << "\n";
        for (const auto& row : out["levels"]) {
            std::cout << "level " << row["level"] << " (" << row["unknowns"] << " unknowns): strain energy "
                      << row["strain_energy"] << ", residual " << std::setprecision(2) << row["residual"].get<double>()
                      << std::setprecision(7) << ", rigid motions removed " << row["rigid_motions_removed"] << '\n';
            for (const auto& p : row["probes"]) {
                std::cout << "  at " << p["position"] << ": displacement " << p["displacement"] << ", normal "
                          << p["normal_displacement"] << '\n';
            }
        }
        return exit_ok;
    });
}

}  // namespace

void add_shell_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<ShellOptions>();
    CLI::App* cmd =
        app.add_subcommand("shell", "Linear Kirchhoff-Love thin shell on the limit surface (catmull-clark or loop)");
    cmd->add_option("input", options->input, "Control mesh, or points of the surface with --interpolate/--surface")
        ->required();
    cmd->add_option("--scheme", options->scheme, "catmull-clark (default) or loop")
        ->check(CLI::IsMember({"catmull-clark", "loop"}));
    cmd->add_option("--levels", options->levels, "Also solve on the mesh refined 1..L times (0..6)")
        ->check(CLI::Range(0, 6));
    cmd->add_option("--E", options->E, "Young's modulus (default 1)");
    cmd->add_option("--nu", options->nu, "Poisson's ratio (default 0.3)");
    cmd->add_option("--thickness", options->thickness, "Shell thickness t (default 0.1)");
    cmd->add_option("--gravity", options->gravity, "Self-weight: force per unit area along -z");
    cmd->add_option("--pressure", options->pressure, "Force per unit area along the normal (outwards if > 0)");
    cmd->add_option("--point-load", options->point_loads,
                    "'x,y,z:fx,fy,fz': a force at the limit point of the control vertex at (x,y,z); repeatable");
    cmd->add_option("--fix", options->fixes,
                    "'FORMULA:COMPONENTS': fix components (x, y, z) of the boundary control vertices where the "
                    "formula in x, y, z is non-zero, e.g. 'abs(y) > 24.99:xz'; repeatable");
    cmd->add_option("--probe", options->probes, "'x,y,z': report the displacement there (a vertex's limit point)");
    cmd->add_flag("--interpolate", options->interpolate,
                  "The input's vertices are points of the surface: fit the control points so that the limit "
                  "surface passes through them");
    cmd->add_option("--surface", options->surface,
                    "The exact surface as F(x,y,z) = 0: at every level the points are projected onto it and "
                    "fitted again (implies --interpolate)");
    cmd->add_option("--degree", options->degree, "Quadrature degree per tile (1..60, default 6)")
        ->check(CLI::Range(1, 60));
    cmd->add_option("--tiles", options->tiles, "Quadrature tile levels towards irregular vertices (0..30, default 4)")
        ->check(CLI::Range(0, 30));
    add_threads_option(cmd, options->threads);
    cmd->add_option("-o,--output", options->output,
                    "Write the finest mesh at its limit points with the displacement (.ply, .vtk, .vtu)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_shell(*options); }); });
}

}  // namespace limsurf::cli
