#include "limsurf/mesh/polygon_soup.h"

#include <cstddef>

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
}

}  // namespace limsurf
