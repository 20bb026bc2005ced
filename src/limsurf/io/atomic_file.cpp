#include "limsurf/io/atomic_file.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <system_error>

#include "limsurf/core/error.h"

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <unistd.h>
#define LIMSURF_IO_POSIX 1
#endif

namespace limsurf {
namespace {

namespace fs = std::filesystem;

std::string error_text(int error) {
    return error != 0 ? std::strerror(error) : "unknown error";
}

/// Creates a new, empty file next to @p path with a name nobody else uses.
fs::path create_temp_file(const fs::path& path, const std::string& shown) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::random_device device;
    std::mt19937_64 random((static_cast<std::uint64_t>(device()) << 32U) ^ static_cast<std::uint64_t>(device()));
    constexpr int attempts = 64;
    int last_error = 0;
    for (int attempt = 0; attempt < attempts; ++attempt) {
        static constexpr char digits[] = "0123456789abcdef";
        std::string suffix;
        std::uint64_t bits = random();
        for (int i = 0; i < 16; ++i) {
            suffix += digits[bits & 0xfU];
            bits >>= 4U;
        }
        fs::path temp = dir / ("." + path.filename().string() + "." + suffix + ".tmp");
#ifdef LIMSURF_IO_POSIX
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return temp;
        }
        last_error = errno;
        if (last_error != EEXIST) {
            break;
        }
#else
        std::error_code ec;
        if (!fs::exists(temp, ec)) {
            std::ofstream create(temp, std::ios::binary);
            if (create.is_open()) {
                return temp;
            }
            last_error = errno;
            break;
        }
#endif
    }
    throw InputError(shown + ": cannot create a temporary file in '" + dir.string() + "': " + error_text(last_error));
}

void sync_file(const fs::path& path) {
#ifdef LIMSURF_IO_POSIX
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd >= 0) {
        (void)::fsync(fd);
        ::close(fd);
    }
#else
    (void)path;
#endif
}

/// The file a path finally names: symbolic links followed (also to a target that does not
/// exist yet, which is then created, as the shell's '>' does).
fs::path follow_links(const fs::path& path) {
    fs::path current = path;
    constexpr int max_links = 40;  // as the kernel's ELOOP limit
    for (int hop = 0; hop < max_links; ++hop) {
        std::error_code ec;
        if (!fs::is_symlink(fs::symlink_status(current, ec))) {
            return current;
        }
        const fs::path target = fs::read_symlink(current, ec);
        if (ec) {
            throw InputError(path.string() + ": cannot read the symbolic link '" + current.string() +
                             "': " + ec.message());
        }
        current = target.is_absolute() ? target : current.parent_path() / target;
    }
    throw InputError(path.string() + ": too many levels of symbolic links");
}

/// Opens @p path, runs @p write, flushes and closes; every failure named after @p shown.
void write_and_close(const fs::path& path, std::ios::openmode mode, const std::string& shown,
                     const std::function<void(std::ostream&)>& write) {
    errno = 0;
    std::ofstream out(path, mode);
    if (!out.is_open()) {
        throw InputError(shown + ": cannot open for writing: " + error_text(errno));
    }
    write(out);
    out.flush();
    if (!out.good()) {
        throw InputError(shown + ": write failed: " + error_text(errno));
    }
    out.close();
    if (out.fail()) {
        throw InputError(shown + ": write failed on close: " + error_text(errno));
    }
}

}  // namespace

void write_file_atomically(const fs::path& requested, const std::function<void(std::ostream&)>& write) {
    const std::string shown = requested.string();
    std::error_code ec;
    const fs::file_status existing = fs::status(requested, ec);  // through any links, as the kernel sees it
    if (fs::is_directory(existing)) {
        throw InputError(shown + ": cannot write: is a directory");
    }
    if (fs::exists(existing) && !fs::is_regular_file(existing)) {
        if (fs::is_socket(existing)) {
            throw InputError(shown + ": cannot write: is a socket");
        }
        // A character device such as /dev/null, a FIFO: nothing to replace atomically, and a
        // temporary file renamed over it would destroy the device or the pipe. Written straight
        // through (the kernel follows /dev/stdout's magic links).
        write_and_close(requested, std::ios::out | std::ios::binary, shown, write);
        return;
    }
    // A regular file (or a new one): replace the file the links end at, so the links stay.
    std::error_code resolve_error;
    const fs::path path = fs::exists(existing) ? fs::canonical(requested, resolve_error) : follow_links(requested);
    if (resolve_error) {
        throw InputError(shown + ": cannot resolve the path: " + resolve_error.message());
    }
    const fs::path temp = create_temp_file(path, shown);
    try {
        write_and_close(temp, std::ios::out | std::ios::binary | std::ios::trunc, shown, write);
        sync_file(temp);
        if (fs::is_regular_file(existing)) {
            fs::permissions(temp, existing.permissions(), ec);  // best effort
        }
        fs::rename(temp, path, ec);
        if (ec) {
            throw InputError(shown + ": cannot replace the file: " + ec.message());
        }
    } catch (...) {
        std::error_code ignored;
        fs::remove(temp, ignored);
        throw;
    }
}

}  // namespace limsurf
