// Vocabulary types shared by every layer (DESIGN.md §3, docs/conventions.md).
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace limsurf {

/// Index of a vertex, edge or face. 32-bit signed, as in OpenSubdiv's Far::Index.
using Index = std::int32_t;

/// Per-vertex positions, one row per vertex: #V×3.
using Points = Eigen::Matrix<double, Eigen::Dynamic, 3>;

/// Sparse operators (subdivision matrices, exterior derivatives, mass matrices).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// Marks "no such element" (e.g. find_edge on two vertices that share no edge).
constexpr Index invalid_index = -1;

/// Sharpness at or above this value is infinitely sharp (OpenSubdiv's
/// Sdc::Crease::SHARPNESS_INFINITE).
constexpr double infinite_sharpness = 10.0;

}  // namespace limsurf
