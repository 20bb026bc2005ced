#include "output.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <new>
#include <stdexcept>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/core/memory.h"
#include "limsurf/render/camera.h"

namespace limsurf::cli {

int run_guarded(const std::function<int()>& command) {
    try {
        return command();
    } catch (const Error& error) {
        std::cerr << "error: " << error.what() << '\n';
        return exit_bad_input;
    } catch (const std::bad_alloc&) {
        std::cerr << "error: out of memory\n";
        return exit_bad_input;
    } catch (const std::exception& error) {
        std::cerr << "internal error: " << error.what() << " (please report this as a limsurf bug)\n";
        return exit_internal;
    }
}

void print_warnings(const std::vector<std::string>& warnings) {
    for (std::size_t i = 0; i < warnings.size() && i < max_warning_lines; ++i) {
        std::cerr << "warning: " << warnings[i] << '\n';
    }
    if (warnings.size() > max_warning_lines) {
        std::cerr << "warning: … and " << warnings.size() - max_warning_lines
                  << " more warnings not shown ('limsurf info' lists them all)\n";
    }
}

void print_warnings(const ValidationReport& report) {
    std::vector<std::string> warnings;
    for (const Issue& issue : report.issues) {
        warnings.push_back(issue.to_string());
    }
    print_warnings(warnings);
}

void refuse_overwriting_inputs(const std::string& output, const std::vector<std::string>& inputs) {
    for (const std::string& input : inputs) {
        std::error_code ec;
        if (!input.empty() && std::filesystem::equivalent(output, input, ec) && !ec) {
            throw InputError(output + ": is also the input '" + input +
                             "': write the result to another file (limsurf never overwrites its input)");
        }
    }
}

void check_output_paths(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
    namespace fs = std::filesystem;
    std::vector<std::pair<fs::path, std::string>> seen;  // (where it points, as given)
    for (const std::string& output : outputs) {
        if (output.empty()) {
            continue;
        }
        refuse_overwriting_inputs(output, inputs);
        std::error_code ec;
        LIMSURF_CHECK(!fs::is_directory(output, ec), InputError, output, ": is a directory, not a file to write");
        const fs::path folder = fs::path(output).parent_path();
        LIMSURF_CHECK(folder.empty() || fs::is_directory(folder, ec), InputError, output, ": the folder '",
                      folder.string(), "' does not exist");
        // Through links, as write_file_atomically follows them; a file that does not exist yet by its
        // absolute path with '.' and '..' resolved.
        const fs::path where = fs::weakly_canonical(fs::absolute(output, ec), ec);
        for (const auto& [other_where, other] : seen) {
            LIMSURF_CHECK(!(where == other_where), InputError, output, ": names the same file as the output '", other,
                          "': give each output its own file");
        }
        seen.emplace_back(where, output);
    }
}

namespace {

/// Whether every number in @p json is finite: the common case, checked without building paths.
bool all_finite(const nlohmann::json& json) {
    if (json.is_number_float()) {
        return std::isfinite(json.get<double>());
    }
    if (json.is_structured()) {
        for (const auto& value : json) {
            if (!all_finite(value)) {
                return false;
            }
        }
    }
    return true;
}

/// The path of the first non-finite number in @p json ("reference.l2_relative"), or empty.
std::string non_finite_entry(const nlohmann::json& json, const std::string& path) {
    if (json.is_number_float() && !std::isfinite(json.get<double>())) {
        return path.empty() ? std::string("value") : path;
    }
    if (json.is_object()) {
        for (const auto& [key, value] : json.items()) {
            if (auto found = non_finite_entry(value, path.empty() ? key : path + "." + key); !found.empty()) {
                return found;
            }
        }
    } else if (json.is_array()) {
        for (std::size_t i = 0; i < json.size(); ++i) {
            if (auto found = non_finite_entry(json[i], path + "[" + std::to_string(i) + "]"); !found.empty()) {
                return found;
            }
        }
    }
    return {};
}

}  // namespace

void require_finite(const nlohmann::json& json, const std::string& path) {
    if (all_finite(json)) {
        return;
    }
    const std::string bad = non_finite_entry(json, path);
    LIMSURF_CHECK(bad.empty(), NumericalError, "the result '", bad,
                  "' is not a finite number (an overflow: the mesh or the data may be too large)");
}

void write_g17(std::ostream& out, double value) {
    std::array<char, 32> buffer{};  // %.17g needs at most 24 characters ("-1.2345678901234567e-308")
    const auto result =
        std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general, 17);
    out.write(buffer.data(), result.ptr - buffer.data());
}

void print_json(const nlohmann::json& json) {
    require_finite(json);
    std::cout << json.dump(2) << '\n';
}

void add_memory_option(CLI::App* cmd, std::string& text) {
    cmd->add_option("--max-memory", text,
                    "Refuse work whose estimated peak memory exceeds SIZE (e.g. 8G, 512M; default 3/4 of this "
                    "machine's memory)");
}

std::optional<std::int64_t> memory_budget(const std::string& text) {
    if (text.empty()) {
        return std::nullopt;
    }
    try {
        return parse_memory_size(text);
    } catch (const InputError& e) {
        throw InputError(std::string("--max-memory: ") + e.what());
    }
}

void add_format_option(CLI::App* cmd, std::string& text) {
    cmd->add_option("--format", text, "Output format when the output's extension does not say it (e.g. /dev/stdout)")
        ->check(CLI::IsMember({"obj", "off", "ply"}));
}

MeshFormat output_format(const std::string& output, const std::string& format) {
    if (format.empty()) {
        return mesh_format_from_path(output);
    }
    const MeshFormat named = mesh_format_from_name(format);
    // --format is for paths whose extension does not say (/dev/stdout, a pipe): one that says
    // otherwise is a mistake, and a .ply holding OFF text would mislead every reader.
    std::optional<MeshFormat> by_extension;
    try {
        by_extension = mesh_format_from_path(output);
    } catch (const InputError&) {
    }
    LIMSURF_CHECK(!by_extension || *by_extension == named, InputError, output, ": --format ", format,
                  " contradicts the extension '", lower_extension(output), "'");
    return named;
}

std::string with_file_named(const Error& error, const SourceMap& source, const std::vector<std::string>& other_files) {
    const std::string message = error.what();
    const auto names = [&](const std::string& file) {
        return !file.empty() && message.compare(0, file.size() + 1, file + ":") == 0;
    };
    if (names(source.file) || std::any_of(other_files.begin(), other_files.end(), names)) {
        return message;
    }
    std::string where = source.file;
    if (const auto& element = error.element()) {
        where = element->kind == ErrorElement::Kind::Face ? source.face_location(element->index)
                                                          : source.vertex_location(element->index);
    }
    return where.empty() ? message : where + ": " + message;
}

std::vector<std::string> report_lines(const ValidationReport& report) {
    std::vector<std::string> lines;
    for (const Issue& issue : report.issues) {
        lines.push_back((issue.severity == Severity::Error ? "error: " : "warning: ") + issue.to_string());
    }
    return lines;
}

nlohmann::json report_json(const ValidationReport& report) {
    nlohmann::json issues = nlohmann::json::array();
    for (const Issue& issue : report.issues) {
        issues.push_back({{"severity", issue.severity == Severity::Error ? "error" : "warning"},
                          {"problem", problem_name(issue.problem)},
                          {"location", issue.location},
                          {"message", issue.message}});
    }
    return {{"valid", !report.has_errors()},
            {"num_errors", report.num_errors()},
            {"num_warnings", report.num_warnings()},
            {"issues", issues}};
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool parse_size(const std::string& text, int& width, int& height) {
    const auto x = text.find('x');
    if (x == std::string::npos || text.find_first_not_of("0123456789x") != std::string::npos || x == 0 ||
        x + 1 == text.size() || x > 5 || text.size() - x - 1 > 5) {
        return false;
    }
    width = std::stoi(text.substr(0, x));
    height = std::stoi(text.substr(x + 1));
    return width >= 16 && width <= 8192 && height >= 16 && height <= 8192;
}

namespace {

/// @p text as one finite number, or nullopt (an overflow reads as ±HUGE_VAL: not finite; an
/// underflow reads as the subnormal or zero it rounds to).
std::optional<double> finite_number(const std::string& text) {
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(x)) {
        return std::nullopt;
    }
    return x;
}

}  // namespace

CLI::Validator positive_number() {
    return CLI::Validator(
        [](const std::string& text) {
            const std::optional<double> x = finite_number(text);
            return x && *x > 0.0 ? std::string() : "'" + text + "' is not a positive finite number";
        },
        "POSITIVE");
}

CLI::Validator non_negative_number() {
    return CLI::Validator(
        [](const std::string& text) {
            const std::optional<double> x = finite_number(text);
            return x && *x >= 0.0 ? std::string() : "'" + text + "' is not a finite number >= 0";
        },
        "NONNEGATIVE");
}

CLI::Validator view_validator() {
    return CLI::Validator(
        [](const std::string& text) {
            try {
                (void)parse_view(text);
            } catch (const Error& error) {
                return std::string(error.what());
            }
            return std::string();
        },
        "VIEW");
}

CLI::Validator size_validator() {
    return CLI::Validator(
        [](const std::string& text) {
            int w = 0;
            int h = 0;
            return parse_size(text, w, h) ? std::string() : "expected WIDTHxHEIGHT, each in 16..8192";
        },
        "WxH");
}

}  // namespace limsurf::cli
