// --threads N: the thread count of the commands whose work is parallel in the library, the same
// words and check in every command.
#pragma once

#include <cstddef>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

namespace limsurf::cli {

/// Adds --threads N (a whole number >= 0; 0, the default: all cores) storing into @p threads.
inline CLI::Option* add_threads_option(CLI::App* cmd, int& threads) {
    const CLI::Validator non_negative(
        [](const std::string& text) {
            long long n = -1;
            std::size_t used = 0;
            try {
                n = std::stoll(text, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            return used == text.size() && n >= 0 ? std::string()
                                                 : "expected a thread count >= 0 (0: all cores), got '" + text + "'";
        },
        "N>=0");
    return cmd->add_option("--threads", threads, "Threads (0: all cores; results do not depend on it)")
        ->check(non_negative);
}

}  // namespace limsurf::cli
