// One function per subcommand: registers its options and its callback.
#pragma once

#include <CLI/CLI.hpp>

namespace limsurf::cli {

/// Where a subcommand's callback leaves its exit code.
struct CommandStatus {
    int exit_code = 0;
};

void add_info_command(CLI::App& app, CommandStatus& status);
void add_convert_command(CLI::App& app, CommandStatus& status);
void add_subdivide_command(CLI::App& app, CommandStatus& status);
void add_eval_command(CLI::App& app, CommandStatus& status);
void add_measure_command(CLI::App& app, CommandStatus& status);
void add_volume_command(CLI::App& app, CommandStatus& status);
void add_poisson_command(CLI::App& app, CommandStatus& status);
void add_eigen_command(CLI::App& app, CommandStatus& status);
void add_plate_command(CLI::App& app, CommandStatus& status);
void add_shell_command(CLI::App& app, CommandStatus& status);
void add_render_command(CLI::App& app, CommandStatus& status);
void add_parameterize_command(CLI::App& app, CommandStatus& status);
void add_geodesic_command(CLI::App& app, CommandStatus& status);
void add_vector_field_command(CLI::App& app, CommandStatus& status);
void add_hodge_command(CLI::App& app, CommandStatus& status);
void add_membrane_command(CLI::App& app, CommandStatus& status);
void add_tune_command(CLI::App& app, CommandStatus& status);
void add_reverse_command(CLI::App& app, CommandStatus& status);
void add_elasticity_command(CLI::App& app, CommandStatus& status);

}  // namespace limsurf::cli
