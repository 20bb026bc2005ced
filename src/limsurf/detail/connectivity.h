// Private: the connectivity checks shared by validate() and the Topology
// constructor, so that both report exactly the same problems.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/validate.h"

namespace limsurf::detail {

/// A face list viewed without copying.
struct FaceListView {
    Index num_vertices = 0;
    std::span<const Index> offsets;   // #F+1
    std::span<const Index> vertices;  // concatenated corners
};

/// One face's traversal of an edge, from corner `corner` (an index into the
/// concatenated corners) to the next corner of the same face.
/// 16 bytes: the tables for a million faces stay small. The vertex it leaves
/// is the corner's vertex; the other end follows from the key.
struct HalfEdge {
    std::uint64_t key;  // (lower vertex << 32) | higher vertex
    Index face;
    Index corner;

    [[nodiscard]] Index lower() const noexcept { return static_cast<Index>(key >> 32U); }
    [[nodiscard]] Index higher() const noexcept { return static_cast<Index>(key & 0xffffffffU); }
};

/// @brief Appends every connectivity and tag problem of @p faces to @p report:
///   face size, repeated and out-of-range vertices, no faces, non-manifold
///   edges and vertices, orientation, orientability, isolated vertices,
///   duplicate faces and tags that name nothing.
/// @throws InputError when the offsets themselves are malformed (not a list of faces).
/// @param[out] sorted_half_edges when not null, receives the half-edges of the
///   faces that passed the per-face checks, sorted by (key, face) — what the
///   Topology constructor numbers its edges from.
void check_connectivity(const FaceListView& faces, const SharpnessTags& sharpness, const SourceMap& source,
                        ValidationReport& report, std::vector<HalfEdge>* sorted_half_edges = nullptr);

/// @brief The half-edges of @p faces sorted by (key, face), without any check.
/// @pre the faces are valid (degree >= 3, indices in range): refinement output only.
[[nodiscard]] std::vector<HalfEdge> sorted_half_edges_unchecked(const FaceListView& faces);

}  // namespace limsurf::detail
