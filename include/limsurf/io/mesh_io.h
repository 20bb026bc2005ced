// Reading and writing meshes by file name (docs/io.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "limsurf/io/ply.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// The mesh file formats limsurf reads and writes.
enum class MeshFormat { Obj, Off, Ply };

/// Options for the writers.
struct WriteOptions {
    PlyEncoding ply_encoding = PlyEncoding::Ascii;  ///< only for .ply
    /// The format, when the path's extension does not say it (/dev/stdout, a pipe); empty: by extension.
    std::optional<MeshFormat> format = std::nullopt;
};

/// @brief The format named "obj", "off" or "ply" (case-insensitive).
/// @throws InputError for any other name
[[nodiscard]] MeshFormat mesh_format_from_name(const std::string& name);

/// @brief The format of @p path from its extension (.obj, .off, .ply; case-insensitive).
/// @throws InputError "path: unknown mesh format '.xyz' (expected .obj, .off or .ply)"
[[nodiscard]] MeshFormat mesh_format_from_path(const std::filesystem::path& path);

/// @brief Reads @p path with read_obj(), read_off() or read_ply(), by extension.
/// @throws InputError for an unknown extension, a file that cannot be opened
///   ("path: cannot open: <strerror>") or any parse error ("path:line: ...")
[[nodiscard]] PolygonSoup read_polygon_soup(const std::filesystem::path& path);

/// @brief build_control_mesh(read_polygon_soup(path), options).
/// @throws InputError / TopologyError as read_polygon_soup() and build_control_mesh()
[[nodiscard]] BuildResult read_mesh(const std::filesystem::path& path, const BuildOptions& options = {});

/// @brief Writes @p soup to @p path atomically (write_file_atomically()), choosing the
///   format by options.format, else by extension.
/// @return warnings about data the format cannot store, e.g.
///   "OFF cannot store subdivision tags: 3 creases, 1 corner dropped"
/// @throws InputError for an unknown extension, a malformed soup, a non-finite position (the
///   stream writers write them, for exact round trips; a file never gets them) or a failed write
std::vector<std::string> write_mesh(const std::filesystem::path& path, const PolygonSoup& soup,
                                    const WriteOptions& options = {});

/// @brief write_mesh(path, to_polygon_soup(mesh), options).
std::vector<std::string> write_mesh(const std::filesystem::path& path, const ControlMesh& mesh,
                                    const WriteOptions& options = {});

}  // namespace limsurf
