// Control points whose limit surface passes through given points: the inverse of the limit
// position masks. A user who has points of the intended surface (a roof, a cylinder, a scan) at the
// vertices of a control topology gets a control mesh whose limit surface interpolates them at
// the limit points of the vertices, instead of a limit surface shrunk inside them (Catmull–Clark
// pulls a circle of control points in by about θ²/6 of its radius for a spacing θ).
#pragma once

#include <functional>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// @brief The control points X with P X = @p targets, P = basis.vertex_limit_matrix(): the limit
///   position of every control vertex is its target.
/// @pre targets has one row per control vertex of the basis's topology
/// @throws InputError on a size mismatch or non-finite targets; NumericalError when the sparse LU
///   of P fails or the solve's relative residual exceeds 1e-10 (targets outside P's range). Where the
///   basis is linearly dependent (very coarse meshes) X is one of several with the same limit surface.
[[nodiscard]] Points interpolating_control_points(const LimitBasis& basis, const Points& targets);

/// @brief Moves every row of @p P onto the zero set of @p F (an implicit description of the intended
///   surface, e.g. x² + z² − 625 for a cylinder of radius 25 about y) by Newton steps along F's
///   gradient, x ← x − F(x) ∇F / |∇F|², the gradient by central differences (step 1e-7 of the points'
///   extent). F is evaluated for all points at once (#P × 3 in, #P values out).
/// @throws InputError when F is not finite or its gradient vanishes at a point, or a point has not
///   reached |F| / |∇F| ≤ 1e-12 of the extent after 50 steps (naming it)
[[nodiscard]] Points project_onto_zero_set(const std::function<Eigen::VectorXd(const Points&)>& F, Points P);

}  // namespace limsurf
