// Private: the connectivity checks shared by validate() and the Topology
// constructor, so that both report exactly the same problems.
#pragma once

#include <cstdint>
#include <memory>
#include <new>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
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

/// HugePageAllocator (whole huge pages once large), except that resize() leaves the new elements default-initialised
/// (for a trivial type: unwritten) instead of zeroing them: the half-edge table, 64 MB for a million quads, is written
/// in full right after it is sized, and zeroing it first cost 8 % of building the topology.
template <class T>
struct DefaultInitAllocator : HugePageAllocator<T> {
    DefaultInitAllocator() noexcept = default;
    template <class U>
    DefaultInitAllocator(const DefaultInitAllocator<U>& /*other*/) noexcept {}
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
};

/// Half-edges in a table that resize() does not zero.
using HalfEdges = std::vector<HalfEdge, DefaultInitAllocator<HalfEdge>>;

/// Whether check_connectivity() looks for vertices whose faces form several fans (bow-ties).
enum class VertexFans {
    Check,
    /// Left to the caller: the Topology constructor finds them in its one-ring walk (which stops
    /// short at such a vertex) and then runs the full check for the report. Saves a pass that
    /// groups every corner by vertex (15 % of building a million-face topology).
    LeftToTheCaller,
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
                        ValidationReport& report, HalfEdges* sorted_half_edges = nullptr,
                        VertexFans fans = VertexFans::Check);

/// @brief The half-edges of @p faces sorted by (key, face), without any check.
/// @pre the faces are valid (degree >= 3, indices in range): refinement output only.
[[nodiscard]] HalfEdges sorted_half_edges_unchecked(const FaceListView& faces);

}  // namespace limsurf::detail
