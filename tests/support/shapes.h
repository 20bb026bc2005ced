// Small meshes generated in code, for tests that need a shape with known
// properties without touching the file system.
#pragma once

#include <optional>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf::test {

/// Faces of a unit cube, outward counter-clockwise; vertex i = (i&1, (i>>1)&1, (i>>2)&1).
[[nodiscard]] std::vector<std::vector<Index>> cube_faces();
[[nodiscard]] Points cube_positions();

/// An n×m grid of quads in the plane z = 0 ((n+1)(m+1) vertices, row-major, normal +z).
[[nodiscard]] std::vector<std::vector<Index>> grid_faces(Index n, Index m);
[[nodiscard]] Points grid_positions(Index n, Index m);

/// An n×m quad torus (both directions wrap), genus 1.
[[nodiscard]] std::vector<std::vector<Index>> torus_faces(Index n, Index m);

/// A sub-mesh: the faces of a mesh that were kept, vertices renumbered in order of first use.
struct Carving {
    Topology topology;
    std::vector<Index> original_vertex;  ///< new vertex id -> vertex id in the carved mesh
};

/// The faces of @p t with keep[f] set; nullopt when the result is empty or not a manifold (a
/// vertex pinched between two fans).
[[nodiscard]] std::optional<Carving> carve(const Topology& t, const std::vector<bool>& keep);

}  // namespace limsurf::test
