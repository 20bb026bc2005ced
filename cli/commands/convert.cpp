// limsurf convert IN OUT: read, validate and write a mesh in another format.
#include <iostream>
#include <memory>
#include <string>

#include "commands/commands.h"
#include "commands/ply_encoding_option.h"
#include "limsurf/io/mesh_io.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct ConvertOptions {
    std::string input;
    std::string output;
    std::string ply_encoding;  ///< empty: ascii
    std::string format;
    bool strict_isolated = false;
};

int run_convert(const ConvertOptions& options) {
    // Refuse before reading: an unknown output format is a usage mistake.
    const MeshFormat format = output_format(options.output, options.format);
    check_output_paths({options.output}, {options.input});
    const BuildResult built =
        read_mesh(options.input,
                  {.isolated_vertices = options.strict_isolated ? IsolatedVertices::Error : IsolatedVertices::Drop});
    print_warnings(built.report);
    print_warnings(write_mesh(options.output, built.mesh,
                              {.ply_encoding = ply_encoding_from(options.ply_encoding, format), .format = format}));
    return exit_ok;
}

}  // namespace

void add_convert_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<ConvertOptions>();
    CLI::App* convert = app.add_subcommand("convert", "Convert a mesh between OBJ, OFF and PLY (by extension)");
    convert->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    convert->add_option("output", options->output, "Output mesh (.obj, .off, .ply); written atomically")->required();
    add_format_option(convert, options->format);
    add_ply_encoding_option(convert, options->ply_encoding);
    convert->add_flag("--strict-isolated", options->strict_isolated,
                      "Treat vertices in no face as errors (default: dropped with a warning)");
    convert->callback([options, &status] { status.exit_code = run_guarded([&] { return run_convert(*options); }); });
}

}  // namespace limsurf::cli
