// limsurf.LimitBasis: exact limit evaluation vectorised over arrays of points (GIL released).
#include <limits>
#include <mutex>
#include <string>

#include <Eigen/Geometry>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
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


/// The points (faces[i], u[i], v[i]), each checked as `limsurf eval --points` checks a line (a face
/// without a limit surface is refused by LimitBasis::evaluate itself: see evaluate_all).
std::vector<SurfacePoint> surface_points(const Basis& b, const py::handle& faces, const py::handle& u,
                                         const py::handle& v) {
    const std::vector<Index> face = indices_from(faces, "faces", b.basis.num_ptex_faces());
    const auto n = static_cast<Index>(face.size());
    const Eigen::VectorXd us = vector_from(u, "u", n);
    const Eigen::VectorXd vs = vector_from(v, "v", n);
    const bool quad = b.basis.domain() == ParameterDomain::Quad;
    std::vector<SurfacePoint> points(face.size());
    for (Index i = 0; i < n; ++i) {
        const double x = us(i);
        const double y = vs(i);
        const bool inside = quad ? x >= 0 && x <= 1 && y >= 0 && y <= 1 : x >= 0 && y >= 0 && x + y <= 1;
        LIMSURF_CHECK(inside, InputError, "point ", i, ": (u, v) = (", x, ", ", y, ") is outside the ",
                      quad ? "unit square" : "triangle u, v >= 0, u + v <= 1", " of ptex face ", face[i]);
        points[static_cast<std::size_t>(i)] = {face[i], x, y};
    }
    return points;
}

/// Evaluation on several threads that reports the first point (lowest index) that failed, whichever
/// thread met it: the same message on every run. A point fails when its ptex face has no limit surface
/// (a hole, a boundary face under 'none'), which LimitBasis::evaluate refuses.
class FirstFailure {
  public:
    /// Evaluates point i into w; false (and the failure noted) when it throws.
    bool evaluate(const LimitBasis& basis, const std::vector<SurfacePoint>& points, Index i, LimitWeights& w,
                  DerivativeOrder order) {
        try {
            basis.evaluate(points[static_cast<std::size_t>(i)], w, order);
            return true;
        } catch (const InputError& e) {
            const std::lock_guard lock(mutex_);
            if (index_ == invalid_index || i < index_) {
                index_ = i;
                message_ = e.what();
            }
            return false;
        }
    }
    /// @throws InputError "point i: ..." for the first failure
    void rethrow() const {
        LIMSURF_CHECK(index_ == invalid_index, InputError, "point ", index_, ": ", message_);
    }

  private:
    std::mutex mutex_;
    Index index_ = invalid_index;
    std::string message_;
};

Points control_points(const Basis& b, const py::handle& X) {
    if (X.is_none()) {
        return b.mesh.mesh.positions();
    }
    Points P = points_from(X, "X");
    LIMSURF_CHECK(P.rows() == b.basis.topology().num_vertices(), InputError, "X: expected ",
                  b.basis.topology().num_vertices(), " rows (one per control vertex), got ", P.rows());
    return P;
}

constexpr const char* row_names[] = {"position", "du", "dv", "duu", "duv", "dvv"};

py::dict evaluate(const Basis& b, const py::handle& faces, const py::handle& u, const py::handle& v, int order,
                  const py::handle& X, int threads, bool frames) {
    LIMSURF_CHECK(order >= 0 && order <= 2, InputError, "order: expected 0, 1 or 2, got ", order);
    const std::vector<SurfacePoint> points = surface_points(b, faces, u, v);
    const Points P = control_points(b, X);
    const auto n = static_cast<py::ssize_t>(points.size());
    const int rows = order == 0 ? 1 : order == 1 ? 3 : 6;
    std::vector<py::array_t<double>> derivative;
    std::vector<double*> out;
    for (int r = 0; r < rows; ++r) {
        derivative.push_back(new_array(n, 3));
        out.push_back(derivative.back().mutable_data());
    }
    py::array_t<double> normal;
    py::array_t<double> mean;
    py::array_t<double> gauss;
    py::array_t<double> k1;
    py::array_t<double> k2;
    py::array_t<bool> defined;
    const bool normals = frames && order >= 1;
    const bool curvatures = frames && order == 2;
    if (normals) {
        normal = new_array(n, 3);
    }
    if (curvatures) {
        mean = new_vector(n);
        gauss = new_vector(n);
        k1 = new_vector(n);
        k2 = new_vector(n);
        defined = py::array_t<bool>(n);
    }
    double* normal_out = normals ? normal.mutable_data() : nullptr;
    double* curvature_out[4] = {curvatures ? mean.mutable_data() : nullptr, curvatures ? gauss.mutable_data() : nullptr,
                                curvatures ? k1.mutable_data() : nullptr, curvatures ? k2.mutable_data() : nullptr};
    bool* defined_out = curvatures ? defined.mutable_data() : nullptr;
    const auto derivative_order = static_cast<DerivativeOrder>(order);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    {
        const py::gil_scoped_release release;
        FirstFailure failure;
        parallel_ranges(static_cast<Index>(n), threads, [&](Index begin, Index end) {
            LimitWeights w;
            for (Index i = begin; i < end; ++i) {
                if (!failure.evaluate(b.basis, points, i, w, derivative_order)) {
                    return;
                }
                const Eigen::Matrix<double, 6, 3> d = w.apply(P);
                for (int r = 0; r < rows; ++r) {
                    for (int c = 0; c < 3; ++c) {
                        out[static_cast<std::size_t>(r)][3 * i + c] = d(r, c);
                    }
                }
                if (!normals) {
                    continue;
                }
                const bool frame = has_tangent_plane(d);
                const Eigen::Vector3d nrm = frame ? Eigen::Vector3d(d.row(Du).cross(d.row(Dv)).normalized())
                                                  : Eigen::Vector3d::Constant(nan);
                for (int c = 0; c < 3; ++c) {
                    normal_out[3 * i + c] = nrm(c);
                }
                if (curvatures) {
                    const bool ok = frame && !w.at_extraordinary_vertex;
                    const SurfaceFrame f = ok ? surface_frame(d) : SurfaceFrame{};
                    const double values[4] = {f.mean_curvature, f.gaussian_curvature, f.k1, f.k2};
                    for (int k = 0; k < 4; ++k) {
                        curvature_out[k][i] = ok ? values[k] : nan;
                    }
                    defined_out[i] = ok;
                }
            }
        });
        failure.rethrow();
    }
    py::dict result;
    for (int r = 0; r < rows; ++r) {
        result[row_names[r]] = derivative[static_cast<std::size_t>(r)];
    }
    if (normals) {
        result["normal"] = normal;
    }
    if (curvatures) {
        result["mean_curvature"] = mean;
        result["gaussian_curvature"] = gauss;
        result["k1"] = k1;
        result["k2"] = k2;
        result["curvature_defined"] = defined;
    }
    return result;
}

/// The weights of the points as scipy CSR matrices (#points × #V), one per requested row.
py::dict weights(const Basis& b, const py::handle& faces, const py::handle& u, const py::handle& v, int order) {
    LIMSURF_CHECK(order >= 0 && order <= 2, InputError, "order: expected 0, 1 or 2, got ", order);
    const std::vector<SurfacePoint> points = surface_points(b, faces, u, v);
    const int rows = order == 0 ? 1 : order == 1 ? 3 : 6;
    const Index num_vertices = b.basis.topology().num_vertices();
    std::vector<SparseMatrix> matrices;
    {
        const py::gil_scoped_release release;
        std::vector<std::vector<Eigen::Triplet<double>>> triplets(static_cast<std::size_t>(rows));
        LimitWeights w;
        FirstFailure failure;
        for (std::size_t i = 0; i < points.size(); ++i) {
            if (!failure.evaluate(b.basis, points, static_cast<Index>(i), w, static_cast<DerivativeOrder>(order))) {
                break;
            }
            for (int r = 0; r < rows; ++r) {
                for (Index k = 0; k < w.size(); ++k) {
                    triplets[static_cast<std::size_t>(r)].emplace_back(static_cast<Index>(i),
                                                                       w.vertices[static_cast<std::size_t>(k)], w.w(r, k));
                }
            }
        }
        failure.rethrow();
        for (int r = 0; r < rows; ++r) {
            SparseMatrix A(static_cast<Index>(points.size()), num_vertices);
            A.setFromTriplets(triplets[static_cast<std::size_t>(r)].begin(), triplets[static_cast<std::size_t>(r)].end());
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
            "domain",
            [](const Basis& b) { return b.basis.domain() == ParameterDomain::Quad ? "quad" : "triangle"; },
            "'quad' (unit square) or 'triangle' (u, v >= 0, u + v <= 1).")
        .def_property_readonly("mesh", [](const Basis& b) { return b.mesh; }, "The mesh the basis was built from.")
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
             "threads"_a = 0, "frames"_a = true,
             R"(Evaluates the limit surface at the points (faces[i], u[i], v[i]) (arrays of equal length).

order 0: 'position'; 1: also 'du', 'dv', 'normal'; 2: also 'duu', 'duv', 'dvv', 'mean_curvature'
(H = (k1 + k2)/2, 1 on the unit sphere), 'gaussian_curvature', 'k1' >= 'k2' and the boolean
'curvature_defined'. Arrays are (n, 3) or (n,) float64. Curvatures are NaN exactly where
'curvature_defined' is False: at an extraordinary, crease or corner vertex itself (where they are not
defined) or where the tangents are parallel (normal NaN too), as `limsurf eval` prints null.
X: other control points (#V × 3) for the same basis (default the mesh's V). threads: 0 = all cores.
frames=False leaves out the normal and the curvatures (derivatives only, the cheapest evaluation).
The GIL is released while C++ works. Raises InputError naming the first bad point.)")
        .def("weights", &weights, "faces"_a, "u"_a, "v"_a, "order"_a = 0,
             "The limit weights at the points as scipy CSR matrices (#points × #V) under the keys 'position' (and\n"
             "'du', 'dv' for order 1, also 'duu', 'duv', 'dvv' for order 2): evaluate(...)['du'] == W['du'] @ V.")
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
            py::kw_only(), "X"_a = py::none(), "The limit positions of the control vertices (#V × 3).");
}

}  // namespace limsurf::python
