// Per-face group (material) files: the face groups of a mesh read from a format that has none
// (OFF, PLY), or given apart from the mesh (docs/io.md "Face groups").
#pragma once

#include <filesystem>
#include <istream>
#include <string>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// @brief Reads one group per face, in face order: one token per line (blank lines and `#`
///   comments skipped).
/// @details When every token is an integer, the integers are the group numbers: names are
///   "0" … "max" (so face_group[f] is the file's integer; at most 65535) and -1 puts a face in no
///   group (a file of -1 only gives empty groups). Otherwise every token is a name ("-1" too), and
///   names are numbered in the order they first appear.
/// @param[in] in          the text
/// @param[in] source_name the name used in messages
/// @param[in] num_faces   the mesh's number of faces, >= 0
/// @return FaceGroups with face_group of size @p num_faces, or empty (no groups)
/// @throws InputError "FILE:LINE: ..." for a line with more than one token, an integer outside
///   [-1, 65535] (in an all-integer file), a line beyond the num_faces-th entry; "FILE: N entries, the mesh has M
///   faces" for too few, or "FILE: empty file"
[[nodiscard]] FaceGroups read_face_groups(std::istream& in, const std::string& source_name, Index num_faces);

/// @brief read_face_groups() on a file; the path is the source name.
/// @throws InputError as above, or "path: cannot open: <reason>"
[[nodiscard]] FaceGroups read_face_groups(const std::filesystem::path& path, Index num_faces);

}  // namespace limsurf
