// GMP scalars for the volume-form generator: exact rationals (the regular forms, and
// irregular ones where the weights are rational) and 100-digit floats (the irregular
// forms), through Boost.Multiprecision's GMP back end.
#pragma once

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/gmp.hpp>

#include "limsurf/core/error.h"
#include "limsurf/volume/form_generator.h"

namespace limsurf::detail {

using Rational = boost::multiprecision::mpq_rational;
using Float100 = boost::multiprecision::mpf_float_100;

/// cos(2π d/n) is rational only at multiples of 60° and 90°.
template <>
inline Rational cos_two_pi<Rational>(int d, int n) {
    LIMSURF_CHECK((12 * d) % n == 0, UnsupportedError, "cos(2π·", d, "/", n, ") is irrational");
    switch (((12 * d) / n) % 12) {
    case 0:
        return Rational(1);
    case 2:
    case 10:
        return Rational(1, 2);
    case 3:
    case 9:
        return Rational(0);
    case 4:
    case 8:
        return Rational(-1, 2);
    case 6:
        return Rational(-1);
    default:
        throw UnsupportedError("cos(2π·" + std::to_string(d) + "/" + std::to_string(n) + ") is irrational");
    }
}

template <>
inline Float100 cos_two_pi<Float100>(int d, int n) {
    return boost::multiprecision::cos(Float100(2) * boost::math::constants::pi<Float100>() * Float100(d) / Float100(n));
}

}  // namespace limsurf::detail
