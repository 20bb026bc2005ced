#include "limsurf/mesh/polygon_soup.h"

#include <cstddef>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

std::string location(const std::string& file, const std::vector<int>& lines, Index i) {
    const auto k = static_cast<std::size_t>(i);
    if (i >= 0 && k < lines.size() && lines[k] > 0) {
        return file.empty() ? "line " + std::to_string(lines[k]) : file + ":" + std::to_string(lines[k]);
    }
    return file;
}

}  // namespace

std::string SourceMap::vertex_location(Index v) const {
    return location(file, vertex_lines, v);
}

std::string SourceMap::face_location(Index f) const {
    return location(file, face_lines, f);
}

std::string SourceMap::line_location(int line) const {
    if (line <= 0) {
        return file;
    }
    return file.empty() ? "line " + std::to_string(line) : file + ":" + std::to_string(line);
}

void PolygonSoup::add_face(std::span<const Index> corners, int line) {
    face_vertices.insert(face_vertices.end(), corners.begin(), corners.end());
    face_offsets.push_back(static_cast<Index>(face_vertices.size()));
    source.face_lines.resize(static_cast<std::size_t>(num_faces()) - 1, 0);
    source.face_lines.push_back(line);
    if (!groups.empty()) {
        groups.face_group.push_back(groups.current);
    }
}

void PolygonSoup::set_group(std::string_view name) {
    if (name.empty()) {
        groups.current = -1;
        return;
    }
    if (groups.empty()) {
        groups.face_group.assign(static_cast<std::size_t>(num_faces()), -1);
    }
    groups.current = groups.add_name(name);
}

Index FaceGroups::group_of(Index f) const {
    const auto k = static_cast<std::size_t>(f);
    return f >= 0 && k < face_group.size() ? face_group[k] : -1;
}

Index FaceGroups::find(std::string_view name) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == name) {
            return static_cast<Index>(i);
        }
    }
    return -1;
}

Index FaceGroups::add_name(std::string_view name) {
    const Index found = find(name);
    if (found >= 0) {
        return found;
    }
    names.emplace_back(name);
    return static_cast<Index>(names.size()) - 1;
}

void FaceGroups::check(Index num_faces) const {
    LIMSURF_CHECK(face_group.empty() || face_group.size() == static_cast<std::size_t>(num_faces), InputError,
                  "face groups: ", face_group.size(), " entries for ", num_faces, " faces");
    LIMSURF_CHECK(names.empty() == face_group.empty() || num_faces == 0, InputError, "face groups: ", names.size(),
                  " names but ", face_group.size(), " face entries");
    const auto count = static_cast<Index>(names.size());
    for (std::size_t f = 0; f < face_group.size(); ++f) {
        LIMSURF_CHECK(face_group[f] >= -1 && face_group[f] < count, InputError, "face groups: face ", f,
                      " is in group ", face_group[f], " but there are ", count, " groups");
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
        LIMSURF_CHECK(!names[i].empty(), InputError, "face groups: group ", i, " has an empty name");
        LIMSURF_CHECK(find(names[i]) == static_cast<Index>(i), InputError, "face groups: the name '", names[i],
                      "' is used twice");
    }
}

}  // namespace limsurf
