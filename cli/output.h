// What every command shares: running a command with the CLI's exit-code
// contract, and printing warnings.
//
// Exit codes: 0 success; 1 bad input (limsurf::Error) — one "error: …" line on
// stderr; 2 bad usage (command line); 3 internal error (a limsurf bug).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "limsurf/mesh/validate.h"

namespace limsurf::cli {

constexpr int exit_ok = 0;
constexpr int exit_bad_input = 1;
constexpr int exit_usage = 2;
constexpr int exit_internal = 3;

/// Runs @p command; maps exceptions to one stderr line and an exit code.
[[nodiscard]] int run_guarded(const std::function<int()>& command);

/// Prints "warning: <text>" on stderr for each entry.
void print_warnings(const std::vector<std::string>& warnings);

/// The issues of a report as text lines ("error: …", "warning: …").
[[nodiscard]] std::vector<std::string> report_lines(const ValidationReport& report);

/// The report as JSON: {"valid", "num_errors", "num_warnings", "issues": [...]}.
[[nodiscard]] nlohmann::json report_json(const ValidationReport& report);

}  // namespace limsurf::cli
