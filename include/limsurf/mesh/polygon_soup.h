// PolygonSoup: faces and positions exactly as a file gave them, before any
// validation. Readers produce it; build_control_mesh() validates it and turns
// it into a ControlMesh. It also remembers where each element came from so
// that every problem can be reported as "file:line: element: what is wrong".
#pragma once

#include <span>
#include <string>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/sharpness.h"

namespace limsurf {

/// Where the elements of a PolygonSoup were read from.
struct SourceMap {
    std::string file;               ///< path as the user gave it; empty for in-memory data
    std::vector<int> vertex_lines;  ///< #V 1-based lines (0 = unknown, e.g. binary PLY); may be empty
    std::vector<int> face_lines;    ///< #F 1-based lines (0 = unknown); may be empty

    /// "file:line", "file" or "" for vertex @p v.
    [[nodiscard]] std::string vertex_location(Index v) const;
    /// "file:line", "file" or "" for face @p f.
    [[nodiscard]] std::string face_location(Index f) const;
    /// "file:line", "file" or "" for an explicit line number.
    [[nodiscard]] std::string line_location(int line) const;
};

/// Unvalidated polygons. Indices are 0-based into positions' rows.
struct PolygonSoup {
    Points positions;                    ///< #V×3
    std::vector<Index> face_offsets{0};  ///< #F+1; face f is face_vertices[offsets[f], offsets[f+1])
    std::vector<Index> face_vertices;    ///< concatenated face corners, counter-clockwise
    SharpnessTags sharpness;             ///< creases, corners, holes
    SchemeHints hints;                   ///< scheme options the file asked for
    SourceMap source;                    ///< provenance for messages

    [[nodiscard]] Index num_vertices() const noexcept { return static_cast<Index>(positions.rows()); }
    [[nodiscard]] Index num_faces() const noexcept { return static_cast<Index>(face_offsets.size()) - 1; }
    /// Corners of face @p f. @pre 0 <= f < num_faces()
    [[nodiscard]] std::span<const Index> face(Index f) const {
        const auto begin = static_cast<std::size_t>(face_offsets[static_cast<std::size_t>(f)]);
        const auto end = static_cast<std::size_t>(face_offsets[static_cast<std::size_t>(f) + 1]);
        return std::span<const Index>(face_vertices).subspan(begin, end - begin);
    }
    /// Appends a face (and its source line, when known).
    void add_face(std::span<const Index> corners, int line = 0);
};

}  // namespace limsurf
