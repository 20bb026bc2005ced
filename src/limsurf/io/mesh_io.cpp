#include "limsurf/io/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <optional>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
#include "limsurf/detail/io_text.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/obj.h"
#include "limsurf/io/off.h"
#include "limsurf/io/ply.h"

namespace limsurf {

namespace {

/// The format called @p name ("obj", "off", "ply", any case), if any.
std::optional<MeshFormat> format_called(std::string name) {
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const auto& [known, format] :
         {std::pair{"obj", MeshFormat::Obj}, std::pair{"off", MeshFormat::Off}, std::pair{"ply", MeshFormat::Ply}}) {
        if (name == known) {
            return format;
        }
    }
    return std::nullopt;
}

}  // namespace

MeshFormat mesh_format_from_path(const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (const auto format = format_called(extension.empty() ? extension : extension.substr(1))) {
        return *format;
    }
    throw InputError(path.string() + ": unknown mesh format '" + extension + "' (expected .obj, .off or .ply)");
}

MeshFormat mesh_format_from_name(const std::string& name) {
    if (const auto format = format_called(name)) {
        return *format;
    }
    throw InputError("unknown mesh format '" + name + "' (expected obj, off or ply)");
}

PolygonSoup read_polygon_soup(const std::filesystem::path& path) {
    const MeshFormat format = mesh_format_from_path(path);
    std::ifstream in = open_input_file(path);
    const std::string name = path.string();
    switch (format) {
    case MeshFormat::Obj:
        return read_obj(in, name);
    case MeshFormat::Off:
        return read_off(in, name);
    case MeshFormat::Ply:
        return read_ply(in, name);
    }
    throw InputError(name + ": unknown mesh format");
}

BuildResult read_mesh(const std::filesystem::path& path, const BuildOptions& options) {
    return build_control_mesh(read_polygon_soup(path), options);
}

std::vector<std::string> write_mesh(const std::filesystem::path& path, const PolygonSoup& soup,
                                    const WriteOptions& options) {
    const MeshFormat format = options.format ? *options.format : mesh_format_from_path(path);
    detail::io_check_soup(soup);
    for (Index v = 0; v < soup.num_vertices(); ++v) {  // a file never carries nan or inf as a result
        LIMSURF_CHECK(soup.positions.row(v).allFinite(), InputError, path.string(), ": cannot write vertex ", v,
                      ": a non-finite coordinate (", soup.positions(v, 0), ", ", soup.positions(v, 1), ", ",
                      soup.positions(v, 2), ")");
    }
    std::vector<std::string> warnings;
    switch (format) {
    case MeshFormat::Obj:
        write_file_atomically(path, [&](std::ostream& out) { write_obj(out, soup); });
        break;
    case MeshFormat::Off:
        write_file_atomically(path, [&](std::ostream& out) { write_off(out, soup); });
        if (auto warning = detail::io_dropped_tags_warning("OFF", soup); !warning.empty()) {
            warnings.push_back(std::move(warning));
        }
        break;
    case MeshFormat::Ply:
        write_file_atomically(path, [&](std::ostream& out) { write_ply(out, soup, options.ply_encoding); });
        if (auto warning = detail::io_dropped_tags_warning("PLY", soup); !warning.empty()) {
            warnings.push_back(std::move(warning));
        }
        break;
    }
    return warnings;
}

std::vector<std::string> write_mesh(const std::filesystem::path& path, const ControlMesh& mesh,
                                    const WriteOptions& options) {
    return write_mesh(path, to_polygon_soup(mesh), options);
}

}  // namespace limsurf
