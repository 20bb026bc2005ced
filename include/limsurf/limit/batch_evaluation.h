// Evaluating the limit surface at many points at once, on several threads: the batch form of
// LimitBasis::evaluate(X, point, order) for samplers, picture makers and the Python module.
#pragma once

#include <span>
#include <utility>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// Positions and derivatives at N points, one row per point. Columns: 3 per requested row of
/// LimitWeights — value (x, y, z), then ∂u, ∂v for DerivativeOrder::First, then ∂uu, ∂uv, ∂vv for
/// Second: N × 3, N × 9 or N × 18.
using PointValues = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// @brief The limit surface of control points @p X at @p points (ptex face, u, v).
/// @param X           #V × 3 control points of basis.topology()
/// @param num_threads 0: hardware concurrency; the result does not depend on it (every point is
///   evaluated alone, bit for bit as LimitBasis::evaluate(X, point, out, order))
/// @throws InputError when X has the wrong shape, or naming the first point (its index) that is
///   out of range, outside its domain or on a face without a limit surface — checked before any
///   evaluation, so nothing is half done
[[nodiscard]] PointValues evaluate_points(const LimitBasis& basis, const Points& X,
                                          std::span<const SurfacePoint> points,
                                          DerivativeOrder order = DerivativeOrder::First, int num_threads = 0);

/// @brief The prefetches a loop makes before it evaluates point @p i of [.., @p end): LimitBasis::
///   prefetch's three stages for points i + 3, i + 2 and i + 1 (those before @p end), each point
///   given by @p point_at(k) (a SurfacePoint; it need not be checked, prefetch ignores what it cannot
///   use). Changes no result; evaluate_points and the Python module's evaluate call it.
template <class PointAt>
void prefetch_ahead(const LimitBasis& basis, const InterleavedPoints& X, Index i, Index end,
                    const PointAt& point_at) noexcept {
    using Stage = LimitBasis::PrefetchStage;
    constexpr std::pair<Index, Stage> chain[] = {{3, Stage::Lookup}, {2, Stage::Patch}, {1, Stage::ControlPoints}};
    for (const auto& [ahead, stage] : chain) {
        if (i + ahead < end) {
            basis.prefetch(X, point_at(i + ahead), stage);
        }
    }
}

/// prefetch_ahead over a span of points.
inline void prefetch_ahead(const LimitBasis& basis, const InterleavedPoints& X, std::span<const SurfacePoint> points,
                           Index i, Index end) noexcept {
    prefetch_ahead(basis, X, i, end, [&](Index k) { return points[static_cast<std::size_t>(k)]; });
}

}  // namespace limsurf
