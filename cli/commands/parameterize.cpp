// limsurf parameterize MESH --scheme loop|catmull-clark [--method dec|decsnap|sec|secsnap|iga] [--level L]
//   [--boundary free|circle] [--reference-level K] [--max-memory SIZE] [--degree D] [--tiles T]
//   [--threads N] [-o OUT.obj|.vtk|.vtu|.ply] [--texture-png OUT.png [--squares N] [--view V] [--size WxH]] [--json]:
// a map of the limit surface to the plane, (u, v) per control vertex (SEC §4.1): spectral conformal
// (Mullen et al. 2008, --boundary free) or the boundary on the unit circle by limit arc length with a
// harmonic interior (--boundary circle), with the inner products of --method or the limit basis
// (iga); reports the quasi-conformal distortion σ1/σ2 measured on the limit surface (SEC Fig. 1)
// and, for the circle,
// the L² and L∞ differences from DEC on the K-times subdivided mesh (SEC Fig. 5).
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/apps/parameterization.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/obj.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/render/camera.h"
#include "limsurf/render/image.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct ParameterizeCommandOptions {
    std::string input;
    std::string scheme;
    std::string method = "sec";
    int level = 3;
    std::string boundary = "free";
    int reference_level = -1;
    std::string max_memory;
    int degree = 6;
    int tiles = 3;
    std::string output;
    std::string texture_png;
    int squares = 10;
    std::string view = "iso";
    std::string size = "1200x900";
    int threads = 0;
    bool json = false;
};

nlohmann::json to_json(const ParameterizeCommandOptions& options, const ParameterizationOptions& p,
                       const ParameterizationResult& r) {
    const bool sec = has_level(p.method);
    const bool free = r.boundary == ParameterizationBoundary::Free;
    const QuasiConformalDistortion& d = r.distortion;
    nlohmann::json out{{"scheme", options.scheme},
                       {"method", options.method},
                       {"level", sec ? options.level : 0},
                       {"boundary", to_string(r.boundary)},
                       {"vertices", r.uv.rows()},
                       {"boundary_vertices", r.boundary_vertices},
                       {"boundary_loops", r.boundary_loops},
                       {"solver", r.solver},
                       {"eigenvalue", free ? nlohmann::json(*r.eigenvalue) : nlohmann::json(nullptr)},
                       {"iterations", r.iterations},
                       {"residual", r.residual},
                       {"boundary_length", free ? nlohmann::json(nullptr) : nlohmann::json(r.boundary_length)},
                       {"u_min", r.uv.col(0).minCoeff()},
                       {"u_max", r.uv.col(0).maxCoeff()},
                       {"v_min", r.uv.col(1).minCoeff()},
                       {"v_max", r.uv.col(1).maxCoeff()},
                       {"distortion",
                        {{"mean", d.mean},
                         {"max", d.max},
                         {"flipped", d.flipped},
                         {"flipped_area", d.flipped_area},
                         {"degenerate", d.degenerate},
                         {"samples", d.samples},
                         {"area", d.area},
                         {"quadrature", {{"degree", options.degree}, {"tiles", options.tiles}}}}},
                       {"times",
                        {{"assembly", r.times.assembly},
                         {"solve", r.times.solve},
                         {"distortion", r.times.distortion},
                         {"reference", r.times.reference}}}};
    if (r.reference) {
        out["reference"] = {{"level", r.reference->level},
                            {"method", "dec"},
                            {"vertices", r.reference->vertices},
                            {"l2_relative", r.reference->l2},
                            {"linf_relative", r.reference->linf}};
    }
    return out;
}

void write_map(const ControlMesh& mesh, const Eigen::MatrixXd& uv, const std::string& path) {
    const std::string extension = std::filesystem::path(path).extension().string();
    if (extension == ".obj" || extension == ".OBJ") {
        const PolygonSoup soup = to_polygon_soup(mesh);
        write_file_atomically(path, [&](std::ostream& out) { write_obj(out, soup, uv); });
        return;
    }
    const std::vector<VertexField> fields{{"u", uv.col(0)}, {"v", uv.col(1)}};
    write_vertex_data(path, to_polygon_soup(mesh), fields);
}

void print_text(const ParameterizeCommandOptions& options, const ParameterizationResult& r) {
    const bool sec = options.method == "sec" || options.method == "secsnap";
    const QuasiConformalDistortion& d = r.distortion;
    std::cout << std::setprecision(6) << "parameterize " << to_string(r.boundary) << " boundary, " << options.method
              << (sec ? " level " + std::to_string(options.level) : std::string()) << ", " << r.uv.rows()
              << " vertices (" << r.boundary_vertices << " on " << r.boundary_loops << " boundary loop"
              << (r.boundary_loops == 1 ? "" : "s") << "), " << r.solver << '\n';
    if (r.eigenvalue) {
        std::cout << "eigenvalue   " << *r.eigenvalue << " (L_C U = λ B U), residual " << r.residual << ", "
                  << r.iterations << " Lanczos restarts\n";
    } else {
        std::cout << "boundary     unit circle by limit arc length (limit boundary length " << r.boundary_length
                  << "), residual " << r.residual << '\n';
    }
    std::cout << "u            " << r.uv.col(0).minCoeff() << " .. " << r.uv.col(0).maxCoeff() << "\nv            "
              << r.uv.col(1).minCoeff() << " .. " << r.uv.col(1).maxCoeff() << "\ndistortion   σ1/σ2 mean " << d.mean
              << ", max " << d.max << " (1: conformal; " << d.samples << " points on the limit surface), flipped "
              << d.flipped << " (" << 100.0 * d.flipped_area << "% of the area)\n";
    if (r.reference) {
        std::cout << "reference    dec on level " << r.reference->level << " (" << r.reference->vertices
                  << " vertices): relative L2 " << r.reference->l2 << ", relative Linf " << r.reference->linf << '\n';
    }
    std::cout << "time         assembly " << r.times.assembly << " s, solve " << r.times.solve << " s, distortion "
              << r.times.distortion << " s";
    if (r.reference) {
        std::cout << ", reference " << r.times.reference << " s";
    }
    std::cout << '\n';
    if (!options.output.empty()) {
        std::cout << "wrote        " << options.output << '\n';
    }
    if (!options.texture_png.empty()) {
        std::cout << "wrote        " << options.texture_png << '\n';
    }
}

int parameterize_and_report(const BuildResult& built, const ParameterizeCommandOptions& options) {
    const ControlMesh& mesh = built.mesh;
    LimitSchemeOptions limit_options;
    limit_options.scheme = options.scheme;
    ParameterizationOptions p;
    p.method = parse_laplacian_method(options.method);
    p.level = options.level;
    p.boundary = parse_parameterization_boundary(options.boundary);
    p.scheme_options = scheme_rules(mesh, limit_options);
    p.distortion.degree = options.degree;
    p.distortion.tiles = options.tiles;
    p.distortion.num_threads = options.threads;
    p.num_threads = options.threads;
    if (options.reference_level >= 0) {
        p.reference_level = options.reference_level;
    }
    p.max_memory = memory_budget(options.max_memory);
    CheckerboardOptions checker;
    if (!options.texture_png.empty()) {  // options refused before the work
        checker.render.view = parse_view(options.view);
        (void)parse_size(options.size, checker.render.width, checker.render.height);  // checked by size_validator
        checker.squares = options.squares;
        checker.render.num_threads = options.threads;
    }
    const SchemeKind scheme = limit_schemes().at(options.scheme);
    const ParameterizationResult r = parameterize(mesh, scheme, p);
    nlohmann::json out = to_json(options, p, r);
    if (!options.output.empty()) {
        out["output"] = options.output;
    }
    if (!options.texture_png.empty()) {
        out["texture_png"] = options.texture_png;
    }
    require_finite(out);  // before anything is written
    if (!options.output.empty()) {
        write_map(mesh, r.uv, options.output);
    }
    if (!options.texture_png.empty()) {
        write_png(options.texture_png, render_uv_checkerboard(mesh, scheme, p.scheme_options, r.uv, checker).image);
    }
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    print_text(options, r);
    return exit_ok;
}

int run_parameterize(const ParameterizeCommandOptions& options) {
    check_output_paths({options.output, options.texture_png}, {options.input});
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.output, options.texture_png},
                       [&] { return parameterize_and_report(built, options); });
}

}  // namespace

void add_parameterize_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<ParameterizeCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "parameterize", "Map the limit surface to the plane: spectral conformal or circle boundary (SEC §4.1)");
    cmd->add_option("input", options->input, "Input mesh with boundary (.obj, .off, .ply)")->required();
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme")
        ->required()
        ->check(CLI::IsMember({"loop", "catmull-clark"}));
    add_laplacian_method_options(cmd, options->method, options->level);
    cmd->add_option("--boundary", options->boundary,
                    "free: spectral conformal (default); circle: boundary on the unit circle, harmonic interior")
        ->check(CLI::IsMember({"free", "circle"}));
    cmd->add_option("--reference-level", options->reference_level,
                    "circle: also solve with DEC on the K-times subdivided mesh and report the differences (0..7)")
        ->check(CLI::Range(0, 7));
    add_memory_option(cmd, options->max_memory);
    cmd->add_option("--degree", options->degree, "Distortion quadrature: degree per tile (1..20, default 6)")
        ->check(CLI::Range(1, 20));
    cmd->add_option("--tiles", options->tiles,
                    "Distortion quadrature: tile levels towards extraordinary vertices (0..10, default 3)")
        ->check(CLI::Range(0, 10));
    add_threads_option(cmd, options->threads);
    cmd->add_option("-o,--output", options->output,
                    "Write the control mesh with the map: .obj (vt per vertex), .vtk, .vtu or .ply (fields u, v)");
    cmd->add_option("--texture-png", options->texture_png, "Write a checkerboard texture view of the limit surface");
    cmd->add_option("--squares", options->squares, "Checker squares across the parameter domain (1..1000, default 10)")
        ->check(CLI::Range(1, 1000));
    cmd->add_option("--view", options->view, "View of the texture picture: iso, front, top or AZIMUTH,ELEVATION")
        ->check(view_validator());
    cmd->add_option("--size", options->size,
                    "Size of the texture picture, WIDTHxHEIGHT, 16..8192 each (default 1200x900)")
        ->check(size_validator());
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, cmd, &status] {
        status.exit_code = run_guarded([&] {
            check_level_option(*cmd, options->method);
            return run_parameterize(*options);
        });
    });
}

}  // namespace limsurf::cli
