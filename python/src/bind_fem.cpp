// The Galerkin layer: mass and Laplace–Beltrami stiffness of the limit basis, Kirchhoff–Love plate
// and shell stiffnesses as scipy matrices, and the plate and shell solvers of `limsurf plate` and
// `limsurf shell` (apps/plate.h, apps/shell.h) with their --json numbers.
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/plate.h"
#include "limsurf/apps/shell.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/fem/plate.h"
#include "limsurf/fem/shell.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

bool is_number(const py::handle& x) {
    return py::isinstance<py::float_>(x) || py::isinstance<py::int_>(x);
}

/// The schemes of the plates and shells: the C¹ limit surfaces with the boundary rules they rely on.
SchemeKind fem_scheme(const std::string& name, const char* what) {
    const SchemeKind kind = scheme_from(name);
    LIMSURF_CHECK(kind == SchemeKind::CatmullClark || kind == SchemeKind::Loop, InputError, what,
                  ": scheme must be catmull-clark or loop, got '", name, "'");
    return kind;
}

py::object mesh_object(const Topology& topology, const Points& X) {
    return py::cast(Mesh{ControlMesh(topology, X), SourceMap{}, ValidationReport{}});
}

py::tuple vec(const Eigen::Vector3d& x) {
    return py::make_tuple(x.x(), x.y(), x.z());
}

py::object optional_float(const std::optional<double>& x) {
    return x ? py::object(py::float_(*x)) : py::object(py::none());
}

Eigen::Vector3d vector3_from(const py::handle& x, const std::string& name) {
    return vector_from(x, name, 3);
}

/// Runs @p work on the quadrature of the limit surface of @p mesh under @p scheme (with the rules of
/// the keyword arguments) without the GIL.
template <class Work>
auto with_quadrature(const Mesh& mesh, const std::string& scheme, const RuleNames& rules, int degree, int tiles,
                     Work&& work) {
    return naming_source(mesh, [&] {
        const SchemeKind kind = scheme_from(scheme);
        const SchemeOptions options = rules_for(mesh.mesh, rules);
        const py::gil_scoped_release release;
        const LimitBasis basis(mesh.mesh.topology(), kind, options);
        const LimitSampler sampler(basis, SamplerOptions{degree, tiles, 0});
        return work(sampler);
    });
}

// ---- plate ----

/// The load of limsurf.plate: a name ('uniform', 'sinusoidal', 'single-wave') with the pressure, a
/// number (uniform), a function of position, or one control value per vertex.
PlateLoad plate_load(const py::handle& load, const std::optional<double>& pressure, Index num_vertices) {
    PlateLoad out;
    if (py::isinstance<py::str>(load)) {
        const std::string name = load.cast<std::string>();
        const auto shape = plate_load_shape(name);
        LIMSURF_CHECK(shape.has_value(), InputError, "load: unknown load '", name,
                      "' (expected uniform, sinusoidal, single-wave, a number, a function of position or one "
                      "value per control vertex)");
        out.shape = *shape;
        out.pressure = pressure.value_or(1e4);
        return out;
    }
    LIMSURF_CHECK(!pressure, InputError,
                  "pressure: applies to the loads given by name ('uniform', 'sinusoidal', 'single-wave'); a number "
                  "is the uniform load itself");
    if (py::isinstance<py::function>(load)) {
        out.shape = PlateLoadShape::Function;
        out.function = surface_function(py::reinterpret_borrow<py::function>(load), "load");
    } else if (is_number(load)) {
        out.shape = PlateLoadShape::Uniform;
        out.pressure = load.cast<double>();
    } else {
        out.shape = PlateLoadShape::Values;
        out.values = vector_from(load, "load", num_vertices);
    }
    return out;
}

/// A pass's deflections and Navier errors under the CLI's keys.
py::dict plate_pass_dict(const std::optional<double>& centre, const std::optional<double>& quarter, double largest,
                         const std::optional<PlateNavierComparison>& navier) {
    py::dict entry("centre_deflection"_a = optional_float(centre), "quarter_deflection"_a = optional_float(quarter),
                   "max_deflection"_a = largest);
    if (navier) {
        const PlateNavierComparison& n = *navier;
        entry["navier"] =
            py::dict("centre_deflection"_a = n.centre_deflection, "quarter_deflection"_a = n.quarter_deflection,
                     "centre_relative_error"_a = optional_float(n.centre_relative_error),
                     "quarter_relative_error"_a = optional_float(n.quarter_relative_error),
                     "l2_relative_error"_a = n.l2_relative_error, "energy_relative_error"_a = n.energy_relative_error);
    }
    return entry;
}

py::dict plate_level_dict(const PlateLevel& level, bool tuned) {
    py::dict entry =
        plate_pass_dict(level.centre_deflection, level.quarter_deflection, level.max_deflection, level.navier);
    entry["level"] = level.level;
    entry["vertices"] = level.topology.num_vertices();
    entry["faces"] = level.topology.num_faces();
    entry["residual"] = level.solution.residual;
    if (tuned) {
        py::list vertices;
        for (const PlateTunedVertex& v : level.tuned_vertices) {
            py::dict d("vertex"_a = v.vertex, "valence"_a = v.valence, "shape"_a = to_string(v.shape),
                       "lambda"_a = v.weights.lambda, "alpha"_a = v.weights.weights.alpha,
                       "beta"_a = v.weights.weights.beta, "gamma"_a = v.weights.weights.gamma);
            if (v.decomposition) {
                const ShapeDecomposition& k = *v.decomposition;
                d["decomposition"] = shape_decomposition_dict(k);
            }
            vertices.append(d);
        }
        entry["tuned_vertices"] = vertices;
    }
    if (level.first_pass) {
        const PlatePass& first = *level.first_pass;
        entry["first_pass"] =
            plate_pass_dict(first.centre_deflection, first.quarter_deflection, first.max_deflection, first.navier);
    }
    entry["w"] = to_numpy(level.solution.w);
    if (level.load_values.size() > 0) {
        entry["p"] = to_numpy(level.load_values);
    }
    entry["mesh"] = mesh_object(level.topology, level.X);
    return entry;
}

py::dict plate(const Mesh& mesh, const std::string& scheme, const py::handle& load, const std::string& support,
               double E, double nu, double thickness, int levels, std::optional<double> pressure, int degree, int tiles,
               const std::string& tuned, std::optional<int> decide_level) {
    return naming_source(mesh, [&] {
        PlateStudyOptions options;
        options.material = PlateMaterial{E, nu, thickness};
        options.support = parse_plate_support(support);
        options.scheme = fem_scheme(scheme, "plate");
        options.levels = levels;
        options.quadrature = SamplerOptions{degree, tiles, 0};
        options.tuning = parse_plate_tuning(tuned);
        options.decide_level = decide_level;
        const PlateLoad spec = plate_load(load, pressure, mesh.mesh.num_vertices());
        PlateStudy r;
        {
            const py::gil_scoped_release release;
            r = solve_plate_levels(mesh.mesh.topology(), mesh.mesh.positions(), spec, options);
        }
        const bool named = spec.shape != PlateLoadShape::Function && spec.shape != PlateLoadShape::Values;
        py::list rows;
        for (const PlateLevel& level : r.levels) {
            rows.append(plate_level_dict(level, options.tuning != PlateTuning::None));
        }
        const PlateRectangle& box = r.rectangle;
        py::dict out("scheme"_a = scheme, "load"_a = to_string(spec.shape),
                     "pressure"_a = named ? py::object(py::float_(spec.pressure)) : py::object(py::none()),
                     "support"_a = support, "E"_a = E, "nu"_a = nu, "thickness"_a = thickness,
                     "bending_rigidity"_a = r.bending_rigidity, "tuned"_a = tuned, "decide_level"_a = decide_level,
                     "warnings"_a = r.warnings,
                     "rectangle"_a = py::dict("x0"_a = box.x0, "y0"_a = box.y0, "a"_a = box.a, "b"_a = box.b),
                     "levels"_a = rows);
        if (r.navier_load && !r.rectangle_plate) {
            out["navier"] = "not compared: the plate is not its bounding rectangle";
        }
        const py::dict finest = rows[rows.size() - 1].cast<py::dict>();
        out["w"] = finest["w"];
        out["mesh"] = finest["mesh"];
        return out;
    });
}

// ---- shell ----

std::array<bool, 3> components_from(const py::handle& letters, const std::string& name) {
    LIMSURF_CHECK(py::isinstance<py::str>(letters), InputError, name,
                  ": the components are a string of letters "
                  "among x, y, z, e.g. 'xz'");
    const std::string text = letters.cast<std::string>();
    std::array<bool, 3> out{false, false, false};
    for (const char c : text) {
        LIMSURF_CHECK(c == 'x' || c == 'y' || c == 'z', InputError, name, " '", text,
                      "': the components are letters among x, y, z");
        out[static_cast<std::size_t>(c - 'x')] = true;
    }
    LIMSURF_CHECK(!text.empty(), InputError, name, ": no components");
    return out;
}

/// The truth of a support function's result for one point: a bool, a number or an array of one.
bool truth_from(const py::object& result, const std::string& name) {
    const py::array a = py::array::ensure(result);
    LIMSURF_CHECK(a, InputError, name, ": expected a boolean, got ",
                  std::string(py::str(py::type::of(result).attr("__name__"))));
    const char kind = a.dtype().kind();
    LIMSURF_CHECK(kind == 'b' || kind == 'i' || kind == 'u' || kind == 'f', InputError, name,
                  ": expected booleans, got dtype ", std::string(py::str(a.dtype())));
    LIMSURF_CHECK(a.size() == 1, InputError, name, ": expected 1 value for 1 point, got ", a.size());
    const auto c = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
    // nan != 0 is true: a nan used to select the point.
    LIMSURF_CHECK(!std::isnan(c.data()[0]), InputError, name, ": got nan, expected a boolean");
    return c.data()[0] != 0.0;
}

/// supports: (where, components) pairs; where is a function of position (an (n, 3) array in, n
/// booleans out), True (every boundary vertex) or vertex indices.
void supports_into(const py::handle& supports, Index num_vertices, ShellStudyOptions& options) {
    LIMSURF_CHECK(py::isinstance<py::sequence>(supports) && !py::isinstance<py::str>(supports), InputError,
                  "supports: expected a list of (where, components) pairs");
    const auto list = py::reinterpret_borrow<py::sequence>(supports);
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string name = "supports[" + std::to_string(k) + "]";
        const py::object item = list[k];
        LIMSURF_CHECK(py::isinstance<py::sequence>(item) && !py::isinstance<py::str>(item) && py::len(item) == 2,
                      InputError, name,
                      ": expected a pair (where, components), e.g. (lambda P: abs(P[:, 1]) > 24.999, 'xz')");
        const auto pair = py::reinterpret_borrow<py::sequence>(item);
        const std::array<bool, 3> components = components_from(pair[1], name + " components");
        const py::object where = pair[0];
        if (py::isinstance<py::function>(where)) {
            ShellSupport support;
            support.components = components;
            const auto f = py::reinterpret_borrow<py::function>(where);
            support.where = [f, name](const Eigen::Vector3d& x) {
                const py::gil_scoped_acquire acquire;
                return truth_from(f(to_numpy(Points(x.transpose()))), name + " where(P) result");
            };
            options.supports.push_back(std::move(support));
        } else if (py::isinstance<py::bool_>(where)) {
            const bool all = where.cast<bool>();
            options.supports.push_back(ShellSupport{[all](const Eigen::Vector3d&) { return all; }, components});
        } else {
            options.vertex_supports.push_back(
                ShellVertexSupport{indices_from(where, name + " vertices", num_vertices), components});
        }
    }
}

std::vector<Eigen::Vector3d> probes_from(const py::handle& probes) {
    std::vector<Eigen::Vector3d> out;
    if (py::isinstance<py::sequence>(probes) && py::len(probes) == 0) {
        return out;
    }
    const Points P = points_from(probes, "probes");
    for (Index i = 0; i < P.rows(); ++i) {
        out.emplace_back(P.row(i).transpose());
    }
    return out;
}

std::vector<ShellPointLoad> point_loads_from(const py::handle& loads) {
    LIMSURF_CHECK(py::isinstance<py::sequence>(loads) && !py::isinstance<py::str>(loads), InputError,
                  "point_loads: expected a list of ((x, y, z), (fx, fy, fz)) pairs");
    std::vector<ShellPointLoad> out;
    const auto list = py::reinterpret_borrow<py::sequence>(loads);
    for (std::size_t k = 0; k < list.size(); ++k) {
        const std::string name = "point_loads[" + std::to_string(k) + "]";
        const py::object item = list[k];
        LIMSURF_CHECK(py::isinstance<py::sequence>(item) && py::len(item) == 2, InputError, name,
                      ": expected a pair ((x, y, z), (fx, fy, fz))");
        const auto pair = py::reinterpret_borrow<py::sequence>(item);
        out.push_back(
            ShellPointLoad{vector3_from(pair[0], name + " position"), vector3_from(pair[1], name + " force")});
    }
    return out;
}

/// A Python traction t(P, N) -> (n, 3) forces per unit area.
SurfaceTraction traction_from(const py::function& t) {
    return [t](const Points& P, const Points& N) {
        const py::gil_scoped_acquire acquire;
        const Points forces = points_from(t(to_numpy(P), to_numpy(N)), "traction(P, N) result");
        LIMSURF_CHECK(forces.rows() == P.rows(), InputError, "traction(P, N) result: expected ", P.rows(),
                      " rows, got ", forces.rows());
        return forces;
    };
}

py::dict shell_level_dict(const ShellLevel& l, SchemeKind scheme) {
    py::list probes;
    for (const ShellProbe& p : l.probes) {
        probes.append(py::dict("vertex"_a = p.vertex, "position"_a = vec(p.position), "normal"_a = vec(p.normal),
                               "displacement"_a = vec(p.displacement),
                               "normal_displacement"_a = p.displacement.dot(p.normal)));
    }
    ShellVertexLimits limits;
    {
        const py::gil_scoped_release release;
        limits = shell_vertex_limits(l, scheme);
    }
    return py::dict("level"_a = l.level, "vertices"_a = l.topology.num_vertices(), "faces"_a = l.topology.num_faces(),
                    "unknowns"_a = l.solution.u.size(), "area"_a = l.area, "strain_energy"_a = 0.5 * l.solution.energy,
                    "residual"_a = l.solution.residual, "rigid_motions_removed"_a = l.solution.free_rigid_motions,
                    "probes"_a = probes, "u"_a = to_numpy(l.solution.displacements()),
                    "mesh"_a = mesh_object(l.topology, l.X), "limit_positions"_a = to_numpy(limits.positions),
                    "limit_displacements"_a = to_numpy(limits.displacements));
}

py::dict shell(const Mesh& mesh, const std::string& scheme, int levels, double E, double nu, double thickness,
               double gravity, double pressure, const py::handle& traction, const py::handle& point_loads,
               const py::handle& supports, const py::handle& probes, bool interpolate, const py::handle& surface,
               int degree, int tiles) {
    return naming_source(mesh, [&] {
        ShellStudyOptions options;
        options.material = ShellMaterial{E, nu, thickness};
        options.scheme = fem_scheme(scheme, "shell");
        options.levels = levels;
        options.quadrature = SamplerOptions{degree, tiles, 0};
        options.gravity = gravity;
        options.pressure = pressure;
        if (!traction.is_none()) {
            LIMSURF_CHECK(py::isinstance<py::function>(traction), InputError,
                          "traction: expected a function t(P, N) of positions and normals or None");
            options.traction = traction_from(py::reinterpret_borrow<py::function>(traction));
        }
        options.point_loads = point_loads_from(point_loads);
        supports_into(supports, mesh.mesh.num_vertices(), options);
        options.probes = probes_from(probes);
        options.interpolate = interpolate;
        if (!surface.is_none()) {
            LIMSURF_CHECK(py::isinstance<py::function>(surface), InputError,
                          "surface: expected a function F(P) whose zero set is the surface, or None");
            options.surface = surface_function(py::reinterpret_borrow<py::function>(surface), "surface");
        }
        ShellProblem problem;
        std::vector<ShellLevel> r;
        {
            const py::gil_scoped_release release;
            problem = shell_problem(mesh.mesh.topology(), mesh.mesh.positions(), options);
            r = solve_shell_levels(mesh.mesh.topology(), mesh.mesh.positions(), problem, levels);
        }
        py::list rows;
        for (const ShellLevel& l : r) {
            rows.append(shell_level_dict(l, problem.scheme));
        }
        const py::dict finest = rows[rows.size() - 1].cast<py::dict>();
        return py::dict("scheme"_a = scheme, "E"_a = E, "nu"_a = nu, "thickness"_a = thickness,
                        "interpolate"_a = problem.interpolate,
                        "surface"_a = surface.is_none() ? py::object(py::none()) : py::object(py::str("function")),
                        "solver"_a = r.back().solution.solver, "levels"_a = rows, "u"_a = finest["u"],
                        "mesh"_a = finest["mesh"]);
    });
}

ShellTerms shell_terms(const std::string& name) {
    if (name == "membrane-and-bending") {
        return ShellTerms::MembraneAndBending;
    }
    if (name == "membrane") {
        return ShellTerms::Membrane;
    }
    LIMSURF_CHECK(name == "bending", InputError, "terms: unknown '", name,
                  "' (expected membrane-and-bending, membrane or bending)");
    return ShellTerms::Bending;
}

}  // namespace

void bind_fem(py::module_& m) {
    m.def(
        "laplace_beltrami",
        [](const Mesh& mesh, const std::string& scheme, int degree, int tiles, std::optional<std::string> boundary,
           std::optional<std::string> creasing, std::optional<std::string> triangles) {
            const GalerkinMatrices g = with_quadrature(
                mesh, scheme, RuleNames{boundary, creasing, triangles}, degree, tiles,
                [&](const LimitSampler& s) { return assemble_laplace_beltrami(s, mesh.mesh.positions()); });
            return py::dict("mass"_a = to_scipy(g.mass), "stiffness"_a = to_scipy(g.stiffness));
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "degree"_a = 8, "tiles"_a = 6, "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The Galerkin matrices of the limit basis φ_i (one per control vertex), by quadrature on the
limit surface (degree per tile, tile levels towards extraordinary vertices), as scipy CSR (#V × #V):
mass M_ij = ∫ φ_i φ_j dA (symmetric positive definite) and stiffness K_ij = ∫ ∇φ_i · ∇φ_j dA (surface
gradients; symmetric, K @ 1 = 0). The matrices of `limsurf poisson --method iga` (same degree, tiles).
Rules: the keyword arguments, else the mesh's hints, else the defaults.
Raises NumericalError at a degenerate quadrature point (parallel tangents), naming its ptex face.)");
    m.def(
        "galerkin_load",
        [](const Mesh& mesh, const std::string& scheme, const py::function& f, int degree, int tiles,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const SurfaceFunction function = surface_function(f, "f");
            const Eigen::VectorXd b = with_quadrature(
                mesh, scheme, RuleNames{boundary, creasing, triangles}, degree, tiles,
                [&](const LimitSampler& s) { return galerkin_load(s, mesh.mesh.positions(), function); });
            return to_numpy(b);
        },
        "mesh"_a, "scheme"_a, "f"_a, py::kw_only(), "degree"_a = 8, "tiles"_a = 6, "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The load vector b_i = ∫ f φ_i dA (#V) of a function f(P) of an (n, 3) position array returning n
values, evaluated at the quadrature points of the limit surface (laplace_beltrami's quadrature).
Raises InputError when f returns the wrong number of values or a non-finite one; an exception raised
by f propagates as itself.)");
    m.def(
        "plate_bending_matrix",
        [](const Mesh& mesh, const std::string& scheme, double E, double nu, double thickness, int degree, int tiles,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const PlateMaterial material{E, nu, thickness};
            return to_scipy(with_quadrature(
                mesh, scheme, RuleNames{boundary, creasing, triangles}, degree, tiles,
                [&](const LimitSampler& s) { return assemble_plate_bending(s, mesh.mesh.positions(), material); }));
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "E"_a = 2e11, "nu"_a = 0.3, "thickness"_a = 0.1, "degree"_a = 6,
        "tiles"_a = 6, "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The Kirchhoff–Love bending stiffness K_ij = ∫ D [(1 − ν) ∇²φ_i : ∇²φ_j + ν Δφ_i Δφ_j] dA of a
planar control mesh (z = 0) as scipy CSR (#V × #V), D = E t³ / (12 (1 − ν²)) (consistent units, e.g.
Pa and m): symmetric positive semi-definite, zero on w = a + b x + c y. No supports applied (plate()
solves with them). Raises InputError for E ≤ 0, t ≤ 0, ν outside (−1, 0.5) or a mesh off the plane
z = 0; NumericalError at a degenerate quadrature point.)");
    m.def(
        "shell_stiffness",
        [](const Mesh& mesh, const std::string& scheme, double E, double nu, double thickness, const std::string& terms,
           int degree, int tiles, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const ShellMaterial material{E, nu, thickness};
            const ShellTerms which = shell_terms(terms);
            return to_scipy(with_quadrature(
                mesh, scheme, RuleNames{boundary, creasing, triangles}, degree, tiles, [&](const LimitSampler& s) {
                    return assemble_shell_stiffness(s, mesh.mesh.positions(), material, which);
                }));
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "E"_a = 1.0, "nu"_a = 0.3, "thickness"_a = 0.1,
        "terms"_a = "membrane-and-bending", "degree"_a = 6, "tiles"_a = 4, "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The linear Kirchhoff–Love shell stiffness on the limit surface as scipy CSR (3 #V × 3 #V; the
unknown of component c (x, y, z) of control vertex v in row 3 v + c): membrane E t / (1 − ν²) and
bending E t³ / (12 (1 − ν²)) energies (terms 'membrane-and-bending', 'membrane' or 'bending').
Symmetric positive semi-definite with the six rigid motions (rigid_body_modes) in its kernel.
Raises InputError for a material out of range; NumericalError at a degenerate quadrature point.)");
    m.def(
        "rigid_body_modes",
        [](const py::handle& V) {
            const Points X = py::isinstance<Mesh>(V) ? V.cast<const Mesh&>().mesh.positions() : points_from(V, "V");
            return to_numpy(rigid_body_modes(X));
        },
        "V"_a,
        R"(The six rigid motions of the control points V ((#V, 3) array or a Mesh) as a (3 #V, 6) array with
rows as shell_stiffness's: translations along x, y, z, then rotations about axes through the centroid
scaled by the points' extent. The limit surface moves rigidly with them: shell_stiffness @ modes ≈ 0.)");
    m.def(
        "rectangle_plate_deflection",
        [](double a, double b, const py::handle& x, const py::handle& y, double D, double p,
           std::optional<std::pair<int, int>> waves, const std::string& series, double tolerance) -> py::object {
            LIMSURF_CHECK(series == "levy" || series == "navier", InputError,
                          "series: expected 'levy' or 'navier', got '", series, "'");
            require_real_numbers(x, "x");
            require_real_numbers(y, "y");
            using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
            const Array ax = Array::ensure(x), ay = Array::ensure(y);
            LIMSURF_CHECK(ax && ay, InputError, "x, y: expected numbers or arrays of numbers");
            const std::vector<py::ssize_t> shape(ax.shape(), ax.shape() + ax.ndim());
            LIMSURF_CHECK(shape == std::vector<py::ssize_t>(ay.shape(), ay.shape() + ay.ndim()), InputError,
                          "x, y: expected the same shape, got ", std::string(py::str(ax.attr("shape"))), " and ",
                          std::string(py::str(ay.attr("shape"))));
            const auto n = static_cast<Index>(ax.size());
            const Eigen::VectorXd vx = vector_from(ax.attr("reshape")(n), "x", n);
            const Eigen::VectorXd vy = vector_from(ay.attr("reshape")(n), "y", n);
            Array out(shape);
            double* w = out.mutable_data();
            for (Index i = 0; i < n; ++i) {
                w[i] = waves              ? navier_sine(a, b, D, p, waves->first, waves->second, vx(i), vy(i))
                       : series == "levy" ? levy_uniform(a, b, D, p, vx(i), vy(i), tolerance)
                                          : navier_uniform(a, b, D, p, vx(i), vy(i), tolerance);
            }
            return ax.ndim() == 0 ? py::object(py::float_(w[0])) : py::object(out);
        },
        "a"_a, "b"_a, "x"_a, "y"_a, py::kw_only(), "D"_a = 1.0, "p"_a = 1.0, "waves"_a = py::none(),
        "series"_a = "levy", "tolerance"_a = 1e-14,
        R"(The exact deflection of the simply supported rectangle [0, a] × [0, b] (bending rigidity D) at the
points (x, y) (numbers or arrays of one shape; the result has that shape): under the uniform load p by
Lévy's single series (series='levy', summed along the shorter side: ~300 terms a point at any aspect
ratio) or Navier's double series (series='navier', 10³–10⁵ terms a point), each to `tolerance`
(docs/fem.md); with waves=(m, n), under p sin(mπx/a) sin(nπy/b) in closed form. The references
`plate()` compares with (its bounding box shifted to the origin): 'navier' → 'centre_deflection' is
this at (a/2, b/2). Raises InputError for sides, D or tolerance out of range, non-finite points or
shapes that differ.)");
    m.def(
        "plate",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& load, const std::string& support, double E,
           double nu, double thickness, int levels, std::optional<double> pressure, int degree, int tiles,
           const std::string& tuned, std::optional<int> decide_level) {
            return plate(mesh, scheme, load, support, E, nu, thickness, levels, pressure, degree, tiles, tuned,
                         decide_level);
        },
        "mesh"_a, "scheme"_a, "load"_a, py::kw_only(), "support"_a = "simply", "E"_a = 2e11, "nu"_a = 0.3,
        "thickness"_a = 0.1, "levels"_a = 0, "pressure"_a = py::none(), "degree"_a = 6, "tiles"_a = 6,
        "tuned"_a = "none", "decide_level"_a = py::none(),
        R"(Kirchhoff–Love bending of the plate bounded by the limit surface of a planar (z = 0) control mesh,
on the mesh and on it refined 1..levels times (0..6): `limsurf plate --json`'s numbers under the same
keys (units: those of E, t and the load, e.g. Pa, m, N/m² give a deflection in m).

load: a number p (uniform); 'uniform', 'sinusoidal' (p sin(2πx/a) sin(2πy/b) over the bounding box
[x0, x0 + a] × [y0, y0 + b]) or 'single-wave' (p sin(πx/a) sin(πy/b)) with p = pressure (default
1e4); a function of position (an (n, 3) array in, n values out; evaluated at the quadrature points);
or #V values, the load's control values (p_h = Σ p_i φ_i, carried to refined levels by S0; the CLI's
--load-file). support: 'simply' (w = 0 on the boundary) or 'clamped' (also the next row of control
values). scheme: 'catmull-clark' (the CLI's) or 'loop', with the default rules. tuned: 'none', 'cup',
'saddle' or 'auto' (Catmull–Clark only): IGA-tuned weights at the interior extraordinary vertices of
valence >= 5, as `limsurf plate --tuned` (levels then carry 'tuned_vertices' and, for 'auto',
'first_pass'; 'warnings' lists what the CLI prints on stderr). decide_level (with 'auto'): decide cup or
saddle once, from the cup pass on that level (0..6), and keep the choice on every level, as the paper's
§4 does (`--decide-level`; 'first_pass' then only on that level).

Returns 'load' ('uniform', 'sinusoidal', 'single-wave', 'function' or 'values'), 'pressure' (None
for a function or values), 'scheme', 'support', 'E', 'nu', 'thickness', 'bending_rigidity', 'rectangle',
'levels' (per level: 'level', 'vertices', 'faces', 'centre_deflection', 'quarter_deflection' (None off
the plate), 'max_deflection', 'residual', for a simply supported rectangle under a uniform or sine
load 'navier' with the exact deflections and relative errors, and the arrays 'w' (#V control values
of the deflection), 'p' (the load's control values, values loads only) and 'mesh' (that level's
control mesh)), 'navier' (a note when the plate is not its bounding rectangle), and 'w', 'mesh' of
the finest level. Raises InputError for a load of the wrong size (naming 'load'), a closed or
non-planar mesh, a material out of range; an exception raised by the load function propagates.)");
    m.def(
        "shell",
        [](const Mesh& mesh, const std::string& scheme, int levels, double E, double nu, double thickness,
           double gravity, double pressure, const py::handle& traction, const py::handle& point_loads,
           const py::handle& supports, const py::handle& probes, bool interpolate, const py::handle& surface,
           int degree, int tiles) {
            return shell(mesh, scheme, levels, E, nu, thickness, gravity, pressure, traction, point_loads, supports,
                         probes, interpolate, surface, degree, tiles);
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "levels"_a = 0, "E"_a = 1.0, "nu"_a = 0.3, "thickness"_a = 0.1,
        "gravity"_a = 0.0, "pressure"_a = 0.0, "traction"_a = py::none(), "point_loads"_a = py::list(),
        "supports"_a = py::list(), "probes"_a = py::list(), "interpolate"_a = false, "surface"_a = py::none(),
        "degree"_a = 6, "tiles"_a = 4,
        R"(Linear Kirchhoff–Love thin shell (membrane and bending) on the limit surface of a Catmull–Clark or
Loop control mesh, on the mesh and on it refined 1..levels times: `limsurf shell --json`'s numbers
under the same keys (consistent units).

Loads: gravity (force per unit area along −z), pressure (along the limit normal, outwards when > 0
on an outward-oriented mesh), traction (a function t(P, N) of (n, 3) positions and unit normals
returning (n, 3) forces per unit area), point_loads [((x, y, z), (fx, fy, fz)), ...] at the limit
points of control vertices. supports [(where, 'xz'), ...]: the listed components are zero on the
boundary control vertices that where selects: a function of position (an (n, 3) array in, n
booleans out, called per vertex on every level), True (all) or vertex indices (levels = 0 only).
probes [(x, y, z), ...]: limit points of control vertices where the displacement is reported.
interpolate: the mesh's vertices are points of the surface (the control points are fitted).
surface: a function F(P) (an (n, 3) array in, n values out) whose zero set is the exact surface: at
every level the points are projected onto it and fitted again (implies interpolate).

Returns 'scheme', 'E', 'nu', 'thickness', 'interpolate', 'surface' (None or 'function'), 'solver',
'levels' (per level: 'level', 'vertices', 'faces', 'unknowns', 'area', 'strain_energy', 'residual',
'rigid_motions_removed', 'probes' (each 'vertex', 'position', 'normal', 'displacement',
'normal_displacement'), and the arrays 'u' (#V × 3 control displacements), 'mesh' (the level's
control mesh), 'limit_positions' and 'limit_displacements' (#V × 3, at the vertices' limit points)),
and 'u', 'mesh' of the finest level. Raises InputError without a load, for a probe or point load
that is not at a vertex limit point, a support that selects nothing, a load with a resultant along a
rigid motion the supports leave free; NumericalError for a mechanism; an exception raised by a
Python function propagates as itself.)");
}

}  // namespace limsurf::python
