// Atomic file replacement: a failed write never leaves a partial or temporary file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace limsurf {

/// @brief Writes a file through @p write, then atomically replaces @p path with it.
/// @details The data goes to a uniquely named temporary file in the directory of @p path
///   (".NAME.XXXXXXXXXXXXXXXX.tmp"), which is checked, flushed, synced and renamed over
///   @p path. When @p path already exists its permissions are kept. If @p write throws or
///   anything fails, the temporary file is removed, @p path is left as it was, and the
///   exception propagates.
/// @param[in] path  file to create or replace
/// @param[in] write called once with a binary output stream
/// @throws InputError naming @p path when the file cannot be created, written or renamed;
///   anything @p write throws
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

}  // namespace limsurf
