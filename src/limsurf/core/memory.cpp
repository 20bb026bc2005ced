#include "limsurf/core/memory.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include "limsurf/core/error.h"

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace limsurf {
namespace {

/// The first number in a cgroup file, or 0 ("max", missing or unreadable: no limit there).
std::int64_t cgroup_limit(const char* path) {
    std::ifstream in(path);
    std::int64_t value = 0;
    if (in >> value && value > 0) {
        return value;
    }
    return 0;
}

}  // namespace

std::int64_t machine_memory_bytes() {
    std::int64_t physical = 0;
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page = ::sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) {
        physical = static_cast<std::int64_t>(pages) * page;
    }
#endif
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        const std::int64_t limit = cgroup_limit(path);
        if (limit > 0 && (physical == 0 || limit < physical)) {
            physical = limit;
        }
    }
    return physical;
}

std::int64_t default_memory_budget() {
    const std::int64_t machine = machine_memory_bytes();
    return machine > 0 ? machine / 4 * 3 : std::numeric_limits<std::int64_t>::max();
}

std::string format_bytes(std::int64_t bytes) {
    std::ostringstream out;
    out.precision(3);
    constexpr const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    if (bytes < 1024) {
        out << bytes << " bytes";
        return out.str();
    }
    double value = static_cast<double>(bytes);
    int unit = -1;
    while (value >= 1024.0 && unit < 5) {
        value /= 1024.0;
        ++unit;
    }
    out << value << ' ' << units[unit];
    return out.str();
}

std::int64_t parse_memory_size(const std::string& text) {
    std::size_t end = 0;
    double number = 0.0;
    try {
        number = std::stod(text, &end);
    } catch (const std::exception&) {
        end = 0;
    }
    std::string unit = text.substr(end);
    std::transform(unit.begin(), unit.end(), unit.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    double scale = 0.0;
    for (const auto& [name, factor] : {std::pair<const char*, double>{"", 1.0},
                                       {"b", 1.0},
                                       {"k", 0x1p10},
                                       {"kb", 0x1p10},
                                       {"kib", 0x1p10},
                                       {"m", 0x1p20},
                                       {"mb", 0x1p20},
                                       {"mib", 0x1p20},
                                       {"g", 0x1p30},
                                       {"gb", 0x1p30},
                                       {"gib", 0x1p30},
                                       {"t", 0x1p40},
                                       {"tb", 0x1p40},
                                       {"tib", 0x1p40}}) {
        if (unit == name) {
            scale = factor;
        }
    }
    const double bytes = number * scale;
    LIMSURF_CHECK(end > 0 && scale > 0.0 && std::isfinite(bytes) && bytes >= 1.0 && bytes < 0x1p62, InputError,
                  "memory size '", text, "' is not a positive size such as 8G, 512M or 1000000");
    return static_cast<std::int64_t>(bytes);
}

}  // namespace limsurf
