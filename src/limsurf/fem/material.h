// The checks every thin-structure material shares (private to src/limsurf/fem).
#pragma once

#include <cmath>

#include "limsurf/core/error.h"

namespace limsurf::detail {

/// @throws InputError naming @p what ("plate", "shell") unless E > 0, ν ∈ (−1, 0.5) and t > 0, all finite.
inline void check_thin_material(const char* what, double E, double nu, double thickness) {
    LIMSURF_CHECK(std::isfinite(E) && E > 0.0, InputError, what, ": E must be > 0, got ", E);
    LIMSURF_CHECK(std::isfinite(nu) && nu > -1.0 && nu < 0.5, InputError, what, ": nu must be in (-1, 0.5), got ", nu);
    LIMSURF_CHECK(std::isfinite(thickness) && thickness > 0.0, InputError, what, ": the thickness must be > 0, got ",
                  thickness);
}

}  // namespace limsurf::detail
