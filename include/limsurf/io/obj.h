// Wavefront OBJ with OpenSubdiv's subdivision tags (docs/io.md).
#pragma once

#include <filesystem>
#include <istream>
#include <ostream>
#include <string>

#include <Eigen/Core>

#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// @brief Reads an OBJ polygon mesh and its OpenSubdiv "t" tags.
/// @details Accepts `v x y z [w]` (divided by w; `v x y z r g b` colours ignored),
///   `f` with the corner forms v, v/vt, v//vn and v/vt/vn (1-based or negative,
///   relative indices), `vt`, `vn`, `vp`, `o`, `s`, `mtllib`, `l`, `p` (ignored), `g NAME` and
///   `usemtl NAME` (face groups, below), `#` comments, CRLF and `\` continuation lines, and the tags crease, corner,
///   hole, interpolateboundary, creasemethod and smoothtriangles. Faces with fewer than
///   three corners are kept (validation reports them). Tag indices are stored as given.
///   Face groups (PolygonSoup::groups, docs/io.md "Face groups"): a face belongs to the group of
///   the last `usemtl` above it when the file has a `usemtl` line with a name, else to that of
///   the last `g` above it; a `g`/`usemtl` line with several names takes the first, one without a
///   name ends the group. Names are numbered in the order faces first use them; a file whose
///   faces are in no group gives empty groups.
/// @param[in] in          the OBJ text
/// @param[in] source_name the name used in messages and stored in SourceMap::file
/// @return the soup with SourceMap::vertex_lines and face_lines filled (1-based)
/// @throws InputError "FILE:LINE: what is wrong" for any syntax error, out-of-range face
///   index, unknown keyword, malformed or unsupported tag, or "FILE: empty file"
[[nodiscard]] PolygonSoup read_obj(std::istream& in, const std::string& source_name);

/// @brief read_obj() on a file; the path is the source name.
/// @throws InputError as above, or "path: cannot open: <reason>"
[[nodiscard]] PolygonSoup read_obj(const std::filesystem::path& path);

/// @brief Writes @p soup as OBJ: `v` lines (shortest round-trip doubles), 1-based `f`
///   lines, then `t` lines for creases, corners, holes and scheme hints, so that
///   read_obj() gives back the same positions (bitwise), faces, tags and hints. With face
///   groups, a `g NAME` line (bare `g` for faces in no group) starts each run of faces of one
///   group, so read_obj() gives back each face's group name (numbered in order of first use).
/// @throws InputError if the soup is malformed (see docs/io.md), its groups fail
///   FaceGroups::check() or a group name has a blank, control character, '#' or '\', or the
///   stream fails
void write_obj(std::ostream& out, const PolygonSoup& soup);

/// @brief write_obj() with texture coordinates: one `vt u v` line per vertex (after the `v`
///   lines) and faces as `f a/a b/b …`, so that a viewer textures the mesh by @p texcoords (e.g. a
///   parameterisation, `limsurf parameterize`). Tags and hints follow as in write_obj().
/// @param texcoords #V × 2, finite
/// @throws InputError as write_obj(), or when texcoords has the wrong shape or a non-finite value
void write_obj(std::ostream& out, const PolygonSoup& soup, const Eigen::MatrixXd& texcoords);

}  // namespace limsurf
