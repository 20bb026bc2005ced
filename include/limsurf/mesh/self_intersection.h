// Self-intersection of a triangle mesh: the pairs of triangles that meet anywhere except where the
// mesh's connectivity joins them. c2g0-sphere-scheme-biomembranes Fig. 7 (a Loop membrane that
// passes through itself where the C2g0 one does not) is the use that asked for it; apps/ runs it on
// a tessellation of the limit surface (apps/self_intersection.h).
//
// The rule is CGAL's (Polygon_mesh_processing::self_intersections), the test-only peer:
//   - triangles with no common vertex intersect when their closed point sets meet;
//   - triangles with one common vertex p intersect when they meet anywhere else than p;
//   - triangles with a common edge intersect when they overlap: the two opposite vertices lie in one
//     plane with the edge and on the same side of it (the mesh folds back onto itself).
// Predicates are orientation determinants in double precision (no exact arithmetic): a pair that
// touches within rounding (a vertex exactly on the other triangle) may be classed either way; pairs
// that cross by more than rounding are classed as CGAL classes them (tests/mesh compares the two).
//
// The search is a uniform grid of cells about the size of the mesh's larger triangles: each
// triangle is listed in the cells its bounding box overlaps, and a pair is tested in the one cell
// that holds the low corner of the overlap of their boxes, so it is tested once. Linear in the
// number of triangles on surface-like meshes.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf {

/// #T×3 vertex indices of a triangle mesh.
using Triangles = Eigen::Matrix<Index, Eigen::Dynamic, 3>;

/// @brief The intersecting pairs {i, j} (i < j, rows of @p triangles), sorted, at most @p max_pairs
///   of them (the first in that order); a triangle with a repeated vertex is skipped.
/// @param points #P×3, finite, of any size (far from order one they are scaled by a power of two
///   first, exactly: the pairs do not depend on the size)
/// @param triangles #T×3 indices into points
/// @throws InputError for an index out of range or a point that is not finite (naming it)
[[nodiscard]] std::vector<std::array<Index, 2>>
intersecting_triangle_pairs(const Points& points, const Triangles& triangles,
                            std::size_t max_pairs = std::numeric_limits<std::size_t>::max());

/// A triangle mesh whose coincident points were merged by weld_coincident_points().
struct WeldedTriangles {
    Points points;             ///< the representatives, in order of first appearance
    Triangles triangles;       ///< the input triangles, re-indexed into points
    std::vector<Index> index;  ///< #P_in: the welded point of each input point
};

/// @brief Merges points closer than @p tolerance (an absolute distance ≥ 0) into the first of them,
///   so that a mesh whose faces carry their own copies of shared points (a limit tessellation,
///   render/tessellation.h) gets the connectivity intersecting_triangle_pairs() needs. Points are
///   merged transitively (a chain of close points becomes one).
/// @throws InputError for a negative or non-finite tolerance, an index out of range or a point that
///   is not finite
[[nodiscard]] WeldedTriangles weld_coincident_points(const Points& points, const Triangles& triangles,
                                                     double tolerance);

}  // namespace limsurf
