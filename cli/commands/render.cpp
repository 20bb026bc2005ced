// limsurf render MESH --scheme S [--field mean-curvature|gaussian-curvature|FILE.vtk:NAME] [--control-mesh]
// [--isolines N] [--view iso|front|top|AZ,EL] [--size WxH] [--resolution N] [--range MIN,MAX]
// [--colormap viridis|coolwarm] [--threads N] -o OUT.png|OUT.glb [--json]: a picture of the limit surface
// (docs/guide/render.md), or its tessellation as glTF.
#include "limsurf/render/render.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/io/gltf.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vtk.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct RenderCommandOptions {
    std::string input;
    LimitSchemeOptions scheme;
    std::string field;
    bool control_mesh = false;
    int isolines = 0;
    std::string view = "iso";
    std::string size = "1200x900";
    int resolution = 0;  // 0: automatic_resolution()
    std::string range;
    std::string colormap = "viridis";
    int supersampling = 2;
    bool no_color_bar = false;
    std::string output;
    int threads = 0;
    bool json = false;
};

/// What --field asks for.
struct FieldRequest {
    enum class Kind { None, MeanCurvature, GaussianCurvature, VertexFile } kind = Kind::None;
    std::string file;  // VertexFile: the VTK file
    std::string name;  // the field's name (the VTK array, or mean_curvature / gaussian_curvature)
};

FieldRequest parse_field(const std::string& text) {
    if (text.empty()) {
        return {};
    }
    if (text == "mean-curvature") {
        return {FieldRequest::Kind::MeanCurvature, {}, "mean_curvature"};
    }
    if (text == "gaussian-curvature") {
        return {FieldRequest::Kind::GaussianCurvature, {}, "gaussian_curvature"};
    }
    const auto colon = text.rfind(':');
    return {FieldRequest::Kind::VertexFile, text.substr(0, colon), text.substr(colon + 1)};
}

std::string check_field(const std::string& text) {
    if (text == "mean-curvature" || text == "gaussian-curvature") {
        return {};
    }
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) {
        return "expected mean-curvature, gaussian-curvature or FILE.vtk:NAME";
    }
    return {};
}

/// "MIN,MAX" as two finite numbers, MIN <= MAX.
std::optional<std::array<double, 2>> parse_range(const std::string& text) {
    const auto comma = text.find(',');
    if (comma == std::string::npos) {
        return std::nullopt;
    }
    std::istringstream lo_in(text.substr(0, comma));
    std::istringstream hi_in(text.substr(comma + 1));
    double lo = 0.0;
    double hi = 0.0;
    std::string rest;
    if (!(lo_in >> lo) || (lo_in >> rest) || !(hi_in >> hi) || (hi_in >> rest) || !std::isfinite(lo) ||
        !std::isfinite(hi) || lo > hi) {
        return std::nullopt;
    }
    return std::array<double, 2>{lo, hi};
}

/// The field at the tessellation's points, or empty.
Eigen::VectorXd tessellation_field(const FieldRequest& request, const LimitTessellation& tessellation,
                                   const ControlMesh& mesh, const std::string& mesh_file) {
    switch (request.kind) {
    case FieldRequest::Kind::None:
        return {};
    case FieldRequest::Kind::MeanCurvature:
        return tessellation.mean_curvature;
    case FieldRequest::Kind::GaussianCurvature:
        return tessellation.gaussian_curvature;
    case FieldRequest::Kind::VertexFile:
        break;
    }
    const Eigen::VectorXd values = read_vtk_point_scalar(request.file, request.name);
    LIMSURF_CHECK(values.size() == mesh.num_vertices(), InputError, request.file, ": '", request.name, "' has ",
                  values.size(), " values, but the mesh ", mesh_file, " has ", mesh.num_vertices(), " vertices");
    return evaluate_vertex_field(tessellation, values);
}

nlohmann::json result_json(const RenderCommandOptions& options, const FieldRequest& field,
                           const LimitTessellation& tessellation, const Eigen::VectorXd& values,
                           const std::optional<RenderResult>& picture) {
    nlohmann::json out{{"output", options.output},
                       {"format", picture ? "png" : "glb"},
                       {"resolution", tessellation.resolution},
                       {"points", tessellation.num_points()},
                       {"triangles", tessellation.num_triangles()}};
    out["field"] = field.kind == FieldRequest::Kind::None ? nlohmann::json(nullptr) : nlohmann::json(field.name);
    out["field_min"] = values.size() > 0 ? nlohmann::json(values.minCoeff()) : nlohmann::json(nullptr);
    out["field_max"] = values.size() > 0 ? nlohmann::json(values.maxCoeff()) : nlohmann::json(nullptr);
    if (picture) {
        out["width"] = picture->image.width;
        out["height"] = picture->image.height;
        out["coverage"] = picture->coverage;
        out["range"] =
            picture->has_field ? nlohmann::json{picture->range[0], picture->range[1]} : nlohmann::json(nullptr);
        out["view"] = {{"azimuth", parse_view(options.view).azimuth},
                       {"elevation", parse_view(options.view).elevation}};
    }
    return out;
}

int run_render(const RenderCommandOptions& options) {
    const FieldRequest field = parse_field(options.field);
    check_output_paths({options.output}, {options.input, field.file});
    const std::string ext = lower_extension(options.output);
    LIMSURF_CHECK(ext == ".png" || ext == ".glb", InputError, options.output, ": unknown output format '", ext,
                  "' (expected .png or .glb)");
    RenderOptions render;
    render.view = parse_view(options.view);
    parse_size(options.size, render.width, render.height);
    render.range = options.range.empty() ? std::nullopt : parse_range(options.range);
    render.colormap = colormap_from_name(options.colormap);
    render.num_threads = options.threads;
    render.isolines = options.isolines;
    render.supersampling = options.supersampling;
    render.color_bar = !options.no_color_bar;

    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    const ControlMesh& mesh = built.mesh;
    Eigen::VectorXd values;
    std::optional<RenderResult> picture;
    const LimitTessellation tessellation = naming_file(built.source, {field.file, options.output}, [&] {
        const LimitBasis basis = make_limit_basis(mesh, options.scheme);
        TessellationOptions tess;
        tess.num_threads = options.threads;
        tess.resolution = options.resolution > 0 ? options.resolution : automatic_resolution(basis);
        tess.curvature =
            field.kind == FieldRequest::Kind::MeanCurvature || field.kind == FieldRequest::Kind::GaussianCurvature;
        LimitTessellation t = tessellate_limit_surface(basis, mesh.positions(), tess);
        values = tessellation_field(field, t, mesh, options.input);
        return t;
    });
    if (ext == ".glb") {
        write_glb(options.output, triangle_surface(tessellation, values, field.name.empty() ? "field" : field.name,
                                                   render.colormap, render.range));
    } else {
        const ControlPolygon overlay =
            options.control_mesh ? control_polygon(mesh.topology(), mesh.positions()) : ControlPolygon{};
        picture = render_tessellation(tessellation, values, render, overlay);
        write_png(options.output, picture->image);
    }
    const nlohmann::json out = result_json(options, field, tessellation, values, picture);
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    require_finite(out);
    std::cout << "wrote       " << options.output << " (" << tessellation.num_triangles() << " triangles";
    if (picture) {
        std::cout << ", " << picture->image.width << "x" << picture->image.height << ", coverage "
                  << std::setprecision(3) << picture->coverage;
    }
    std::cout << ")\n";
    if (values.size() > 0) {
        std::cout << "field       " << field.name << " from " << std::setprecision(6) << values.minCoeff() << " to "
                  << values.maxCoeff() << '\n';
    }
    return exit_ok;
}

}  // namespace

void add_render_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<RenderCommandOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Picture of the limit surface (PNG), or its tessellation (glTF)");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    add_limit_scheme_options(cmd, options->scheme);
    cmd->add_option("--field", options->field,
                    "Colour by mean-curvature, gaussian-curvature, or FILE.vtk:NAME (a per-vertex scalar, e.g. "
                    "from 'limsurf poisson -o u.vtk')")
        ->check(CLI::Validator(check_field, "FIELD"));
    cmd->add_flag("--control-mesh", options->control_mesh, "Draw the control polygon over the surface");
    cmd->add_option("--isolines", options->isolines, "Isolines of the field (0..100)")->check(CLI::Range(0, 100));
    cmd->add_option("--view", options->view, "iso, front, top, or AZIMUTH,ELEVATION in degrees (default iso)")
        ->check(view_validator());
    cmd->add_option("--size", options->size, "Image size WIDTHxHEIGHT, 16..8192 each (default 1200x900)")
        ->check(size_validator());
    cmd->add_option("--resolution", options->resolution,
                    "Segments per ptex face edge of the tessellation (1..256; default: about 250000 points)")
        ->check(CLI::Range(1, 256));
    cmd->add_option("--range", options->range,
                    "Field values at the ends of the colour map, MIN,MAX (default: the field's min and max)")
        ->check(CLI::Validator(
            [](const std::string& text) {
                return parse_range(text) ? std::string() : "expected MIN,MAX, finite, MIN <= MAX";
            },
            "MIN,MAX"));
    cmd->add_option("--colormap", options->colormap, "viridis (default) or coolwarm (diverging, symmetric about 0)")
        ->check(CLI::IsMember({"viridis", "coolwarm"}));
    cmd->add_option("--supersampling", options->supersampling, "Anti-aliasing samples per pixel side (1..4, default 2)")
        ->check(CLI::Range(1, 4));
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--no-color-bar", options->no_color_bar, "Leave out the colour bar");
    cmd->add_option("-o,--output", options->output, "Output .png (a picture) or .glb (glTF); written atomically")
        ->required();
    cmd->add_flag("--json", options->json, "Print what was written as JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_render(*options); }); });
}

}  // namespace limsurf::cli
