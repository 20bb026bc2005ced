// Vector-field design and 1-forms as vectors on the limit surface (apps/vector_field.h): the numbers of
// `limsurf vector-field --json` under the same keys, with the arrays.
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/vector_field.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

/// (element, value) or (element, value, weight). The element is returned owned: an item of a numpy
/// row is a new object that a handle would outlive.
std::tuple<py::object, double, double> spec(const py::handle& item, const char* name, double weight) {
    const py::sequence s = py::reinterpret_borrow<py::sequence>(item);
    LIMSURF_CHECK(py::isinstance<py::sequence>(item) && (s.size() == 2 || s.size() == 3), InputError, name,
                  ": each constraint is (element, value) or (element, value, weight)");
    const std::string where = std::string(name) + " (value, weight)";
    return {s[0], cast_as<double>(s[1], where, "a number"),
            s.size() == 3 ? cast_as<double>(s[2], where, "a number") : weight};
}

VectorFieldConstraints constraints_from(const py::iterable& sources, const py::iterable& sinks,
                                        const py::iterable& vortices, const py::iterable& strokes, double weight) {
    VectorFieldConstraints c;
    for (const py::handle item : sources) {
        const auto [v, s, w] = spec(item, "sources", weight);
        c.sources.push_back({cast_as<Index>(v, "sources", "a vertex index"), s, w});
    }
    for (const py::handle item : sinks) {
        const auto [v, s, w] = spec(item, "sinks", weight);
        c.sources.push_back({cast_as<Index>(v, "sinks", "a vertex index"), -s, w});
    }
    for (const py::handle item : vortices) {
        const auto [f, s, w] = spec(item, "vortices", weight);
        c.vortices.push_back({cast_as<Index>(f, "vortices", "a face index"), s, w});
    }
    for (const py::handle item : strokes) {
        const auto [path, s, w] = spec(item, "strokes", weight);
        c.strokes.push_back({cast_as<std::vector<Index>>(path, "strokes", "a path of vertex indices"), s, w});
    }
    return c;
}

py::dict vectors_dict(const OneFormVectors& v) {
    return py::dict("level"_a = v.level, "points"_a = to_numpy(v.points), "vectors"_a = to_numpy(v.vectors),
                    "normals"_a = to_numpy(v.normals), "level_points"_a = to_numpy(v.level_points),
                    "level_vectors"_a = to_numpy(v.level_vectors), "fit_residual"_a = v.fit_residual);
}

}  // namespace

void bind_vector_field(py::module_& m) {
    m.def(
        "one_form_vectors",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& w, int level,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            return naming_source(mesh, [&] {
                const Eigen::VectorXd form = vector_from(w, "w", mesh.mesh.num_edges());
                const SchemeKind kind = scheme_from(scheme);
                const SchemeOptions rules = rules_for(mesh.mesh, RuleNames{boundary, creasing, triangles});
                OneFormVectors v;
                {
                    const py::gil_scoped_release release;
                    v = one_form_vectors(mesh.mesh.topology(), mesh.mesh.positions(), kind, form, level, rules);
                }
                return vectors_dict(v);
            });
        },
        "mesh"_a, "scheme"_a, "w"_a, py::kw_only(), "level"_a = 2, "boundary"_a = py::none(), "creasing"_a = py::none(),
        "triangles"_a = py::none(),
        R"(The vectors of the 1-form w (#E edge integrals) on the limit surface: w subdivided `level` times with
the form subdivision matrices, and on each level-L face the least-squares tangent vector that reproduces its
edge integrals, at the limit point of the face's centre (exact for constant fields on planes).
Returns 'points', 'vectors', 'normals' (#F_L × 3), 'level_points', 'level_vectors' (#V_L × 3, limit positions
and the mean of the faces' vectors), 'fit_residual' and 'level'.)");
    m.def(
        "design_vector_field",
        [](const Mesh& mesh, const std::string& scheme, const py::iterable& sources, const py::iterable& sinks,
           const py::iterable& vortices, const py::iterable& strokes, double weight, const std::string& method,
           std::optional<int> given_level, const std::string& vertex_mass, int sample_level,
           std::optional<int> reference_level, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            return naming_source(mesh, [&] {
                const VectorFieldConstraints c = constraints_from(sources, sinks, vortices, strokes, weight);
                const SchemeKind kind = scheme_from(scheme);
                VectorFieldOptions o;
                o.inner_products.method = parse_inner_product_method(method);
                o.inner_products.level = level;
                o.vertex_mass = parse_vertex_mass_inverse(vertex_mass);
                o.scheme_options = rules_for(mesh.mesh, RuleNames{boundary, creasing, triangles});
                o.reference_level = reference_level;
                const Topology& t = mesh.mesh.topology();
                VectorFieldResult r;
                OneFormVectors v;
                {
                    const py::gil_scoped_release release;
                    r = design_vector_field(t, mesh.mesh.positions(), kind, c, o);
                    v = one_form_vectors(t, mesh.mesh.positions(), kind, r.w, sample_level, o.scheme_options);
                }
                py::list constraints;
                for (const ConstraintReport& k : r.constraints) {
                    constraints.append(py::dict("kind"_a = k.kind, "element"_a = k.element, "target"_a = k.target,
                                                "achieved"_a = k.achieved, "weight"_a = k.weight));
                }
                const Eigen::VectorXd magnitude = v.vectors.rowwise().norm();
                py::dict out("scheme"_a = scheme, "method"_a = method,
                             "level"_a = uses_subdivision(o.inner_products.method) ? level : 0,
                             "vertices"_a = t.num_vertices(), "edges"_a = t.num_edges(), "faces"_a = t.num_faces(),
                             "closed"_a = t.is_closed(), "genus"_a = t.genus(), "solver"_a = r.solver,
                             "vertex_mass"_a = vertex_mass, "solver_steps"_a = r.solver_steps, "energy"_a = r.energy,
                             "w_norm"_a = r.w.norm(), "max_residual"_a = r.max_residual,
                             "source_imbalance"_a = r.source_imbalance, "vorticity_imbalance"_a = r.vorticity_imbalance,
                             "constraints"_a = constraints, "warnings"_a = r.warnings,
                             "samples"_a = py::dict(
                                 "level"_a = v.level, "count"_a = v.points.rows(), "fit_residual"_a = v.fit_residual,
                                 "magnitude_min"_a = magnitude.minCoeff(), "magnitude_max"_a = magnitude.maxCoeff(),
                                 "magnitude_mean"_a = magnitude.mean()),
                             "w"_a = to_numpy(r.w), "vectors"_a = vectors_dict(v));
                if (r.reference) {
                    out["reference"] =
                        py::dict("level"_a = r.reference->level, "method"_a = "dec", "edges"_a = r.reference->edges,
                                 "l2_relative"_a = r.reference->l2_relative, "energy"_a = r.reference->energy);
                }
                return out;
            });
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "sources"_a = py::list(), "sinks"_a = py::list(),
        "vortices"_a = py::list(), "strokes"_a = py::list(), "weight"_a = 1000.0, "method"_a = "sec",
        "level"_a = py::none(), "vertex_mass"_a = "exact", "sample_level"_a = 2, "reference_level"_a = py::none(),
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Designs the smoothest tangent field (Fisher et al. 2007; SEC §4.3): `limsurf vector-field`.

Minimises the anti-holomorphic energy ½ wᵀ L1 w (SEC Eq. 4) plus soft penalties; vertex_mass 'exact' (default:
the inner products' own M0⁻¹ in the divergence term, by conjugate gradients when M0 is not diagonal) or 'lumped'
(diag(M0 1)⁻¹, one sparse solve):
sources [(vertex, strength[, weight])] (divergence −(d0ᵀ M1 w)_v = strength), sinks (the same with −strength),
vortices [(face, circulation[, weight])] ((d1 w)_f), strokes [([v0, v1, ...], speed[, weight])] (w_e = speed |e|
along the path's edges). weight: the default weight (dimensionless, × 1/area). method 'dec', 'decsnap', 'sec',
'secsnap' with `level`. reference_level K: also design with DEC on the K-times subdivided mesh and report the
relative L2 difference. Returns the keys of `--json`, with 'w' (#E) and 'vectors' (as one_form_vectors at
sample_level).)");
}

}  // namespace limsurf::python
