// Object File Format (OFF, COFF, NOFF, CNOFF, STOFF; ASCII only).
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// @brief Reads an ASCII OFF mesh.
/// @details Header `[ST][C][N]OFF`, counts `nv nf [ne]` (on the header line or the next
///   data line), one vertex per line (extra columns such as colours or normals ignored),
///   one face per line `n i0 ... i(n-1)` with 0-based indices (extra colour values
///   ignored). `#` starts a comment. Counts are checked against the stream's size before
///   anything is allocated.
/// @param[in] in          the OFF text
/// @param[in] source_name the name used in messages and stored in SourceMap::file
/// @throws InputError "FILE:LINE: what is wrong" (truncated file, bad number, index out of
///   range, counts that cannot fit) or "FILE: empty file"
[[nodiscard]] PolygonSoup read_off(std::istream& in, const std::string& source_name);

/// @brief read_off() on a file; the path is the source name.
/// @throws InputError as above, or "path: cannot open: <reason>"
[[nodiscard]] PolygonSoup read_off(const std::filesystem::path& path);

/// @brief Writes @p soup as ASCII OFF with shortest round-trip doubles. Tags and hints are
///   not written (write_mesh() warns about them).
/// @throws InputError if the soup is malformed or the stream fails
void write_off(std::ostream& out, const PolygonSoup& soup);

}  // namespace limsurf
