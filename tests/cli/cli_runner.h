// Runs the limsurf binary from the CLI tests: captures stdout, stderr and the exit
// code. LIMSURF_CLI_PATH is defined by tests/cli/CMakeLists.txt.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace limsurf::test {

struct CliRun {
    int exit_code = -1;
    std::string out;
    std::string err;
};

/// @p arg in single quotes for the shell.
inline std::string quote(const std::string& arg) {
    std::string quoted = "'";
    for (const char c : arg) {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

/// The whole content of a text file ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream buffer;
    buffer << in.rdbuf();
    return buffer.str();
}

/// Runs `limsurf ARGS`; stderr goes through a file in @p scratch_dir.
inline CliRun run_limsurf(const std::vector<std::string>& args, const std::filesystem::path& scratch_dir) {
    const std::filesystem::path err_file = scratch_dir / "stderr.txt";
    std::string command = quote(LIMSURF_CLI_PATH);
    for (const std::string& arg : args) {
        command += " " + quote(arg);
    }
    command += " 2>" + quote(err_file.string());
    CliRun run;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) {
        return run;
    }
    char buffer[4096];
    std::size_t n = 0;
    while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) {
        run.out.append(buffer, n);
    }
    const int status = pclose(pipe);
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.err = slurp(err_file);
    return run;
}

}  // namespace limsurf::test
