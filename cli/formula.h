// Formulas on the command line (muParser): a right-hand side, a load, boundary values.
#pragma once

#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf::cli {

/// @brief Values of @p expression (variables x, y, z; constant pi) at the rows of @p X (#P × 3).
/// @throws InputError naming @p what ("--rhs") and the formula: muParser's message, or the first
///   point where the value is not finite
/// @throws InputError also when @p expression is several comma-separated expressions (muParser
///   would return the last)
[[nodiscard]] Eigen::VectorXd evaluate_formula(const std::string& what, const std::string& expression, const Points& X);

/// @brief Checks @p expression before any work, as evaluate_formula() would at the first point, so
///   that a formula that is only used in some cases (a boundary value on a closed mesh) is still
///   refused when it is malformed.
/// @throws InputError as evaluate_formula()
void check_formula(const std::string& what, const std::string& expression);

}  // namespace limsurf::cli
