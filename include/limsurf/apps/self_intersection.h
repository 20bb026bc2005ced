// Does a limit surface pass through itself? The check behind `limsurf membrane`'s
// "self_intersection" report and limsurf.self_intersections in Python.
//
// c2g0-sphere-scheme-biomembranes Fig. 7: at reduced volume 0.18 the Canham shape on F_tetra,3 is a
// stomatocyte whose inner sphere nearly touches the outer one; the Loop result passes through
// itself, the C2g0 one does not. The check tessellates the exact limit surface
// (render/tessellation.h: every point on the surface), welds the copies of each point that the ptex
// faces along an edge share, and lists the triangle pairs that meet other than where the surface's
// connectivity joins them (mesh/self_intersection.h, CGAL's rule). What it finds is a
// self-intersection of the tessellation: a sheet crossing another by more than the tessellation's
// chordal error (O(h²) at N segments per ptex edge) is found; two sheets closer than that may be
// reported either way, so refine (a larger resolution) where the report is near a contact.
// A Catmull–Clark n-gon's sub-faces meet the quads beside it in T-junctions (2N segments against N):
// there the welded tessellation has slits, not joins; the triangles on either side lie on their own
// sides of the limit curve and are not reported (tests/apps/self_intersection_test.cpp).
#pragma once

#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// Options of limit_self_intersections().
struct SelfIntersectionOptions {
    /// Segments per ptex face edge, 1..256; 0: about 40 000 points (render's automatic_resolution),
    /// at least 2 segments: F_tetra,3 gets 16 (65 536 triangles).
    int resolution = 0;
    /// Points closer than this × the diagonal of the surface's bounding box are one point (> 0).
    double weld_tolerance = 1e-9;
    int num_threads = 0;  ///< for the tessellation; 0: all cores (the result does not depend on it)
};

/// What limit_self_intersections() found.
struct SelfIntersections {
    int resolution = 0;                  ///< segments per ptex face edge used
    Index triangles = 0;                 ///< triangles of the tessellation
    Index points = 0;                    ///< its points after welding
    std::size_t intersecting_pairs = 0;  ///< triangle pairs that meet (CGAL's rule)
    std::vector<Index> control_faces;    ///< sorted: the control faces whose limit patches take part
    [[nodiscard]] bool intersects() const noexcept { return intersecting_pairs > 0; }
};

/// @brief The self-intersections of the limit surface of @p X under @p basis (see the file comment).
/// @param X #V×3 control points
/// @throws InputError for a resolution outside 0..256, a weld tolerance that is not positive and
///   finite, or X of the wrong shape or not finite (tessellate_limit_surface())
[[nodiscard]] SelfIntersections limit_self_intersections(const LimitBasis& basis, const Points& X,
                                                         const SelfIntersectionOptions& options = {});

}  // namespace limsurf
