// Opening a file for reading with an error that names it and the reason.
#pragma once

#include <filesystem>
#include <fstream>

namespace limsurf {

/// @brief Opens @p path for binary reading. Pipes and devices are read as streams.
/// @throws InputError "path: cannot open: <reason>" (strerror), or "path: cannot open: is a
///   directory" (a directory opens on some systems and then reads as empty)
[[nodiscard]] std::ifstream open_input_file(const std::filesystem::path& path);

}  // namespace limsurf
