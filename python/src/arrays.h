// Conversions between numpy/scipy and limsurf's Eigen types, with the checks that turn bad
// arrays into Python exceptions naming the array, the row and the problem (never a crash).
#pragma once

#include <complex>
#include <span>
#include <string>
#include <vector>

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf::python {

namespace py = pybind11;

/// A C-contiguous float64 numpy array of shape (rows, cols), uninitialised.
[[nodiscard]] py::array_t<double> new_array(py::ssize_t rows, py::ssize_t cols);
/// A C-contiguous float64 numpy array of shape (rows,), uninitialised.
[[nodiscard]] py::array_t<double> new_vector(py::ssize_t rows);

/// @brief #rows × 3 positions from any real array-like (copied; non-contiguous and integer
///   arrays are accepted and converted).
/// @throws InputError naming @p name for a wrong shape, a non-real dtype or a non-finite entry (with its row)
[[nodiscard]] Points points_from(const py::handle& array, const std::string& name);

/// @brief A float64 vector of @p expected entries (any real array-like, copied).
/// @throws InputError naming @p name for a wrong shape or size, a non-real dtype or a non-finite entry
[[nodiscard]] Eigen::VectorXd vector_from(const py::handle& array, const std::string& name, Index expected);

/// @brief Faces from a 2-D integer array (one polygon per row, all of one degree) or a sequence of
///   integer sequences (polygons of any degree), checked against @p num_vertices.
/// @throws InputError naming @p name, the face and the problem: a float dtype, a face with fewer than
///   3 corners, an index out of range or negative
void faces_into(const py::handle& faces, const std::string& name, Index num_vertices, PolygonSoup& soup);

/// Integer indices (ptex faces) of @p n points, checked to be in [0, limit).
[[nodiscard]] std::vector<Index> indices_from(const py::handle& array, const std::string& name, Index limit);

/// @brief Refuses an array whose dtype is not real (complex, object, strings): numpy's casts would
///   drop the imaginary part with only a warning.
/// @throws InputError "<name>: expected real numbers, got dtype …"
void require_real_numbers(const py::handle& array, const std::string& name);

/// The numpy view of @p matrix's memory, read-only, keeping @p owner alive (no copy).
[[nodiscard]] py::array_t<double> read_only_view(const Points& matrix, const py::handle& owner);

/// A numpy copy of a dense vector.
[[nodiscard]] py::array_t<double> to_numpy(const Eigen::VectorXd& vector);
/// A C-ordered numpy copy of #rows × 3 points.
[[nodiscard]] py::array_t<double> to_numpy(const Points& points);
/// A C-ordered numpy copy of a dense matrix.
[[nodiscard]] py::array_t<double> to_numpy(const Eigen::MatrixXd& matrix);
/// A C-ordered complex128 numpy copy of a dense complex matrix.
[[nodiscard]] py::array_t<std::complex<double>> to_numpy(const Eigen::MatrixXcd& matrix);

/// @brief F of a face list (face f is @p vertices[@p offsets[f], @p offsets[f + 1])): one int32 array
///   (#F × k) when every face has degree k, else a list of int32 arrays; copies.
[[nodiscard]] py::object faces_array(std::span<const Index> offsets, std::span<const Index> vertices);

/// @brief scipy.sparse.csr_matrix of @p matrix (its arrays copied once, no Python loop).
[[nodiscard]] py::object to_scipy(const SparseMatrix& matrix);

}  // namespace limsurf::python
