// limsurf reverse IN -o OUT [--levels K] [--tolerance T] [--json]: reverse Catmull–Clark
// (iga-with-catmull-clark §3): recovers the coarse control mesh of a subdivided mesh by the
// least-squares fit on S0 and writes it (docs/guide/reverse.md).
#include "limsurf/refine/reverse.h"

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "limsurf/io/mesh_io.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct ReverseOptions {
    std::string input;
    std::string output;
    int levels = -1;  // -1: as many as possible
    double tolerance = 1e-9;
    std::string format;
    bool json = false;
};

/// The rules the file asked for, else limsurf's defaults (as subdivide reads them).
SchemeOptions scheme_options(const SchemeHints& hints) {
    SchemeOptions options;
    options.boundary = hints.boundary.value_or(options.boundary);
    options.creasing = hints.creasing.value_or(options.creasing);
    options.triangles = hints.triangles.value_or(options.triangles);
    return options;
}

int run_reverse(const ReverseOptions& options) {
    const MeshFormat format = output_format(options.output, options.format);  // refused before any work
    check_output_paths({options.output}, {options.input});
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.output}, [&] {
        const SchemeOptions scheme = scheme_options(built.mesh.hints());
        const ReverseResult result = reverse_catmull_clark(built.mesh, options.levels, scheme, options.tolerance);
        print_warnings(write_mesh(options.output, result.coarse, {.format = format}));
        if (options.json) {
            nlohmann::json steps = nlohmann::json::array();
            for (const ReverseStep& step : result.steps) {
                steps.push_back({{"fine_vertices", step.fine_vertices},
                                 {"fine_faces", step.fine_faces},
                                 {"coarse_vertices", step.coarse_vertices},
                                 {"coarse_faces", step.coarse_faces},
                                 {"residual_max", step.residual_max},
                                 {"residual_rms", step.residual_rms},
                                 {"unique", step.unique}});
            }
            print_json(
                {{"method", "least-squares"},
                 {"levels_requested", options.levels},
                 {"levels_reversed", result.levels_reversed},
                 {"boundary", to_string(scheme.boundary)},
                 {"creasing", to_string(scheme.creasing)},
                 {"triangles", to_string(scheme.triangles)},
                 {"input", {{"num_vertices", built.mesh.num_vertices()}, {"num_faces", built.mesh.num_faces()}}},
                 {"output", {{"num_vertices", result.coarse.num_vertices()}, {"num_faces", result.coarse.num_faces()}}},
                 {"per_level", steps},
                 {"output_file", options.output}});
        }
        return exit_ok;
    });
}

}  // namespace

void add_reverse_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<ReverseOptions>();
    CLI::App* cmd = app.add_subcommand(
        "reverse", "Reverse Catmull-Clark: recover the coarse control mesh of a subdivided mesh (least squares)");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply), all quads")->required();
    cmd->add_option("-o,--output", options->output, "Coarse mesh (.obj, .off, .ply); written atomically")->required();
    add_format_option(cmd, options->format);
    cmd->add_option("--levels", options->levels,
                    "Levels to reverse (1..16), or -1 (default): as many as possible, the first always, later "
                    "ones while their residual is within --tolerance")
        ->check(CLI::Range(-1, 16))
        ->check(CLI::Validator(
            [](std::string& text) {
                return text == "0" ? std::string("0 levels: give 1..16, or -1 for as many as possible") : std::string();
            },
            "", "not zero"));
    cmd->add_option("--tolerance", options->tolerance,
                    "With --levels -1: largest residual of a level after the first, relative to the bounding-box "
                    "diagonal")
        ->check(non_negative_number());
    cmd->add_flag("--json", options->json, "Print a JSON summary");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_reverse(*options); }); });
}

}  // namespace limsurf::cli
