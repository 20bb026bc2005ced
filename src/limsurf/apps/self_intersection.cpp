#include "limsurf/apps/self_intersection.h"

#include <algorithm>
#include <cmath>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/mesh/self_intersection.h"
#include "limsurf/render/tessellation.h"

namespace limsurf {

SelfIntersections limit_self_intersections(const LimitBasis& basis, const Points& X,
                                           const SelfIntersectionOptions& options) {
    LIMSURF_CHECK(options.resolution >= 0 && options.resolution <= 256, InputError,
                  "self-intersection resolution must be in 0..256 (0: automatic), got ", options.resolution);
    LIMSURF_CHECK(std::isfinite(options.weld_tolerance) && options.weld_tolerance > 0.0, InputError,
                  "weld tolerance must be positive and finite, got ", options.weld_tolerance);
    TessellationOptions tess;
    tess.resolution = options.resolution > 0 ? options.resolution : automatic_resolution(basis, 40000);
    tess.curvature = false;
    tess.num_threads = options.num_threads;
    const LimitTessellation t = tessellate_limit_surface(basis, X, tess);

    SelfIntersections out;
    out.resolution = tess.resolution;
    out.triangles = t.num_triangles();
    if (t.num_points() == 0) {
        return out;
    }
    // Without squaring the extent: the diagonal of a surface 1e300 across overflowed, and the weld
    // tolerance derived from it was named as the error. (intersecting_triangle_pairs copes with any
    // size itself.)
    const double diagonal = scale_free_norm(t.positions.colwise().maxCoeff() - t.positions.colwise().minCoeff());
    const WeldedTriangles welded = weld_coincident_points(t.positions, t.triangles, options.weld_tolerance * diagonal);
    out.points = static_cast<Index>(welded.points.rows());
    const auto pairs = intersecting_triangle_pairs(welded.points, welded.triangles);
    out.intersecting_pairs = pairs.size();
    for (const auto& pair : pairs) {
        for (Index triangle : pair) {
            const Index ptex = t.points[static_cast<std::size_t>(t.triangles(triangle, 0))].face;
            out.control_faces.push_back(basis.ptex_face(ptex).control_face);
        }
    }
    std::sort(out.control_faces.begin(), out.control_faces.end());
    out.control_faces.erase(std::unique(out.control_faces.begin(), out.control_faces.end()), out.control_faces.end());
    return out;
}

}  // namespace limsurf
