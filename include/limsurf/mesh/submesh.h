// A part of a mesh as a mesh of its own: the faces a caller keeps, renumbered, with a vertex
// split wherever the kept faces meet at it without sharing an edge there.
//
// Used to refine only the faces near what a computation reads (the parameterisation's area form
// refines the strip of faces around the boundary; apps/parameterization.cpp).
#pragma once

#include <span>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf {

/// The kept faces of a topology and where each of their vertices and faces came from.
struct Submesh {
    /// Kept faces in their order in the parent, corners in the parent's order (so the same
    /// orientation); no sharpness tags (what a tag means on a part is the caller's choice).
    Topology topology;
    std::vector<Index> vertex_origin;  ///< submesh vertex → parent vertex
    std::vector<Index> face_origin;    ///< submesh face → parent face
};

/// @brief The faces of @p parent marked in @p keep, as a manifold mesh of their own.
///
/// A parent vertex becomes one submesh vertex per fan of kept faces around it (a fan: kept faces
/// consecutive about the vertex, each sharing an edge at it with the next). A vertex whose whole
/// one-ring is kept, or whose kept faces are consecutive, stays one vertex with the same one-ring;
/// one where kept faces touch only at the vertex becomes several, so the result never has a
/// bow-tie. Submesh vertices are numbered in the order in which their parent vertices first appear
/// in the kept faces; a split vertex's copies follow one another, in the order of its fans about it.
/// @param keep one entry per parent face, non-zero to keep it
/// @throws InputError when @p keep does not have one entry per face or keeps no face
[[nodiscard]] Submesh face_submesh(const Topology& parent, std::span<const char> keep);

}  // namespace limsurf
