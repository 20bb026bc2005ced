#include "output.h"

#include <iostream>
#include <new>
#include <stdexcept>

#include "limsurf/core/error.h"

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
    for (const std::string& warning : warnings) {
        std::cerr << "warning: " << warning << '\n';
    }
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

}  // namespace limsurf::cli
