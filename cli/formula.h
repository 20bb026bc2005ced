// Formulas on the command line (muParser): a right-hand side, a load, boundary values.
#pragma once

#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf::cli {

/// @brief Values of @p expression (variables x, y, z; constant pi) at the rows of @p X (#P × 3).
/// @throws InputError naming @p what ("--rhs") and the formula: muParser's message, or the first
///   point where the value is not finite
[[nodiscard]] Eigen::VectorXd evaluate_formula(const std::string& what, const std::string& expression, const Points& X);

}  // namespace limsurf::cli
