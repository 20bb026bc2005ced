// limsurf — exact computation on subdivision surfaces, from the command line.
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands/commands.h"
#include "limsurf/core/version.h"
#include "output.h"

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
