// Placeholder: filled in by the SEC-applications work (issue 16).
#include "commands/commands.h"

namespace limsurf::cli {

void add_hodge_command(CLI::App& app, CommandStatus& status) {
    (void)app;
    (void)status;
}

}  // namespace limsurf::cli
