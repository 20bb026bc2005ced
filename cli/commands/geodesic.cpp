// limsurf geodesic MESH --scheme S --source V [--source V ...] [--method dec|decsnap|sec|secsnap|iga]
//   [--level L] [--degree D --tiles T] [--gradient auto|limit|subdivided] [--gradient-level G]
//   [--gradient-degree D] [--time-factor c] [--reference-level K] [--max-memory SIZE] [--threads N]
//   [-o OUT.ply|.vtk|.vtu] [--png OUT.png] [--json]:
// geodesic distance on the limit surface by the heat method (Crane et al. 2013) with the DEC or
// SEC operators of --method, or Galerkin with the limit basis (iga) (SEC §4.2; apps/geodesics.h).
// With --reference-level K it also runs the heat method with DEC on the K-times subdivided mesh
// (the paper's reference, same t) and reports the relative L² and L∞ differences of the
// subdivided distance from it.
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
#include "limsurf/apps/geodesics.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/render/render.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct GeodesicCommandOptions {
    std::string input;
    std::string scheme;
    std::vector<Index> sources;
    std::string method = "sec";
    int level = 3;
    std::string gradient = "auto";
    int gradient_level = -1;
    int gradient_degree = 2;
    int degree = 8;  // iga: quadrature degree per tile
    int tiles = 6;   // iga: tile levels towards extraordinary vertices
    double time_factor = 1.0;
    int reference_level = -1;
    std::string max_memory;
    std::string output;
    std::string png;
    int isolines = 12;
    int threads = 0;
    bool json = false;
};

/// The picture of --png, in memory: it is drawn before any file is written.
Image draw_picture(const ControlMesh& mesh, const std::string& scheme, const Eigen::VectorXd& distance,
                   const GeodesicCommandOptions& options) {
    LimitSchemeOptions limit_options;
    limit_options.scheme = scheme;
    const LimitBasis basis = make_limit_basis(mesh, limit_options);
    TessellationOptions tess;
    tess.resolution = automatic_resolution(basis);
    tess.num_threads = options.threads;
    const LimitTessellation surface = tessellate_limit_surface(basis, mesh.positions(), tess);
    RenderOptions render;
    render.colormap = Colormap::Viridis;
    render.num_threads = options.threads;
    render.isolines = options.isolines;
    return render_tessellation(surface, evaluate_vertex_field(surface, distance), render).image;
}

int solve_and_report(const BuildResult& built, const GeodesicCommandOptions& options) {
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    LimitSchemeOptions limit_options;
    limit_options.scheme = options.scheme;
    GeodesicOptions geodesic;
    geodesic.heat.method = parse_laplacian_method(options.method);
    geodesic.heat.level = options.level;
    geodesic.heat.gradient = parse_heat_gradient(options.gradient);
    geodesic.heat.gradient_level = options.gradient_level;
    geodesic.heat.gradient_quadrature.degree = options.gradient_degree;
    geodesic.heat.iga_quadrature.degree = options.degree;
    geodesic.heat.iga_quadrature.subdivide_near_extraordinary = options.tiles;
    geodesic.heat.time_factor = options.time_factor;
    geodesic.heat.scheme_options = scheme_rules(mesh, limit_options);
    geodesic.heat.num_threads = options.threads;
    if (options.reference_level >= 0) {
        geodesic.reference_level = options.reference_level;
    }
    geodesic.max_memory = memory_budget(options.max_memory);
    const GeodesicResult result =
        geodesic_distance(mesh, limit_schemes().at(options.scheme), options.sources, geodesic);
    const bool sec = has_level(geodesic.heat.method);
    const Eigen::VectorXd& d = result.distance;
    nlohmann::json out{{"scheme", options.scheme},
                       {"method", options.method},
                       {"level", sec ? options.level : 0},
                       {"quadrature", geodesic.heat.method == LaplacianMethod::Iga
                                          ? nlohmann::json{{"degree", options.degree}, {"tiles", options.tiles}}
                                          : nlohmann::json(nullptr)},
                       {"gradient", result.gradient},
                       {"gradient_level", result.gradient_level ? nlohmann::json(*result.gradient_level) : nullptr},
                       {"vertices", t.num_vertices()},
                       {"closed", t.is_closed()},
                       {"sources", options.sources},
                       {"time_factor", options.time_factor},
                       {"t", result.time_step},
                       {"mean_edge_length", result.mean_edge_length},
                       {"max_edge_length", result.max_edge_length},
                       {"distance_min", d.minCoeff()},
                       {"distance_max", d.maxCoeff()},
                       {"limit_distance_min", result.limit_distance.minCoeff()},
                       {"limit_distance_max", result.limit_distance.maxCoeff()},
                       {"source_values", std::vector<double>(result.source_values.begin(), result.source_values.end())},
                       {"seconds",
                        {{"setup", result.setup_seconds},
                         {"factorisation", result.factorisation_seconds},
                         {"solve", result.solve_seconds}}}};
    if (result.reference) {
        out["reference"] = {{"level", result.reference->level},
                            {"method", "dec"},
                            {"vertices", result.reference->vertices},
                            {"l2_relative", result.reference->l2},
                            {"linf_relative", result.reference->linf}};
    }
    if (!options.output.empty()) {
        out["output"] = options.output;
    }
    if (!options.png.empty()) {
        out["png"] = options.png;
    }
    require_finite(out);  // before anything is written
    const std::optional<Image> picture =
        options.png.empty() ? std::nullopt : std::optional<Image>(draw_picture(mesh, options.scheme, d, options));
    if (!options.output.empty()) {
        const std::vector<VertexField> fields{{"distance", d}, {"limit_distance", result.limit_distance}};
        write_vertex_data(options.output, to_polygon_soup(mesh), fields);
    }
    if (picture) {
        write_png(options.png, *picture);
    }
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << std::setprecision(6) << "geodesic    heat method, " << options.method
              << (sec ? " level " + std::to_string(options.level) : std::string()) << ", " << t.num_vertices()
              << " unknowns, " << options.sources.size() << " source(s)\ngradient    " << result.gradient
              << (result.gradient == "subdivided" ? " level " + std::to_string(*result.gradient_level) : std::string())
              << "\ntime step   t = " << result.time_step << " (" << options.time_factor << " x mean edge length "
              << result.mean_edge_length << " squared; max edge " << result.max_edge_length << ")\ndistance    min "
              << d.minCoeff() << "  max " << d.maxCoeff()
              << " (on the limit surface: " << result.limit_distance.minCoeff() << " .. "
              << result.limit_distance.maxCoeff() << ")\nat sources  " << result.source_values.transpose()
              << "\nseconds     set-up " << result.setup_seconds << ", factorisation " << result.factorisation_seconds
              << ", solve " << result.solve_seconds << '\n';
    if (result.reference) {
        std::cout << "reference   heat method with dec on level " << result.reference->level << " ("
                  << result.reference->vertices << " vertices): relative L2 " << result.reference->l2
                  << ", relative Linf " << result.reference->linf << '\n';
    }
    for (const std::string& file : {options.output, options.png}) {
        if (!file.empty()) {
            std::cout << "wrote       " << file << '\n';
        }
    }
    return exit_ok;
}

int run_geodesic(const GeodesicCommandOptions& options) {
    check_output_paths({options.output, options.png}, {options.input});
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.output, options.png}, [&] { return solve_and_report(built, options); });
}

}  // namespace

void add_geodesic_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<GeodesicCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "geodesic", "Geodesic distance on the limit surface by the heat method with DEC or SEC operators (SEC §4.2)");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme")
        ->required()
        ->check(CLI::IsMember({"loop", "catmull-clark"}));
    cmd->add_option("--source", options->sources, "Source vertex (0-based control vertex index; repeatable)")
        ->required();
    add_laplacian_method_options(cmd, options->method, options->level);
    add_iga_quadrature_options(cmd, options->degree, options->tiles);
    cmd->add_option("--gradient", options->gradient,
                    "sec, secsnap: normalise the heat gradient on the limit surface (limit) or on the control "
                    "mesh subdivided --gradient-level times (subdivided); auto (default): subdivided when "
                    "--gradient-level is given or --level is below 3, else limit")
        ->check(CLI::IsMember({"auto", "limit", "subdivided"}));
    cmd->add_option("--gradient-level", options->gradient_level,
                    "sec, secsnap: level of the subdivided gradient (0..8, default: --level)")
        ->check(CLI::Range(0, 8));
    cmd->add_option("--gradient-degree", options->gradient_degree,
                    "sec, secsnap with the limit gradient: degree of the quadrature rule per face (1..8, default 2: "
                    "2 x 2 Gauss points on quads, 3 points on triangles)")
        ->check(CLI::Range(1, 8));
    cmd->add_option("--time-factor", options->time_factor,
                    "t = factor x (mean edge length of the control mesh)^2 (default 1, Crane et al.)");
    cmd->add_option(
           "--reference-level", options->reference_level,
           "Also run the heat method with DEC on the K-times subdivided mesh and report the differences (0..7)")
        ->check(CLI::Range(0, 7));
    add_memory_option(cmd, options->max_memory);
    add_threads_option(cmd, options->threads);
    cmd->add_option("-o,--output", options->output,
                    "Write the control mesh with fields distance and limit_distance (.ply, .vtk, .vtu)");
    cmd->add_option("--png", options->png, "Render the distance on the limit surface (PNG)");
    cmd->add_option("--isolines", options->isolines, "Isolines in the picture (0..100, default 12)")
        ->check(CLI::Range(0, 100));
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, cmd, &status] {
        status.exit_code = run_guarded([&] {
            check_method_options(*cmd, options->method);
            return run_geodesic(*options);
        });
    });
}

}  // namespace limsurf::cli
