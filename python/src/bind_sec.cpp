// Subdivision Exterior Calculus: exterior derivatives, inner products and operators as scipy
// sparse matrices (SEC §2–3), and the Poisson solver of `limsurf poisson`.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/poisson.h"
#include "limsurf/sec/exterior_derivative.h"
#include "limsurf/sec/inner_products.h"
#include "limsurf/sec/operators.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

InnerProductOptions inner_product_options(const std::string& method, int level, bool lumped) {
    InnerProductOptions options;
    options.method = parse_inner_product_method(method);
    options.level = level;
    options.lumped = lumped;
    return options;
}

InnerProducts inner_products_of(const Mesh& mesh, const std::string& scheme, const std::string& method, int level,
                                bool lumped, const RuleNames& rules) {
    return naming_source(mesh, [&] {
        const SchemeKind kind = scheme_from(scheme);
        const SchemeOptions scheme_options = rules_for(mesh.mesh, rules);
        const InnerProductOptions options = inner_product_options(method, level, lumped);
        const py::gil_scoped_release release;
        return control_inner_products(mesh.mesh.topology(), mesh.mesh.positions(), kind, options, scheme_options);
    });
}

/// Boundary values: None (0), a number, a callable of positions, or #V values at the control vertices.
SurfaceFunction boundary_function(const py::handle& g, Index num_vertices) {
    if (g.is_none()) {
        return {};
    }
    if (py::isinstance<py::function>(g)) {
        return surface_function(py::reinterpret_borrow<py::function>(g), "boundary_values");
    }
    if (py::isinstance<py::float_>(g) || py::isinstance<py::int_>(g)) {
        const double value = g.cast<double>();
        return [value](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), value); };
    }
    const Eigen::VectorXd values = vector_from(g, "boundary_values", num_vertices);
    return [values](const Points& P) {
        LIMSURF_CHECK(P.rows() == values.size(), InputError,
                      "boundary_values given per control vertex cannot serve a reference: pass a function of position");
        return values;
    };
}

py::dict poisson(const Mesh& mesh, const std::string& scheme, const py::handle& rhs,
                 const SurfacePoissonOptions& options, const py::handle& boundary) {
    return naming_source(mesh, [&] {
        const Index n = mesh.mesh.num_vertices();
        SurfacePoissonData data;
        if (py::isinstance<py::function>(rhs)) {
            data.f = surface_function(py::reinterpret_borrow<py::function>(rhs), "rhs");
        } else {
            data.f_values = vector_from(rhs, "rhs", n);
        }
        data.boundary = boundary_function(boundary, n);
        const SchemeKind kind = scheme_from(scheme);
        SurfacePoissonResult r;
        {
            const py::gil_scoped_release release;
            r = solve_surface_poisson(mesh.mesh, kind, options, data);
        }
        const bool sec = options.method == LaplacianMethod::Sec || options.method == LaplacianMethod::SecSnap;
        const bool iga = options.method == LaplacianMethod::Iga;
        const Eigen::VectorXd& u = r.solution.u;
        py::dict out("scheme"_a = scheme, "method"_a = to_string(options.method), "level"_a = sec ? options.level : 0,
                     "lumped"_a = options.lumped, "vertices"_a = n, "closed"_a = mesh.mesh.topology().is_closed(),
                     "solver"_a = r.solution.solver, "residual"_a = r.solution.residual,
                     "mean_removed"_a = r.solution.mean_removed,
                     "quadrature"_a = iga ? py::object(py::dict("degree"_a = options.degree, "tiles"_a = options.tiles))
                                          : py::object(py::none()),
                     "u_min"_a = u.minCoeff(), "u_max"_a = u.maxCoeff(), "u"_a = to_numpy(u), "f"_a = to_numpy(r.f));
        if (r.reference) {
            out["reference"] = reference_dict(*r.reference);
        }
        return out;
    });
}

}  // namespace

void bind_sec(py::module_& m) {
    m.def(
        "exterior_derivatives",
        [](const Mesh& mesh) {
            const Topology& t = mesh.mesh.topology();
            return py::make_tuple(to_scipy(exterior_derivative_0(t)), to_scipy(exterior_derivative_1(t)));
        },
        "mesh"_a,
        "(d0, d1): d0 (#E × #V, edge e runs from Mesh.edges[e, 0] to [e, 1]) and d1 (#F × #E, faces walked\n"
        "counter-clockwise); d1 @ d0 == 0 exactly (SEC §2).");
    m.def(
        "inner_products",
        [](const Mesh& mesh, const std::string& scheme, const std::string& method, std::optional<int> given_level,
           bool lumped, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            const InnerProducts ip =
                inner_products_of(mesh, scheme, method, level, lumped, RuleNames{boundary, creasing, triangles});
            return py::dict("M0"_a = to_scipy(ip.M0), "M1"_a = to_scipy(ip.M1), "M2"_a = to_scipy(ip.M2));
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "lumped"_a = false,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The inner products M0 (#V × #V), M1 (#E × #E), M2 (#F × #F) on the control mesh (SEC §3.4) as scipy CSR:
method 'dec' (polygonal, of the control mesh), 'decsnap' (vertices at their limit positions),
'sec' (Eq. 12: (A_k^L)ᵀ M_k^L A_k^L at level L = `level`, None: 3), 'secsnap' (Eq. 16); `level` with
'dec' or 'decsnap' is refused (it would be ignored), in every function that takes a method. lumped replaces M0 and
M2 by diag(M 1) (§3.5). scheme: 'loop' or 'catmull-clark' (the form subdivision rules).)");
    m.def(
        "operators",
        [](const Mesh& mesh, const std::string& scheme, const std::string& method, std::optional<int> given_level,
           bool lumped, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            InnerProducts ip =
                inner_products_of(mesh, scheme, method, level, lumped, RuleNames{boundary, creasing, triangles});
            const Operators ops(mesh.mesh.topology(), std::move(ip));
            const InnerProducts& m_ = ops.inner_products();
            return py::dict("d0"_a = to_scipy(ops.d0()), "d1"_a = to_scipy(ops.d1()), "M0"_a = to_scipy(m_.M0),
                            "M1"_a = to_scipy(m_.M1), "M2"_a = to_scipy(m_.M2),
                            "laplacian"_a = to_scipy(ops.laplacian()), "divergence"_a = to_scipy(ops.divergence()));
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "lumped"_a = false,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The operators of SEC Table 1 as scipy CSR: d0, d1, M0, M1, M2 (as inner_products()), the weak
Laplacian L = d0ᵀ M1 d0 (#V × #V, symmetric positive semi-definite, constants in its kernel) and the
divergence d0ᵀ M1 (#V × #E). The strong Laplacian is M0⁻¹ L.)");
    m.def(
        "poisson",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& rhs, const std::string& method,
           std::optional<int> given_level, bool lumped, std::optional<int> degree, std::optional<int> tiles,
           const py::handle& boundary_values, std::optional<int> reference_level,
           std::optional<std::int64_t> max_memory, std::optional<std::string> boundary,
           std::optional<std::string> creasing, std::optional<std::string> triangles, int threads) {
            const int level = level_for(method, given_level);
            LIMSURF_CHECK(threads >= 0, InputError, "threads must be >= 0 (0: all cores), not ", threads);
            SurfacePoissonOptions options;
            options.num_threads = threads;
            options.method = parse_laplacian_method(method);
            options.level = level;
            options.lumped = lumped;
            require_iga_for_quadrature(options.method, method, degree, tiles);
            options.degree = degree.value_or(options.degree);
            options.tiles = tiles.value_or(options.tiles);
            options.scheme_options = rules_for(mesh.mesh, RuleNames{boundary, creasing, triangles});
            options.reference_level = reference_level;
            options.max_memory = max_memory;
            return poisson(mesh, scheme, rhs, options, boundary_values);
        },
        "mesh"_a, "scheme"_a, "rhs"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "lumped"_a = false,
        "degree"_a = py::none(), "tiles"_a = py::none(), "boundary_values"_a = py::none(),
        "reference_level"_a = py::none(), "max_memory"_a = py::none(), "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(), "threads"_a = 0,
        R"(Solves −Δu = f on the limit surface with every unknown on the control mesh: `limsurf poisson`.

rhs: a function f(P) of an (n, 3) position array returning n values (integrated where the method
integrates: level L for sec, the quadrature points for iga; it may be called several times, on
blocks of points, so it must depend on the point alone), or #V values at the control vertices.
method: 'dec', 'decsnap', 'sec', 'secsnap' (SEC §3 inner products; level L, lumped) or 'iga'
(Galerkin with the limit basis; quadrature `degree` per tile and `tiles` levels towards extraordinary
vertices, None: 8 and 6; other methods refuse them). Closed meshes: the mean of f is removed
and u has mean 0. Open meshes: boundary_values (None = 0, a number, a function of position, or #V
values) at the boundary vertices. reference_level K: also solve with DEC on the K-times subdivided
mesh and report the relative L2/Linf differences (needs rhs as a function). threads: for the sec
inner products and the iga quadrature, 0 = all cores (the result does not depend on it).
Returns the numbers of `limsurf poisson --json` under the same keys, with the arrays 'u' and 'f' (#V).)");
}

}  // namespace limsurf::python
