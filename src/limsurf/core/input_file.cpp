#include "limsurf/core/input_file.h"

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "limsurf/core/error.h"

namespace limsurf {

std::ifstream open_input_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        throw InputError(path.string() + ": cannot open: is a directory");
    }
    errno = 0;
    std::ifstream in(path, std::ios::in | std::ios::binary);
    if (!in.is_open()) {
        const int error = errno;
        throw InputError(path.string() + ": cannot open: " + (error != 0 ? std::strerror(error) : "unknown error"));
    }
    return in;
}

}  // namespace limsurf
