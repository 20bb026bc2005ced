// PolygonSoup: faces and positions exactly as a file gave them, before any
// validation. Readers produce it; build_control_mesh() validates it and turns
// it into a ControlMesh. It also remembers where each element came from so
// that every problem can be reported as "file:line: element: what is wrong".
#pragma once

#include <span>
#include <string>
#include <string_view>
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

/// Named groups of faces, e.g. materials: OBJ `usemtl` or `g` (docs/io.md), or a per-face file
/// (read_face_groups). Face f belongs to names[face_group[f]], or to no group when face_group[f] is -1.
/// Either no groups at all (names and face_group empty: the mesh has no groups) or face_group has one
/// entry per face. Faces keep their numbers through build_control_mesh(), so the same record
/// describes the ControlMesh's faces (BuildResult::groups).
struct FaceGroups {
    std::vector<std::string> names;  ///< distinct, non-empty names; index = group number
    std::vector<Index> face_group;   ///< #F group numbers in [-1, names.size()), or empty
    /// Group that PolygonSoup::add_face() gives the faces it appends (-1: none); see set_current().
    Index current = -1;

    /// True when there are no groups (no names).
    [[nodiscard]] bool empty() const noexcept { return names.empty(); }
    /// Group number of face @p f, or -1 (no group, or no groups at all).
    [[nodiscard]] Index group_of(Index f) const;
    /// Number of the group called @p name, or -1.
    [[nodiscard]] Index find(std::string_view name) const;
    /// Index of @p name, adding it when new. @pre name is not empty
    Index add_name(std::string_view name);
    /// @throws InputError unless face_group is empty or has @p num_faces entries, each in
    ///   [-1, names.size()), and the names are distinct and non-empty ("face groups: ...").
    void check(Index num_faces) const;
};

/// Unvalidated polygons. Indices are 0-based into positions' rows.
struct PolygonSoup {
    Points positions;                    ///< #V×3
    std::vector<Index> face_offsets{0};  ///< #F+1; face f is face_vertices[offsets[f], offsets[f+1])
    std::vector<Index> face_vertices;    ///< concatenated face corners, counter-clockwise
    SharpnessTags sharpness;             ///< creases, corners, holes
    SchemeHints hints;                   ///< scheme options the file asked for
    SourceMap source;                    ///< provenance for messages
    FaceGroups groups;                   ///< face groups (materials); empty when the file had none

    [[nodiscard]] Index num_vertices() const noexcept { return static_cast<Index>(positions.rows()); }
    [[nodiscard]] Index num_faces() const noexcept { return static_cast<Index>(face_offsets.size()) - 1; }
    /// Corners of face @p f. @pre 0 <= f < num_faces()
    [[nodiscard]] std::span<const Index> face(Index f) const {
        const auto begin = static_cast<std::size_t>(face_offsets[static_cast<std::size_t>(f)]);
        const auto end = static_cast<std::size_t>(face_offsets[static_cast<std::size_t>(f) + 1]);
        return std::span<const Index>(face_vertices).subspan(begin, end - begin);
    }
    /// Appends a face (and its source line, when known). While groups are in use
    /// (!groups.empty()), the face gets groups.current.
    void add_face(std::span<const Index> corners, int line = 0);
    /// Makes @p name (added when new; "" for no group) the group of the faces add_face() appends
    /// from now on. The first named group puts the faces already there in no group (-1).
    void set_group(std::string_view name);
};

}  // namespace limsurf
