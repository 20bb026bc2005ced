#include "limsurf/mesh/submesh.h"

#include <cstddef>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Numbers the fans of kept faces around v: writes a new submesh vertex for each into
/// corner_vertex at v's corners of the kept faces. v's faces are ordered about it, each sharing an
/// edge with the next (cyclically for an interior vertex, from boundary edge to boundary edge for a
/// boundary vertex), so a fan is a run of kept faces in that order.
void number_fans(const Topology& parent, std::span<const char> keep, Index v, std::vector<Index>& corner_vertex,
                 std::vector<Index>& vertex_origin) {
    const std::span<const Index> faces = parent.vertex_faces(v);
    const VertexFaceCorners corners = parent.vertex_face_corners(v);
    const std::size_t m = faces.size();
    const auto kept = [&](std::size_t i) { return keep[at(faces[i])] != 0; };
    // Walk from just after a face that is not kept, so that no run is cut in two by the walk's
    // start; a boundary vertex's order is not cyclic and starts a run by itself.
    std::size_t start = 0;
    if (!parent.is_boundary_vertex(v)) {
        while (start < m && kept(start)) {
            ++start;
        }
        start = start == m ? 0 : start + 1;
    }
    bool previous_kept = false;
    for (std::size_t step = 0; step < m; ++step) {
        const std::size_t i = (start + step) % m;
        if (!kept(i)) {
            previous_kept = false;
            continue;
        }
        if (!previous_kept) {
            vertex_origin.push_back(v);  // a new fan
        }
        corner_vertex[at(parent.face_offset(faces[i]) + corners[i])] = static_cast<Index>(vertex_origin.size()) - 1;
        previous_kept = true;
    }
}

}  // namespace

Submesh face_submesh(const Topology& parent, std::span<const char> keep) {
    LIMSURF_CHECK(static_cast<Index>(keep.size()) == parent.num_faces(), InputError, "the face selection has ",
                  keep.size(), " entries for ", parent.num_faces(), " faces");
    // corner_vertex[face_offset(f) + k]: the submesh vertex at corner k of a kept face f.
    std::vector<Index> corner_vertex(at(parent.num_corners()), invalid_index);
    std::vector<char> numbered(at(parent.num_vertices()), 0);
    Submesh sub;
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    for (Index f = 0; f < parent.num_faces(); ++f) {
        if (keep[at(f)] == 0) {
            continue;
        }
        const std::span<const Index> face = parent.face_vertices(f);
        for (std::size_t k = 0; k < face.size(); ++k) {
            if (numbered[at(face[k])] == 0) {
                numbered[at(face[k])] = 1;
                number_fans(parent, keep, face[k], corner_vertex, sub.vertex_origin);
            }
            corners.push_back(corner_vertex[at(parent.face_offset(f)) + k]);
        }
        offsets.push_back(static_cast<Index>(corners.size()));
        sub.face_origin.push_back(f);
    }
    LIMSURF_CHECK(!sub.face_origin.empty(), InputError, "the face selection keeps no face");
    sub.topology = Topology(static_cast<Index>(sub.vertex_origin.size()), offsets, corners);
    return sub;
}

}  // namespace limsurf
