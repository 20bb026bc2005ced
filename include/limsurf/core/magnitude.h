// Scale-free arithmetic: bringing data of any magnitude to order one by an exact power of two,
// and back, naming overflow and underflow instead of returning inf, nan or a false zero.
//
// Geometry that is valid at one size is valid at every size, but doubles are not: the area of a
// mesh 1e155 across overflows, the cross products of one 1e-160 across underflow. Verdicts
// (degenerate, zero area, zero volume) are therefore taken on normalised data, and quantities
// of dimension length^k are scaled back by 2^(k·e) at the end (docs/conventions.md "Scale").
#pragma once

#include <cmath>
#include <string>

#include <Eigen/Core>

#include "limsurf/core/error.h"

namespace limsurf {

/// @brief The exponent e with max |x| in [2^(e−1), 2^e): x · 2^−e has entries of order one.
/// @return 0 for empty or all-zero data, and when an entry is not finite
template <class Derived>
[[nodiscard]] int magnitude_exponent(const Eigen::MatrixBase<Derived>& x) {
    if (x.size() == 0) {
        return 0;
    }
    const double largest = x.cwiseAbs().maxCoeff();
    if (!(largest > 0.0) || !std::isfinite(largest)) {
        return 0;
    }
    int e = 0;
    (void)std::frexp(largest, &e);
    return e;
}

/// @brief @p x · 2^k, exact while the result stays a normal double (in two factors, so that
///   |k| up to 2100 works: subnormal data brought up to order one, for instance).
template <class Derived>
[[nodiscard]] auto times_power_of_two(const Eigen::MatrixBase<Derived>& x, int k) {
    const int half = k / 2;
    return ((x * std::ldexp(1.0, half)) * std::ldexp(1.0, k - half)).eval();
}

/// @brief The Euclidean (Frobenius) norm of @p x without overflow or underflow of its squares:
///   computed on x · 2^−e. (Eigen 3.4's stableNorm() is wrong for matrix expressions.)
template <class Derived>
[[nodiscard]] double scale_free_norm(const Eigen::MatrixBase<Derived>& x) {
    const auto values = x.eval();
    const int e = magnitude_exponent(values);
    return std::ldexp(times_power_of_two(values, -e).norm(), e);
}

/// @brief @p value · 2^k for a quantity computed on normalised data.
/// @throws NumericalError naming @p what when the result overflows, or underflows to zero or a
///   subnormal number while @p value is not zero: "the enclosed volume (about 1e+465) overflows a double"
[[nodiscard]] inline double scale_back(double value, int k, const char* what) {
    const double out = std::ldexp(value, k);
    if (std::isfinite(out) && (value == 0.0 || std::isnormal(out))) {
        return out;
    }
    LIMSURF_CHECK(std::isfinite(value), NumericalError, "the ", what, " is not finite");
    const double decimal_exponent = std::log10(std::abs(value)) + k * std::log10(2.0);
    const bool overflow = !std::isfinite(out);
    throw NumericalError(detail::concat("the ", what, " (about 1e", std::lround(decimal_exponent), ") ",
                                        overflow ? "overflows" : "underflows", " a double: the mesh is too ",
                                        overflow ? "large" : "small", " for this quantity; rescale its coordinates"));
}

}  // namespace limsurf
