// Loop's vertex rule, shared by S0 (loop.cpp) and the 1-form rules (loop_forms.cpp), which must
// use the same weight for the forms to commute with d0.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>

namespace limsurf::detail {

/// Weight α of each neighbour of a smooth interior vertex of valence n (the vertex keeps
/// 1 − nα): Loop's original α = (5/8 − (3/8 + cos(2π/n)/4)²)/n, exactly 1/16 at n = 6.
[[nodiscard]] inline double loop_neighbour_weight(std::size_t n) {
    if (n == 6) {
        return 0.0625;
    }
    const double nd = static_cast<double>(n);
    const double beta = 0.25 * std::cos(2.0 * std::numbers::pi / nd) + 0.375;
    return (0.625 - beta * beta) / nd;
}

}  // namespace limsurf::detail
