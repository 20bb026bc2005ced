// Local patches for exact limit evaluation (private to src/limsurf/limit).
//
// A local patch is the one-ring of a face — every face that shares a vertex
// with it — copied into a small Topology of its own, numbered canonically from
// the face and one of its corners. Refining it with the scheme's own step
// (refine.h) gives exactly the child vertices the limit surface over the face's
// children depends on: the rules of the face's vertices and of the edges at
// them only involve faces of the one-ring (iga-with-catmull-clark §4.1: the
// surface over a face is determined by its one-ring). Vertices on the outer rim
// of the copy get wrong rules, but no child of the face ever needs them.
//
// Canonical numbering makes two patches with the same structure identical
// topologies, so that a self-similar configuration around an extraordinary
// vertex (a Stam patch, also on boundaries and creases) is recognised by
// comparing a patch with the patch of its corner child.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/topology.h"

namespace limsurf::detail {

/// The one-ring copy of a face. Face 0 of `topology` is the face itself, its
/// corner 0 the chosen start corner; its vertices are local vertices 0..n-1.
struct PatchMesh {
    Topology topology;
    std::vector<Index> source;  ///< #local: the vertex of the source topology each local vertex copies
};

/// The canonical one-ring copy as plain arrays, before any Topology is built: cheap
/// to compare, so that equal configurations share their refinement (limit_basis.cpp).
struct PatchArrays {
    std::vector<Index> offsets;  ///< #faces + 1
    std::vector<Index> corners;  ///< local vertex of each face corner
    SharpnessTags tags;          ///< creases, corners and holes in local numbering
    std::vector<Index> source;   ///< #local: the vertex of the source topology each local vertex copies
};

/// @brief The canonical one-ring copy of @p face of @p source, starting at corner @p start_corner.
///   Rim vertices where the one-ring touches itself only at a vertex are split into one
///   local vertex per fan, so the copy is always a manifold.
[[nodiscard]] PatchArrays extract_patch_arrays(const Topology& source, Index face, int start_corner);

/// The Topology of a copy (built without re-validating: a one-ring copy is a manifold by construction).
[[nodiscard]] PatchMesh make_patch_mesh(PatchArrays arrays);

/// extract_patch_arrays followed by make_patch_mesh.
[[nodiscard]] PatchMesh extract_patch_mesh(const Topology& source, Index face, int start_corner);

/// Bytes that identify a copy with its sharpness: equal exactly when two copies have the
/// same canonical structure (faces, corners, tags in canonical order).
[[nodiscard]] std::string patch_signature(const PatchArrays& arrays);

/// Bytes that identify a topology with its sharpness (equal for canonical copies of the same structure).
[[nodiscard]] std::string topology_signature(const Topology& topology);

/// A point of a regular patch as a combination of at most four vertices
/// (phantom points beyond a boundary or an infinitely sharp crease are linear
/// extrapolations of real ones).
struct PatchPointStencil {
    std::array<Index, 4> vertex{};
    std::array<double, 4> weight{};
    int size = 0;
    void add(Index v, double w);
    void add(const PatchPointStencil& other, double w);
};

/// The control points of a regular patch: 16 for Catmull–Clark (bicubic B-spline,
/// index 4j+i, the face spans points 5, 6, 10, 9), 12 for Loop (quartic box spline,
/// the face is points 4, 5, 8). `rotation` r: the patch's (0,0) is corner r of the
/// face, its (1,0) corner r+1 (Loop only; Catmull–Clark patches are never rotated).
struct RegularPatch {
    std::array<PatchPointStencil, 16> points;
    int size = 0;
    int rotation = 0;
};

/// @brief Whether the limit surface over quad @p face is a bicubic B-spline patch, and its
///   16 points: every corner is smooth (interior, valence 4, no sharp edge), on a regular
///   infinitely sharp crease or boundary (two faces on the face's side, phantom points
///   beyond), or a corner (both face edges sharp, corner rule). Semi-sharp features are
///   never regular.
[[nodiscard]] bool catmull_clark_regular_patch(const Topology& topology, Index face, BoundaryInterpolation boundary,
                                               RegularPatch& out);

/// @brief As catmull_clark_regular_patch for a Loop triangle: all three vertices smooth
///   (interior, valence 6), or one face edge on a regular boundary/crease (three faces on
///   the face's side at both of its ends; phantom points by parallelograms, as OpenSubdiv).
[[nodiscard]] bool loop_regular_patch(const Topology& topology, Index face, BoundaryInterpolation boundary,
                                      RegularPatch& out);

}  // namespace limsurf::detail
