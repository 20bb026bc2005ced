// limsurf.LimitBasis: exact limit evaluation vectorised over arrays of points (GIL released).
#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Geometry>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/core/parallel.h"
#include "limsurf/limit/batch_evaluation.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/limit/surface_frame.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

/// A limit basis with the mesh it was built from (its positions are the default control points).
struct Basis {
    LimitBasis basis;
    Mesh mesh;
};

/// The point arrays of evaluate(), read in place (no copy when faces is int64 and u, v float64,
/// C-contiguous): each point is checked as `limsurf eval --points` checks a line when it is evaluated.
class PointArrays {
  public:
    PointArrays(const Basis& b, const py::handle& faces, const py::handle& u, const py::handle& v)
        : limit_(b.basis.num_ptex_faces()), quad_(b.basis.domain() == ParameterDomain::Quad) {
        const py::array f = py::array::ensure(faces);
        // An empty list is a float64 array in numpy: empty is empty, whatever its dtype.
        LIMSURF_CHECK(f && (f.size() == 0 || f.dtype().kind() == 'i' || f.dtype().kind() == 'u'), InputError,
                      "faces: expected integers, got ", f ? std::string(py::str(f.dtype())) : "no array");
        LIMSURF_CHECK(f.ndim() <= 1, InputError, "faces: expected a vector, got ", f.ndim(), " dimensions");
        if (f.dtype().kind() == 'u' && f.itemsize() == 8) {  // 2^64 - 1 wrapped to -1 in the cast below
            const auto big = py::array_t<unsigned long long, py::array::c_style | py::array::forcecast>::ensure(f);
            for (py::ssize_t i = 0; i < big.size(); ++i) {
                LIMSURF_CHECK(big.data()[i] < static_cast<unsigned long long>(limit_), InputError, "faces[", i,
                              "] = ", big.data()[i], ": out of range [0, ", limit_, ")");
            }
        }
        faces_ = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(f);
        u_ = real_vector(u, "u");
        v_ = real_vector(v, "v");
        for (const auto& [name, a] : {std::pair{"u", &u_}, std::pair{"v", &v_}}) {
            LIMSURF_CHECK(a->size() == faces_.size(), InputError, "faces has ", faces_.size(), " values and ", name,
                          " has ", a->size(), ": give one (face, u, v) per point");
        }
    }
    [[nodiscard]] Index size() const { return static_cast<Index>(faces_.size()); }
    /// Point i, or an empty message on success / the reason it is refused.
    [[nodiscard]] SurfacePoint at(Index i, std::string& error) const {
        const long long face = faces_.data()[i];
        const double x = u_.data()[i];
        const double y = v_.data()[i];
        if (face < 0 || face >= limit_) {
            error = "faces[" + std::to_string(i) + "] = " + std::to_string(face) + ": out of range [0, " +
                    std::to_string(limit_) + ")";
            return {};
        }
        for (const auto& [name, value] : {std::pair{"u", x}, std::pair{"v", y}}) {
            if (!std::isfinite(value)) {
                std::ostringstream message;
                message << name << "[" << i << "] = " << value << ": values must be finite";
                error = message.str();
                return {};
            }
        }
        const bool inside = quad_ ? x >= 0 && x <= 1 && y >= 0 && y <= 1 : x >= 0 && y >= 0 && x + y <= 1;
        if (!inside) {
            std::ostringstream message;
            message << "point " << i << ": (u, v) = (" << x << ", " << y << ") is outside the "
                    << (quad_ ? "unit square" : "triangle u, v >= 0, u + v <= 1") << " of ptex face " << face;
            error = message.str();
            return {};
        }
        return {static_cast<Index>(face), x, y};
    }
    /// Point i as given, unchecked (a face out of range becomes -1): for LimitBasis::prefetch,
    /// which ignores what it cannot use.
    [[nodiscard]] SurfacePoint unchecked(Index i) const {
        const long long face = faces_.data()[i];
        return {face >= 0 && face < limit_ ? static_cast<Index>(face) : Index{-1}, u_.data()[i], v_.data()[i]};
    }

  private:
    static py::array_t<double, py::array::c_style | py::array::forcecast> real_vector(const py::handle& h,
                                                                                      const char* name) {
        const py::array a = py::array::ensure(h);
        const char kind = a ? a.dtype().kind() : '?';
        LIMSURF_CHECK(kind == 'f' || kind == 'i' || kind == 'u', InputError, name, ": expected real numbers, got ",
                      a ? std::string(py::str(a.dtype())) : "no array");
        LIMSURF_CHECK(a.ndim() <= 1, InputError, name, ": expected a vector, got ", a.ndim(), " dimensions");
        return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    }
    py::array_t<long long, py::array::c_style | py::array::forcecast> faces_;
    py::array_t<double, py::array::c_style | py::array::forcecast> u_, v_;
    Index limit_;
    bool quad_;
};

/// Evaluation on several threads that reports the first point (lowest index) that failed, whichever
/// thread met it: the same message on every run. A point fails when it is outside its face's domain
/// or its ptex face is out of range or has no limit surface (a hole, a boundary face under 'none'),
/// which LimitBasis::evaluate refuses.
class FirstFailure {
  public:
    /// Evaluates point i by @p evaluate (called with its SurfacePoint); false (and the failure
    /// noted) when it is refused.
    template <class Evaluate>
    bool evaluate(const PointArrays& points, Index i, const Evaluate& evaluate) {
        std::string error;
        const SurfacePoint p = points.at(i, error);
        if (error.empty()) {
            try {
                evaluate(p);
                return true;
            } catch (const InputError& e) {
                error = "point " + std::to_string(i) + ": " + e.what();
            }
        }
        const std::lock_guard lock(mutex_);
        if (index_ == invalid_index || i < index_) {
            index_ = i;
            message_ = std::move(error);
        }
        return false;
    }
    /// @throws InputError with the first failure's message
    void rethrow() const { LIMSURF_CHECK(index_ == invalid_index, InputError, message_); }

  private:
    std::mutex mutex_;
    Index index_ = invalid_index;
    std::string message_;
};

/// The control points evaluate() applies the weights to: the mesh's own (no copy) or X.
class ControlPoints {
  public:
    ControlPoints(const Basis& b, const py::handle& X) {
        if (X.is_none()) {
            points_ = &b.mesh.mesh.positions();
            return;
        }
        own_ = points_from(X, "X");
        LIMSURF_CHECK(own_.rows() == b.basis.topology().num_vertices(), InputError, "X: expected ",
                      b.basis.topology().num_vertices(), " rows (one per control vertex), got ", own_.rows());
        points_ = &own_;
    }
    [[nodiscard]] const Points& get() const { return *points_; }

  private:
    Points own_;
    const Points* points_ = nullptr;
};

Points control_points(const Basis& b, const py::handle& X) {
    return ControlPoints(b, X).get();
}

constexpr const char* row_names[] = {"position", "du", "dv", "duu", "duv", "dvv"};
constexpr const char* frame_names[] = {"normal", "mean_curvature", "gaussian_curvature", "k1", "k2"};

/// An output array of evaluate(): taken from @p out (a dict of arrays from an earlier call, reused
/// to save allocating and first-touching fresh memory) or new.
template <typename T>
py::array_t<T> output_array(const py::dict& out, const char* key, py::ssize_t n, py::ssize_t cols) {
    if (!out.contains(key)) {
        // Fresh and not yet written: advised for huge pages before the evaluation's threads first
        // touch it (a million points' derivatives are six 24 MB arrays).
        py::array_t<T> fresh = cols == 0 ? py::array_t<T>(n) : py::array_t<T>({n, cols});
        limsurf::detail::advise_huge_pages(fresh.mutable_data(), static_cast<std::size_t>(fresh.nbytes()));
        return fresh;
    }
    const py::object given = out[key];
    LIMSURF_CHECK(py::isinstance<py::array_t<T>>(given), InputError, "out['", key, "']: expected a ",
                  std::is_same_v<T, bool> ? "bool" : "float64", " numpy array");
    auto a = py::reinterpret_borrow<py::array_t<T>>(given);
    const bool shape =
        cols == 0 ? a.ndim() == 1 && a.shape(0) == n : a.ndim() == 2 && a.shape(0) == n && a.shape(1) == cols;
    LIMSURF_CHECK(shape, InputError, "out['", key, "']: expected shape (", n, cols == 0 ? "" : ", ",
                  cols == 0 ? std::string() : std::to_string(cols), "), got ", std::string(py::str(a.attr("shape"))));
    LIMSURF_CHECK((a.flags() & py::array::c_style) && a.writeable(), InputError, "out['", key,
                  "']: expected a writeable C-contiguous array");
    return a;
}

py::dict evaluate(const Basis& b, const py::handle& faces, const py::handle& u, const py::handle& v, int order,
                  const py::handle& X, int threads, bool frames, const py::handle& out_handle) {
    LIMSURF_CHECK(order >= 0 && order <= 2, InputError, "order: expected 0, 1 or 2, got ", order);
    const PointArrays points(b, faces, u, v);
    check_threads(threads);
    const ControlPoints control(b, X);
    const Points& P = control.get();
    LIMSURF_CHECK(out_handle.is_none() || py::isinstance<py::dict>(out_handle), InputError,
                  "out: expected the dict of an earlier evaluate() call, or None");
    const py::dict given = out_handle.is_none() ? py::dict() : py::reinterpret_borrow<py::dict>(out_handle);
    // A misspelled key ('positon') was ignored and a new array returned: the caller's buffer unused.
    for (const auto& [key, value] : given) {
        const std::string name = py::str(key);
        const bool known = name == "curvature_defined" ||
                           std::find(std::begin(row_names), std::end(row_names), name) != std::end(row_names) ||
                           std::find(std::begin(frame_names), std::end(frame_names), name) != std::end(frame_names);
        LIMSURF_CHECK(known, InputError, "out: unknown key '", name,
                      "' (the keys are those evaluate() returns: position, du, dv, duu, duv, dvv, normal, "
                      "mean_curvature, gaussian_curvature, k1, k2, curvature_defined)");
    }
    const auto n = static_cast<py::ssize_t>(points.size());
    const int rows = order == 0 ? 1 : order == 1 ? 3 : 6;
    const bool normals = frames && order >= 1;
    const bool curvatures = frames && order == 2;
    py::dict result;
    std::vector<double*> out;
    for (int r = 0; r < rows; ++r) {
        auto a = output_array<double>(given, row_names[r], n, 3);
        out.push_back(a.mutable_data());
        result[row_names[r]] = a;
    }
    double* frame_out[5] = {};
    for (int k = 0; k < (curvatures ? 5 : normals ? 1 : 0); ++k) {
        auto a = output_array<double>(given, frame_names[k], n, k == 0 ? 3 : 0);
        frame_out[k] = a.mutable_data();
        result[frame_names[k]] = a;
    }
    bool* defined_out = nullptr;
    if (curvatures) {
        auto a = output_array<bool>(given, "curvature_defined", n, 0);
        defined_out = a.mutable_data();
        result["curvature_defined"] = a;
    }
    const auto derivative_order = static_cast<DerivativeOrder>(order);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    // As evaluate_points (limit/batch_evaluation.cpp): interleaved control points once there are
    // as many points as control points (one cache line per control point instead of three).
    const bool interleave = static_cast<Index>(n) >= static_cast<Index>(P.rows());
    {
        const py::gil_scoped_release release;
        const InterleavedPoints interleaved = interleave ? InterleavedPoints(P) : InterleavedPoints();
        FirstFailure failure;
        parallel_ranges(static_cast<Index>(n), threads, [&](Index begin, Index end) {
            LimitPoint values;
            for (Index i = begin; i < end; ++i) {
                if (interleave) {  // the points ahead, as evaluate_points does
                    prefetch_ahead(b.basis, interleaved, i, end, [&](Index k) { return points.unchecked(k); });
                }
                const bool ok = failure.evaluate(points, i, [&](const SurfacePoint& p) {
                    if (interleave) {
                        b.basis.evaluate(interleaved, p, values, derivative_order);
                    } else {
                        b.basis.evaluate(P, p, values, derivative_order);
                    }
                });
                if (!ok) {
                    return;
                }
                const Eigen::Matrix<double, 6, 3>& d = values.d;
                for (int r = 0; r < rows; ++r) {
                    for (int c = 0; c < 3; ++c) {
                        out[static_cast<std::size_t>(r)][3 * i + c] = d(r, c);
                    }
                }
                if (!normals) {
                    continue;
                }
                const bool frame = has_tangent_plane(d);
                // The tangents brought to order one first (exactly, by a power of two): their cross
                // product overflowed for a surface 1e160 across and the normal came back nan.
                const Eigen::Matrix<double, 2, 3> tangents =
                    times_power_of_two(d.middleRows<2>(Du), -magnitude_exponent(d.middleRows<2>(Du)));
                const Eigen::Vector3d nrm = frame ? Eigen::Vector3d(tangents.row(0).cross(tangents.row(1)).normalized())
                                                  : Eigen::Vector3d::Constant(nan);
                for (int c = 0; c < 3; ++c) {
                    frame_out[0][3 * i + c] = nrm(c);
                }
                if (curvatures) {
                    const bool defined = frame && !values.at_extraordinary_vertex;
                    const SurfaceFrame f = defined ? surface_frame(d) : SurfaceFrame{};
                    const double curvature[4] = {f.mean_curvature, f.gaussian_curvature, f.k1, f.k2};
                    for (int k = 0; k < 4; ++k) {
                        frame_out[k + 1][i] = defined ? curvature[k] : nan;
                    }
                    defined_out[i] = defined;
                }
            }
        });
        failure.rethrow();
    }
    return result;
}

/// The weights of the points as scipy CSR matrices (#points × #V), one per requested row.
py::dict weights(const Basis& b, const py::handle& faces, const py::handle& u, const py::handle& v, int order) {
    LIMSURF_CHECK(order >= 0 && order <= 2, InputError, "order: expected 0, 1 or 2, got ", order);
    const PointArrays points(b, faces, u, v);
    const int rows = order == 0 ? 1 : order == 1 ? 3 : 6;
    const Index num_vertices = b.basis.topology().num_vertices();
    std::vector<SparseMatrix> matrices;
    {
        const py::gil_scoped_release release;
        std::vector<std::vector<Eigen::Triplet<double>>> triplets(static_cast<std::size_t>(rows));
        LimitWeights w;
        FirstFailure failure;
        const auto weights_at = [&](const SurfacePoint& p) {
            b.basis.evaluate(p, w, static_cast<DerivativeOrder>(order));
        };
        for (Index i = 0; i < points.size(); ++i) {
            if (!failure.evaluate(points, i, weights_at)) {
                break;
            }
            for (int r = 0; r < rows; ++r) {
                for (Index k = 0; k < w.size(); ++k) {
                    triplets[static_cast<std::size_t>(r)].emplace_back(i, w.vertices[static_cast<std::size_t>(k)],
                                                                       w.w(r, k));
                }
            }
        }
        failure.rethrow();
        for (int r = 0; r < rows; ++r) {
            SparseMatrix A(points.size(), num_vertices);
            A.setFromTriplets(triplets[static_cast<std::size_t>(r)].begin(),
                              triplets[static_cast<std::size_t>(r)].end());
            matrices.push_back(std::move(A));
        }
    }
    py::dict result;
    for (int r = 0; r < rows; ++r) {
        result[row_names[r]] = to_scipy(matrices[static_cast<std::size_t>(r)]);
    }
    return result;
}

}  // namespace

void bind_limit(py::module_& m) {
    py::class_<Basis>(m, "LimitBasis", R"(The exact limit basis of a mesh under a scheme.

For a point (ptex face, u, v) it gives the control vertices the surface depends on and their weights
for the value and the derivatives ∂u, ∂v, ∂uu, ∂uv, ∂vv; evaluate() applies them to control points.
Ptex faces follow OpenSubdiv: a quad is one ptex face, an n-gon n of them (Catmull–Clark, Doo–Sabin);
a triangle is one (Loop, C2g0, domain u, v >= 0, u + v <= 1). Exact at extraordinary vertices,
boundaries, creases and corners (docs/limit_evaluation.md).)")
        .def(py::init([](const Mesh& mesh, const std::string& scheme, std::optional<std::string> boundary,
                         std::optional<std::string> creasing, std::optional<std::string> triangles) {
                 return naming_source(mesh, [&] {
                     const SchemeOptions rules = rules_for(mesh.mesh, RuleNames{boundary, creasing, triangles});
                     return Basis{LimitBasis(mesh.mesh.topology(), scheme_from(scheme), rules), mesh};
                 });
             }),
             "mesh"_a, "scheme"_a, py::kw_only(), "boundary"_a = py::none(), "creasing"_a = py::none(),
             "triangles"_a = py::none(),
             "scheme: 'catmull-clark', 'loop', 'doo-sabin' or 'c2g0'; rules as subdivide(). Raises UnsupportedError\n"
             "for what the scheme's limit cannot do (Loop on quads, faces beyond 128 corners...).")
        .def_property_readonly("num_ptex_faces", [](const Basis& b) { return b.basis.num_ptex_faces(); })
        .def_property_readonly("num_vertices", [](const Basis& b) { return b.basis.topology().num_vertices(); })
        .def_property_readonly("scheme", [](const Basis& b) { return std::string(to_string(b.basis.scheme())); })
        .def_property_readonly(
            "domain", [](const Basis& b) { return b.basis.domain() == ParameterDomain::Quad ? "quad" : "triangle"; },
            "'quad' (unit square) or 'triangle' (u, v >= 0, u + v <= 1).")
        .def_property_readonly(
            "mesh", [](const Basis& b) { return b.mesh; }, "The mesh the basis was built from.")
        .def(
            "ptex_face",
            [](const Basis& b, Index p) {
                LIMSURF_CHECK(p >= 0 && p < b.basis.num_ptex_faces(), InputError, "ptex face ", p, " out of range [0, ",
                              b.basis.num_ptex_faces(), ")");
                const PtexFace f = b.basis.ptex_face(p);
                return py::make_tuple(f.control_face, f.corner);
            },
            "p"_a, "(control face, corner) of ptex face p; corner is -1 when the face is one ptex face.")
        .def(
            "has_limit_surface",
            [](const Basis& b) {
                py::array_t<bool> out(b.basis.num_ptex_faces());
                for (Index p = 0; p < b.basis.num_ptex_faces(); ++p) {
                    out.mutable_data()[p] = b.basis.has_limit_surface(p);
                }
                return out;
            },
            "Boolean array over ptex faces: False for holes and for faces touching the boundary under 'none'.")
        .def("evaluate", &evaluate, "faces"_a, "u"_a, "v"_a, "order"_a = 2, py::kw_only(), "X"_a = py::none(),
             "threads"_a = 0, "frames"_a = true, "out"_a = py::none(),
             R"(Evaluates the limit surface at the points (faces[i], u[i], v[i]) (arrays of equal length).

order 0: 'position'; 1: also 'du', 'dv', 'normal'; 2: also 'duu', 'duv', 'dvv', 'mean_curvature'
(H = (k1 + k2)/2, 1 on the unit sphere), 'gaussian_curvature', 'k1' >= 'k2' and the boolean
'curvature_defined'. Arrays are (n, 3) or (n,) float64. Curvatures are NaN exactly where
'curvature_defined' is False: at an extraordinary, crease or corner vertex itself (where they are not
defined) or where the tangents are parallel (normal NaN too), as `limsurf eval` prints null.
X: other control points (#V × 3) for the same basis (default the mesh's V). threads: 0 = all cores.
frames=False leaves out the normal and the curvatures (derivatives only, the cheapest evaluation).
out: the dict an earlier call returned, for points of the same count: its arrays are filled again in
place and returned (no allocation; evaluating point batches in a loop this saves a fifth of the time).
When a point is bad the call raises and out's arrays may already hold some rows of this call (as numpy's
out= does): do not read them after an error.
faces as int64 and u, v as float64 C-contiguous arrays are read without a copy.
The GIL is released while C++ works. Raises InputError naming the first bad point.)")
        .def("weights", &weights, "faces"_a, "u"_a, "v"_a, "order"_a = 0,
             "The limit weights at the points as scipy CSR matrices (#points × #V) under the keys 'position' (and\n"
             "'du', 'dv' for order 1, also 'duu', 'duv', 'dvv' for order 2): evaluate(...)['du'] equals W['du'] @ V\n"
             "to rounding (evaluate applies V before the basis, the faster path; docs/limit_evaluation.md).")
        .def(
            "patch",
            [](const Basis& b, Index face, double u, double v, const py::handle& X, bool points) -> py::object {
                const Eigen::MatrixXd P = control_points(b, X);
                const SurfacePoint point{face, u, v};
                LimitPatch patch;
                Eigen::MatrixXd data;
                if (!(points ? b.basis.patch(point, patch) : b.basis.patch_data(point, P, patch, data))) {
                    return py::none();
                }
                if (points) {
                    data = patch.control_data(P);
                }
                py::array_t<Index> vertices(static_cast<py::ssize_t>(patch.vertices.size()));
                std::copy(patch.vertices.begin(), patch.vertices.end(), vertices.mutable_data());
                // The control net itself: each point its weights (with the offset) applied to X.
                const Eigen::MatrixXd net = data.topRows(patch.size()).rowwise() + data.bottomRows<1>();
                py::dict out("domain"_a = patch.domain == ParameterDomain::Quad ? "quad" : "triangle",
                             "vertices"_a = vertices, "origin"_a = to_numpy(Eigen::VectorXd(patch.origin)),
                             "axes"_a = to_numpy(Eigen::MatrixXd(patch.axes)), "control_points"_a = to_numpy(net));
                if (points) {
                    out["points"] = to_numpy(patch.points);
                    out["offset"] = to_numpy(Eigen::VectorXd(patch.offset.transpose()));
                }
                return out;
            },
            "face"_a, "u"_a, "v"_a, py::kw_only(), "X"_a = py::none(), "points"_a = true,
            R"(The regular patch of the limit surface that holds the point (face, u, v), or None where there is
none (Doo–Sabin, C2g0, and within 2^-60 of an extraordinary vertex; docs/limit_evaluation.md "Patches").

A dict: 'domain' ('quad': a bicubic B-spline patch of 16 points; 'triangle': a quartic box spline of
12), 'vertices' (the support, int64), 'points' (16 or 12 × #support: each control point's weights
over the support, less 'offset') and 'offset' (#support: part of every control point; the limit
mask of an extraordinary vertex the patch is n levels towards, else zeros), 'origin' and 'axes'
(ptex (u, v) = origin + axes @ (s, t) for the patch parameter (s, t)), and 'control_points'
(16 or 12 × 3: the control net of X, default the mesh's V). Every point of the patch's tile shares
them. points=False leaves out 'points' and 'offset' and forms the control net without them, in the
cheaper order (LimitBasis::patch_data; the same net to rounding). Raises InputError for a bad point,
as evaluate().)")
        .def(
            "vertex_limit_matrix",
            [](const Basis& b) {
                SparseMatrix P;
                {
                    const py::gil_scoped_release release;
                    P = b.basis.vertex_limit_matrix();
                }
                return to_scipy(P);
            },
            "The snapping matrix P (#V × #V, SEC §3.4): P @ V are the limit positions of the control vertices.")
        .def(
            "limit_positions",
            [](const Basis& b, const py::handle& X) {
                const Points P = control_points(b, X);
                Points limit;
                {
                    const py::gil_scoped_release release;
                    limit = b.basis.vertex_limit_matrix() * P;
                }
                return to_numpy(limit);
            },
            py::kw_only(), "X"_a = py::none(), "The limit positions of the control vertices (#V × 3).")
        .def(
            "quadrature_samples",
            [](const Basis& b, int degree, int tiles) {
                QuadratureSamples q;
                {
                    const py::gil_scoped_release release;
                    q = quadrature_samples(b.basis, SamplerOptions{degree, tiles, 0}, 0, b.basis.num_ptex_faces());
                }
                const auto n = static_cast<py::ssize_t>(q.points.size());
                py::array_t<long long> faces(n);
                py::array_t<double> u = new_vector(n), v = new_vector(n), weights = new_vector(n);
                for (py::ssize_t i = 0; i < n; ++i) {
                    const SurfacePoint& p = q.points[static_cast<std::size_t>(i)];
                    faces.mutable_data()[i] = p.face;
                    u.mutable_data()[i] = p.u;
                    v.mutable_data()[i] = p.v;
                    weights.mutable_data()[i] = q.weights[static_cast<std::size_t>(i)];
                }
                return py::dict("faces"_a = faces, "u"_a = u, "v"_a = v, "weights"_a = weights);
            },
            py::kw_only(), "degree"_a = 8, "tiles"_a = 0,
            R"(The quadrature samples limsurf integrates with (measure, the Galerkin matrices): a rule of the
given degree on every ptex face with a limit surface (Gauss on the unit square, a symmetric rule on the
triangle), on quadtree tiles `tiles` levels deep towards extraordinary corners, where the surface is
only piecewise polynomial. Returns 'faces' (int64), 'u', 'v' and the parameter-domain 'weights' (they
sum to 1 per quad ptex face, 1/2 per triangle): ∫ f dA ≈ Σ weights · f · |∂u x × ∂v x| with the
derivatives from evaluate(faces, u, v, order=1). Raises InputError for a degree outside the rules'
range or tiles outside 0..30.)");
}

}  // namespace limsurf::python
