// How an application discretises the Laplace–Beltrami operator, all unknowns on the control mesh:
// the inner products of SEC §3 (dec, decsnap on the control mesh; sec, secsnap refined to level
// L, sec/inner_products.h) or Galerkin with the limit basis (iga: mass and stiffness integrated on
// the limit surface, fem/galerkin.h). Shared by Poisson and the heat-method geodesics, which take
// every method limsurf has.
#pragma once

#include <string>

#include "limsurf/sec/inner_products.h"

namespace limsurf {

enum class LaplacianMethod { Dec, DecSnap, Sec, SecSnap, Iga };

/// "dec", "decsnap", "sec", "secsnap", "iga".
[[nodiscard]] const char* to_string(LaplacianMethod method) noexcept;
/// @throws InputError naming the accepted values
[[nodiscard]] LaplacianMethod parse_laplacian_method(const std::string& name);

/// True for sec, secsnap and iga, whose unknowns are the control coefficients of a function on the
/// limit surface (dec, decsnap: values at the control vertices).
[[nodiscard]] constexpr bool uses_limit_basis(LaplacianMethod m) noexcept {
    return m == LaplacianMethod::Sec || m == LaplacianMethod::SecSnap || m == LaplacianMethod::Iga;
}

/// True for sec and secsnap, whose inner products are refined to a level L.
[[nodiscard]] constexpr bool has_level(LaplacianMethod m) noexcept {
    return m == LaplacianMethod::Sec || m == LaplacianMethod::SecSnap;
}

/// @brief The inner products of dec, decsnap, sec, secsnap.
/// @throws InputError for iga, which has none
[[nodiscard]] InnerProductMethod inner_product_method(LaplacianMethod method);

}  // namespace limsurf
