// A triangle tessellation of the exact limit surface, for pictures (render.h), glTF export and
// plotting: every point lies on the limit surface (it is evaluated there, not interpolated).
//
// Representation: each ptex face with a limit surface gets its own grid of points, so a point on
// an edge shared by two ptex faces appears once per face (with equal positions and, the limit
// surface being G1, equal normals up to rounding):
//   - quad domain (Catmull–Clark, Doo–Sabin): (N+1)² points (u, v) = (i/N, j/N), i, j = 0..N, in
//     the order j, then i; 2N² triangles, the diagonal from (i, j) to (i+1, j+1);
//   - triangle domain (Loop, C2g0): (N+1)(N+2)/2 points (i/N, j/N) with i + j <= N, in the order j,
//     then i; N² triangles.
// Faces follow in ptex order; faces without a limit surface (holes, faces touching the boundary
// under BoundaryInterpolation::None) are skipped. Triangles are counter-clockwise in (u, v), hence
// counter-clockwise seen from the side the normal (∂u × ∂v)/|∂u × ∂v| points to: outward on a closed
// mesh whose faces are counter-clockwise seen from outside (limit/surface_frame.h).
//
// Where the derivatives do not give a tangent plane or a curvature — an extraordinary, crease or
// corner vertex itself (LimitWeights::at_extraordinary_vertex), or a degenerate parameterisation —
// the normal and curvatures are taken from a nearby point of the same ptex face (a quarter of a grid
// step towards its centre), and `estimated` is set. Nothing in a tessellation is NaN.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// Options of tessellate_limit_surface().
struct TessellationOptions {
    int resolution = 8;     ///< N: segments along each edge of a ptex face, 1..1024
    bool curvature = true;  ///< compute the mean and Gaussian curvature at every point
    int num_threads = 0;    ///< threads for the evaluation; 0: hardware concurrency (the result does not depend on it)
};

/// Triangles on the limit surface; see the file comment for the layout.
struct LimitTessellation {
    std::vector<SurfacePoint> points;                   ///< #P ptex points (face, u, v)
    Points positions;                                   ///< #P×3 points of the limit surface
    Points normals;                                     ///< #P×3 unit normals (∂u × ∂v)/|∂u × ∂v|
    Eigen::VectorXd mean_curvature;                     ///< #P, H (1 on the unit sphere); empty without curvature
    Eigen::VectorXd gaussian_curvature;                 ///< #P, K; empty without curvature
    Eigen::Array<bool, Eigen::Dynamic, 1> estimated;    ///< #P: normal and curvature from a nearby point
    Eigen::Matrix<Index, Eigen::Dynamic, 3> triangles;  ///< #T×3 indices into points, counter-clockwise
    /// #P×#V: row p is the value row of the limit weights at point p, so that positions = value_weights · X
    /// and a per-control-vertex field u has the limit values value_weights · u (u_h = Σ u_i φ_i).
    SparseMatrix value_weights;
    int resolution = 0;  ///< the N it was made with

    [[nodiscard]] Index num_points() const noexcept { return static_cast<Index>(points.size()); }
    [[nodiscard]] Index num_triangles() const noexcept { return static_cast<Index>(triangles.rows()); }
};

/// @brief Tessellates the limit surface of control points @p X under @p basis.
/// @param X #V×3 control points, V = basis.topology().num_vertices()
/// @throws InputError for a resolution outside 1..1024 or X of the wrong shape or not finite;
///   NumericalError when the surface's derivatives overflow a double (a mesh beyond ~1e150)
[[nodiscard]] LimitTessellation tessellate_limit_surface(const LimitBasis& basis, const Points& X,
                                                         const TessellationOptions& options = {});

/// @brief The resolution that gives about @p target_points points for @p basis (at least 2, at most 32):
///   fine enough for a picture of a coarse mesh, bounded for a large one.
[[nodiscard]] int automatic_resolution(const LimitBasis& basis, Index target_points = 250000);

/// @brief A per-control-vertex scalar carried to the tessellation: tessellation.value_weights · values.
/// @param values #V, finite
/// @throws InputError for the wrong length, or a value that is not finite (naming its vertex)
[[nodiscard]] Eigen::VectorXd evaluate_vertex_field(const LimitTessellation& tessellation,
                                                    const Eigen::VectorXd& values);

/// @brief The sum of the triangles' areas: the area of the limit surface up to O(1/N²).
[[nodiscard]] double tessellation_area(const LimitTessellation& tessellation);

}  // namespace limsurf
