// What every command shares: running a command with the CLI's exit-code
// contract, naming the input file in errors, and printing warnings.
//
// Exit codes: 0 success; 1 bad input (limsurf::Error) — one "error: …" line on
// stderr; 2 bad usage (command line); 3 internal error (a limsurf bug).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/validate.h"

namespace limsurf::cli {

constexpr int exit_ok = 0;
constexpr int exit_bad_input = 1;
constexpr int exit_usage = 2;
constexpr int exit_internal = 3;

/// At most this many warnings are printed on stderr; the rest are counted in one more line.
constexpr std::size_t max_warning_lines = 10;

/// Runs @p command; maps exceptions to one stderr line and an exit code.
[[nodiscard]] int run_guarded(const std::function<int()>& command);

/// Prints "warning: <text>" on stderr for each entry, at most max_warning_lines of them.
void print_warnings(const std::vector<std::string>& warnings);

/// The warnings of a validation report, as print_warnings prints them.
void print_warnings(const ValidationReport& report);

/// The issues of a report as text lines ("error: …", "warning: …").
[[nodiscard]] std::vector<std::string> report_lines(const ValidationReport& report);

/// The report as JSON: {"valid", "num_errors", "num_warnings", "issues": [...]}.
[[nodiscard]] nlohmann::json report_json(const ValidationReport& report);

/// @brief Refuses an output path that names the same file as one of @p inputs (also through a
///   link): writing it would destroy the input before or while it is read.
/// @throws InputError "OUT: is also the input 'IN': write the result to another file"
void refuse_overwriting_inputs(const std::string& output, const std::vector<std::string>& inputs);

/// @brief Checks a command's output paths before any work (empty paths, for outputs not asked for,
///   are skipped): none names an input (refuse_overwriting_inputs), none is a directory, each one's
///   folder exists, and no two name the same file. A command with several outputs then never writes
///   the first and fails on the next, and a long solve never ends in "cannot write".
/// @throws InputError naming the path and what is wrong with it
void check_output_paths(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

/// @brief Checks that every number in @p json is finite: the backstop of every command's results,
///   in JSON and in text (a result must never be printed as nan or inf, nor pass for a missing
///   value, which is how nlohmann prints them).
/// @throws NumericalError naming the first entry that is not ("reference.l2_relative")
/// @p path: where @p json sits in a larger document ("points[3]"), to name the entry there.
void require_finite(const nlohmann::json& json, const std::string& path = "");

/// require_finite(), then @p json on stdout (2-space indent).
void print_json(const nlohmann::json& json);

/// @brief Writes @p value as printf's "%.17g" (what a stream with setprecision(17) prints) through
///   std::to_chars, which is specified to give the same characters: 5–10× faster than the stream's
///   own formatting, for commands that print tables of many numbers.
void write_g17(std::ostream& out, double value);

/// Registers --max-memory SIZE on @p cmd (8G, 512M, ...; default 3/4 of the machine's memory).
void add_memory_option(CLI::App* cmd, std::string& text);

/// The budget --max-memory asked for, or empty for the default.
/// @throws InputError for a malformed size
[[nodiscard]] std::optional<std::int64_t> memory_budget(const std::string& text);

/// The extension of @p path in lower case, with its dot (".vtk"); empty when it has none.
std::string lower_extension(const std::string& path);

/// --size "W x H" as two integers in 16..8192 (limsurf render, limsurf elasticity --png).
/// @return false when the text is not of that form or out of range
bool parse_size(const std::string& text, int& width, int& height);

/// The CLI11 check of a --size option (parse_size).
CLI::Validator size_validator();

/// CLI11 checks of a number option, with readable messages: CLI11's own PositiveNumber prints its
/// range with all 309 digits of the largest double (and calls 0 out of a range that starts at 0),
/// and NonNegativeNumber lets nan through. Finite numbers only.
CLI::Validator positive_number();
CLI::Validator non_negative_number();

/// The CLI11 check of --view (iso, front, top or AZIMUTH,ELEVATION; limsurf render, parameterize).
CLI::Validator view_validator();

/// Registers --format obj|off|ply on @p cmd: the output format where the path's extension does
/// not say it (/dev/stdout, a pipe).
void add_format_option(CLI::App* cmd, std::string& text);

/// The output format: --format when given, else the extension of @p output.
/// @throws InputError when neither names a mesh format, or --format contradicts a mesh extension
///   (checked before any work)
[[nodiscard]] MeshFormat output_format(const std::string& output, const std::string& format);

/// The message of @p error as naming_file() reports it.
[[nodiscard]] std::string with_file_named(const Error& error, const SourceMap& source,
                                          const std::vector<std::string>& other_files);

/// @brief Runs @p work, the part of a command that works on the mesh read from @p source.file.
/// @details A limsurf::Error from it whose message does not name a file yet — neither the mesh
///   nor one of @p other_files (the command's other inputs and outputs, which their own
///   errors name) — is rethrown naming the mesh file: "mesh.obj:12: face 0 has 4 vertices…"
///   when the error is about a face or vertex whose line @p source knows, else "mesh.obj: …".
template <class Work>
auto naming_file(const SourceMap& source, const std::vector<std::string>& other_files, Work&& work)
    -> decltype(work()) {
    try {
        return work();
    } catch (const Error& error) {
        throw Error(with_file_named(error, source, other_files));
    }
}

}  // namespace limsurf::cli
