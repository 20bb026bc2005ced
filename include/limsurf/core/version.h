// Library version and build configuration, reported by `limsurf info --version`.
#pragma once

#include <string>

namespace limsurf {

/// "major.minor.patch" of the library.
[[nodiscard]] std::string version();

}  // namespace limsurf
