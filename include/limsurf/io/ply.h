// Stanford PLY (ASCII, binary little- and big-endian).
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <span>
#include <string>

#include "limsurf/io/vertex_field.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// How write_ply() encodes the data section.
enum class PlyEncoding { Ascii, BinaryLittleEndian, BinaryBigEndian };

/// @brief Reads a PLY mesh in any of the three encodings.
/// @details Needs an element `vertex` with scalar properties x, y, z (any PLY scalar
///   type) and, when present, an element `face` with a list property `vertex_indices`
///   (or `vertex_index`) of an integer type. Other properties and elements, lists
///   included, are skipped. Element counts are checked against the stream's size before
///   anything is allocated. Data after the last element is an error in ASCII and ignored
///   in binary files.
/// @param[in] in          the PLY bytes (open the file in binary mode)
/// @param[in] source_name the name used in messages and stored in SourceMap::file
/// @return the soup; SourceMap lines are 1-based for ASCII and 0 for binary files
/// @throws InputError "FILE:LINE: what is wrong" for header and ASCII errors,
///   "FILE: element 'face' 12 (byte offset 345): what is wrong" for binary data, or
///   "FILE: empty file"
[[nodiscard]] PolygonSoup read_ply(std::istream& in, const std::string& source_name);

/// @brief read_ply() on a file; the path is the source name.
/// @throws InputError as above, or "path: cannot open: <reason>"
[[nodiscard]] PolygonSoup read_ply(const std::filesystem::path& path);

/// @brief Writes @p soup as PLY with double x, y, z, optional per-vertex fields as extra
///   double properties (scalar `name`, vector `name_x`, `name_y`, `name_z`; names
///   sanitised), and faces as `list uchar int vertex_indices` (`list uint int` when a face
///   has more than 255 corners). Tags and hints are not written.
/// @param[in] fields #V×1 or #V×3 each, finite
/// @throws InputError for a malformed soup, an invalid field (see validate_vertex_fields())
///   or a failed stream
void write_ply(std::ostream& out, const PolygonSoup& soup, PlyEncoding encoding,
               std::span<const VertexField> fields = {});

}  // namespace limsurf
