// The checks every thin-structure material shares (private to src/limsurf/fem).
#pragma once

#include <cmath>

#include "limsurf/core/error.h"

namespace limsurf::detail {

/// @throws InputError naming @p what ("plate", "shell") unless E > 0, ν ∈ (−1, 0.5) and t > 0, all finite,
///   and the rigidities E t / (1 − ν²) and E t³ / (12 (1 − ν²)) are normal numbers (neither overflowed to
///   infinity nor underflowed to 0 or to a subnormal, where the stiffness matrix would lose its digits
///   and its factorisation report a "degenerate geometry" that is not there).
inline void check_thin_material(const char* what, double E, double nu, double thickness) {
    LIMSURF_CHECK(std::isfinite(E) && E > 0.0, InputError, what, ": E must be > 0, got ", E);
    LIMSURF_CHECK(std::isfinite(nu) && nu > -1.0 && nu < 0.5, InputError, what, ": nu must be in (-1, 0.5), got ", nu);
    LIMSURF_CHECK(std::isfinite(thickness) && thickness > 0.0, InputError, what, ": the thickness must be > 0, got ",
                  thickness);
    const double membrane = E * thickness / (1.0 - nu * nu);
    const double bending = E * thickness * thickness * thickness / (12.0 * (1.0 - nu * nu));
    LIMSURF_CHECK(std::isnormal(membrane) && std::isnormal(bending), InputError, what, ": E = ", E,
                  " and thickness = ", thickness, " give the rigidities E t/(1-nu^2) = ", membrane,
                  " and E t^3/(12(1-nu^2)) = ", bending,
                  ", outside the range of double precision: state the problem in other units");
}

}  // namespace limsurf::detail
