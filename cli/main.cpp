// limsurf — exact computation on subdivision surfaces, from the command line.
#include <iostream>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>

#include "commands/commands.h"
#include "limsurf/core/version.h"
#include "output.h"

namespace {

/// What CLI11 would report badly, or not at all: an empty argument (CLI11 reads "" as 0 for a
/// number, and as "not given" for a path), and an unknown command or option before the command
/// (CLI11 says only "A subcommand is required"). Empty when there is none.
std::string usage_problem(const CLI::App& app, int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (arg.empty()) {
            return "argument " + std::to_string(i) + (i > 1 ? " (after '" + std::string(argv[i - 1]) + "')" : "") +
                   " is empty: give a value, or leave the option out";
        }
        if (arg.starts_with("--") && arg.ends_with("=")) {
            return "'" + std::string(arg) + "' has an empty value: give a value, or leave the option out";
        }
    }
    if (argc < 2) {
        return {};
    }
    const std::string first = argv[1];
    if (first == "-h" || first == "--help" || first == "--version") {
        return {};
    }
    std::string names;
    for (const CLI::App* command : app.get_subcommands({})) {
        if (command->get_name() == first) {
            return {};
        }
        names += (names.empty() ? "" : ", ") + command->get_name();
    }
    return (first.starts_with("-") ? "unknown option '" + first + "' before the command"
                                   : "unknown command '" + first + "'") +
           "; the commands are " + names;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace limsurf::cli;
    CLI::App app{"limsurf — exact computation on subdivision surfaces"};
    app.set_version_flag("--version", limsurf::version());
    app.require_subcommand(1);
    app.fallthrough(false);

    CommandStatus status;
    add_info_command(app, status);
    add_convert_command(app, status);
    add_subdivide_command(app, status);
    add_eval_command(app, status);
    add_measure_command(app, status);
    add_volume_command(app, status);
    add_poisson_command(app, status);
    add_eigen_command(app, status);
    add_plate_command(app, status);
    add_shell_command(app, status);
    add_render_command(app, status);
    add_parameterize_command(app, status);
    add_geodesic_command(app, status);
    add_vector_field_command(app, status);
    add_hodge_command(app, status);
    add_membrane_command(app, status);
    add_tune_command(app, status);
    add_reverse_command(app, status);
    add_elasticity_command(app, status);

    return run_guarded([&]() -> int {
        if (const std::string problem = usage_problem(app, argc, argv); !problem.empty()) {
            std::cerr << "error: " << problem << " (see 'limsurf --help')\n";
            return exit_usage;
        }
        try {
            app.parse(argc, argv);
        } catch (const CLI::CallForHelp& help) {
            return app.exit(help);
        } catch (const CLI::CallForAllHelp& help) {
            return app.exit(help);
        } catch (const CLI::CallForVersion& version) {
            return app.exit(version);
        } catch (const CLI::ParseError& error) {
            std::cerr << "error: " << error.what() << " (see 'limsurf --help')\n";
            return exit_usage;
        }
        return status.exit_code;
    });
}
