// Atomic file replacement: a failed write never leaves a partial or temporary file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace limsurf {

/// @brief Writes a file through @p write, then atomically replaces @p path with it.
/// @details The data goes to a uniquely named temporary file in the directory of the file
///   @p path names (".NAME.XXXXXXXXXXXXXXXX.tmp"), which is checked, flushed, synced and
///   renamed over it. When the file already exists its permissions are kept. If @p write
///   throws or anything fails, the temporary file is removed, the file is left as it was,
///   and the exception propagates.
///   - A symbolic link is followed: its target is replaced (or created), the link stays.
///   - An existing file that is not a regular file — a character device such as /dev/null or
///     /dev/stdout, a FIFO — is written straight through (no temporary file: replacing it
///     would destroy the device or the pipe); a failed write (e.g. /dev/full) still throws.
/// @param[in] path  file to create or replace
/// @param[in] write called once with a binary output stream
/// @throws InputError naming @p path when the file cannot be created, written or renamed, or
///   @p path is a directory or a socket; anything @p write throws
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

}  // namespace limsurf
