#include "arrays.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "limsurf/core/error.h"

namespace limsurf::python {
namespace {

/// numpy's kind letter: 'f' float, 'i' signed, 'u' unsigned, 'b' bool, 'c' complex, 'O' object...
char dtype_kind(const py::array& a) {
    return a.dtype().kind();
}

/// @p object as a numpy array. pybind11's ensure() does not throw when numpy refuses (a ragged
/// list, say): it clears the error and returns a null array, whose use crashed the interpreter. The
/// refusal is an InputError here, with numpy's own reason.
py::array as_array(const py::handle& object, const std::string& name) {
    py::array a = py::array::ensure(object);
    if (a) {
        return a;
    }
    std::string reason;
    try {
        (void)py::module_::import("numpy").attr("asarray")(object);
    } catch (const py::error_already_set& e) {
        reason = e.what();
        reason = ": " + reason.substr(0, reason.find('\n'));
    }
    throw InputError(name + ": not an array of numbers (got " +
                     std::string(py::str(py::type::of(object).attr("__name__"))) + reason + ")");
}

std::string shape_of(const py::array& a) {
    std::string out = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) {
        out += (k > 0 ? ", " : "") + std::to_string(a.shape(k));
    }
    return out + (a.ndim() == 1 ? ",)" : ")");
}

void require_real(const py::array& a, const std::string& name) {
    const char kind = dtype_kind(a);
    LIMSURF_CHECK(kind == 'f' || kind == 'i' || kind == 'u', InputError, name, ": expected real numbers, got dtype ",
                  std::string(py::str(a.dtype())));
}

/// @p a (integers) as 64-bit signed integers. Unsigned 64-bit values above the signed range wrapped
/// in the cast (2^64 − 1 was reported as -1): they are refused by value.
py::array_t<long long> signed_indices(const py::array& a, const std::string& name) {
    if (dtype_kind(a) == 'u' && a.itemsize() == 8) {
        const auto u = py::array_t<unsigned long long, py::array::c_style | py::array::forcecast>::ensure(a);
        for (py::ssize_t i = 0; i < u.size(); ++i) {
            LIMSURF_CHECK(u.data()[i] <= static_cast<unsigned long long>(std::numeric_limits<long long>::max()),
                          InputError, name, ": index ", u.data()[i], " is out of range");
        }
    }
    return py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
}

}  // namespace

void require_real_numbers(const py::handle& array, const std::string& name) {
    require_real(as_array(array, name), name);
}

py::array_t<double> new_array(py::ssize_t rows, py::ssize_t cols) {
    return py::array_t<double>({rows, cols});
}

py::array_t<double> new_vector(py::ssize_t rows) {
    return py::array_t<double>(rows);
}

Points points_from(const py::handle& array, const std::string& name) {
    const py::array a = as_array(array, name);
    require_real(a, name);
    LIMSURF_CHECK(a.ndim() == 2 && a.shape(1) == 3, InputError, name, ": expected shape (n, 3), got ", shape_of(a));
    LIMSURF_CHECK(a.shape(0) <= std::numeric_limits<Index>::max(), InputError, name, ": ", a.shape(0),
                  " rows exceed 32-bit indices");
    // forcecast + c_style: one converting copy whatever the dtype and strides were.
    const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    const auto view = c.unchecked<2>();
    Points out(a.shape(0), 3);
    for (py::ssize_t i = 0; i < view.shape(0); ++i) {
        for (py::ssize_t j = 0; j < 3; ++j) {
            const double x = view(i, j);
            LIMSURF_CHECK(std::isfinite(x), InputError, name, "[", i, ", ", j, "] = ", x, ": values must be finite");
            out(i, j) = x;
        }
    }
    return out;
}

Eigen::VectorXd vector_from(const py::handle& array, const std::string& name, Index expected) {
    const py::array a = as_array(array, name);
    require_real(a, name);
    LIMSURF_CHECK(a.ndim() == 1 || (a.ndim() == 2 && a.shape(1) == 1), InputError, name, ": expected a vector of ",
                  expected, " values, got ", a.ndim(), " dimensions");
    LIMSURF_CHECK(a.shape(0) == expected, InputError, name, ": expected ", expected, " values, got ", a.shape(0));
    const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    const double* data = c.data();
    Eigen::VectorXd out(expected);
    for (Index i = 0; i < expected; ++i) {
        LIMSURF_CHECK(std::isfinite(data[i]), InputError, name, "[", i, "] = ", data[i], ": values must be finite");
        out(i) = data[i];
    }
    return out;
}

namespace {

Index checked_corner(long long value, const std::string& where, Index num_vertices) {
    LIMSURF_CHECK(value >= 0 && value < num_vertices, InputError, where, " = ", value,
                  ": vertex index out of range (V has ", num_vertices, " rows)");
    return static_cast<Index>(value);
}

void faces_from_array(const py::array& a, const std::string& name, Index num_vertices, PolygonSoup& soup) {
    const char kind = dtype_kind(a);
    LIMSURF_CHECK(kind == 'i' || kind == 'u', InputError, name, ": expected integer vertex indices, got dtype ",
                  std::string(py::str(a.dtype())));
    LIMSURF_CHECK(a.ndim() == 2, InputError, name, ": expected shape (faces, corners), got ", a.ndim(),
                  " dimensions (a list of sequences gives polygons of mixed degree)");
    LIMSURF_CHECK(a.shape(1) >= 3, InputError, name, ": faces need at least 3 corners, got ", a.shape(1));
    const auto c = signed_indices(a, name);
    const auto view = c.unchecked<2>();
    std::vector<Index> corners(static_cast<std::size_t>(a.shape(1)));
    soup.face_vertices.reserve(static_cast<std::size_t>(a.shape(0) * a.shape(1)));
    soup.face_offsets.reserve(static_cast<std::size_t>(a.shape(0)) + 1);
    for (py::ssize_t f = 0; f < view.shape(0); ++f) {
        for (py::ssize_t k = 0; k < view.shape(1); ++k) {
            const long long value = view(f, k);
            if (value < 0 || value >= num_vertices) {
                checked_corner(value, name + "[" + std::to_string(f) + ", " + std::to_string(k) + "]", num_vertices);
            }
            corners[static_cast<std::size_t>(k)] = static_cast<Index>(value);
        }
        soup.add_face(corners);
    }
}

void faces_from_sequence(const py::sequence& faces, const std::string& name, Index num_vertices, PolygonSoup& soup) {
    std::vector<Index> corners;
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const std::string face_name = name + "[" + std::to_string(f) + "]";
        const py::array a = as_array(faces[f], face_name);
        const char kind = dtype_kind(a);
        LIMSURF_CHECK(a.size() == 0 || kind == 'i' || kind == 'u', InputError, face_name,
                      ": expected integer vertex indices, got dtype ", std::string(py::str(a.dtype())));
        LIMSURF_CHECK(a.ndim() == 1 && a.size() >= 3, InputError, face_name,
                      ": a face needs a sequence of at least 3 vertex indices");
        const auto c = signed_indices(a, face_name);
        corners.clear();
        for (py::ssize_t k = 0; k < c.size(); ++k) {
            corners.push_back(checked_corner(c.data()[k], face_name + "[" + std::to_string(k) + "]", num_vertices));
        }
        soup.add_face(corners);
    }
}

}  // namespace

void faces_into(const py::handle& faces, const std::string& name, Index num_vertices, PolygonSoup& soup) {
    if (py::isinstance<py::array>(faces)) {
        faces_from_array(py::reinterpret_borrow<py::array>(faces), name, num_vertices, soup);
        return;
    }
    LIMSURF_CHECK(py::isinstance<py::sequence>(faces) && !py::isinstance<py::str>(faces), InputError, name,
                  ": expected an integer array (faces × corners) or a list of polygons");
    faces_from_sequence(py::reinterpret_borrow<py::sequence>(faces), name, num_vertices, soup);
}

std::vector<Index> indices_from(const py::handle& array, const std::string& name, Index limit) {
    const py::array a = as_array(array, name);
    const char kind = dtype_kind(a);
    // An empty list becomes a float64 array in numpy: empty is empty, whatever its dtype.
    LIMSURF_CHECK(a.size() == 0 || kind == 'i' || kind == 'u', InputError, name, ": expected integers, got dtype ",
                  std::string(py::str(a.dtype())));
    LIMSURF_CHECK(a.ndim() <= 1, InputError, name, ": expected a vector, got ", a.ndim(), " dimensions");
    const auto c = signed_indices(a, name);
    std::vector<Index> out(static_cast<std::size_t>(c.size()));
    for (py::ssize_t i = 0; i < c.size(); ++i) {
        const long long value = c.data()[i];
        LIMSURF_CHECK(value >= 0 && value < limit, InputError, name, "[", i, "] = ", value, ": out of range [0, ",
                      limit, ")");
        out[static_cast<std::size_t>(i)] = static_cast<Index>(value);
    }
    return out;
}

py::array_t<double> read_only_view(const Points& matrix, const py::handle& owner) {
    // Points is column-major: element (i, j) at data + i + j * rows.
    const auto rows = static_cast<py::ssize_t>(matrix.rows());
    const py::ssize_t item = sizeof(double);
    py::array_t<double> view({rows, py::ssize_t{3}}, {item, item * rows}, matrix.data(), owner);
    py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
    return view;
}

py::array_t<double> to_numpy(const Eigen::VectorXd& vector) {
    py::array_t<double> out(vector.size());
    std::copy(vector.data(), vector.data() + vector.size(), out.mutable_data());
    return out;
}

py::array_t<double> to_numpy(const Points& points) {
    py::array_t<double> out = new_array(points.rows(), 3);
    auto view = out.mutable_unchecked<2>();
    for (Index i = 0; i < points.rows(); ++i) {
        for (int j = 0; j < 3; ++j) {
            view(i, j) = points(i, j);
        }
    }
    return out;
}

namespace {

/// A C-ordered numpy copy of a dense matrix of any scalar type.
template <class Scalar>
py::array_t<Scalar> dense_copy(const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& matrix) {
    py::array_t<Scalar> out({static_cast<py::ssize_t>(matrix.rows()), static_cast<py::ssize_t>(matrix.cols())});
    auto view = out.template mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < matrix.rows(); ++i) {
        for (Eigen::Index j = 0; j < matrix.cols(); ++j) {
            view(i, j) = matrix(i, j);
        }
    }
    return out;
}

}  // namespace

py::array_t<double> to_numpy(const Eigen::MatrixXd& matrix) {
    return dense_copy(matrix);
}

py::array_t<std::complex<double>> to_numpy(const Eigen::MatrixXcd& matrix) {
    return dense_copy(matrix);
}

py::object to_scipy(const SparseMatrix& matrix) {
    SparseMatrix compressed = matrix;
    compressed.makeCompressed();
    const auto nnz = static_cast<py::ssize_t>(compressed.nonZeros());
    py::array_t<double> data(nnz);
    py::array_t<std::int32_t> indices(nnz);
    py::array_t<std::int32_t> indptr(compressed.rows() + 1);
    std::copy(compressed.valuePtr(), compressed.valuePtr() + nnz, data.mutable_data());
    std::copy(compressed.innerIndexPtr(), compressed.innerIndexPtr() + nnz, indices.mutable_data());
    std::copy(compressed.outerIndexPtr(), compressed.outerIndexPtr() + compressed.rows() + 1, indptr.mutable_data());
    const py::object csr = py::module_::import("scipy.sparse").attr("csr_matrix");
    return csr(py::make_tuple(data, indices, indptr), py::arg("shape") = py::make_tuple(matrix.rows(), matrix.cols()));
}

py::object faces_array(std::span<const Index> offsets, std::span<const Index> vertices) {
    const auto n = static_cast<py::ssize_t>(offsets.size()) - 1;
    const Index degree = n > 0 ? offsets[1] - offsets[0] : 3;
    bool uniform = true;
    for (py::ssize_t f = 0; f < n && uniform; ++f) {
        uniform = offsets[static_cast<std::size_t>(f) + 1] - offsets[static_cast<std::size_t>(f)] == degree;
    }
    if (uniform) {
        py::array_t<Index> out({n, static_cast<py::ssize_t>(degree)});
        std::copy(vertices.begin(), vertices.end(), out.mutable_data());
        return py::object(std::move(out));
    }
    py::list out(static_cast<std::size_t>(n));
    for (py::ssize_t f = 0; f < n; ++f) {
        const auto begin = static_cast<std::size_t>(offsets[static_cast<std::size_t>(f)]);
        const auto end = static_cast<std::size_t>(offsets[static_cast<std::size_t>(f) + 1]);
        py::array_t<Index> face(static_cast<py::ssize_t>(end - begin));
        std::copy(vertices.begin() + static_cast<std::ptrdiff_t>(begin),
                  vertices.begin() + static_cast<std::ptrdiff_t>(end), face.mutable_data());
        out[static_cast<std::size_t>(f)] = std::move(face);
    }
    return py::object(std::move(out));
}

}  // namespace limsurf::python
