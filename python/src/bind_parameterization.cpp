// limsurf.parameterize: the parameterisation of `limsurf parameterize` (apps/parameterization.h),
// with the same numbers as its --json.
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/parameterization.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

py::dict parameterize_mesh(const Mesh& mesh, const std::string& scheme, const std::string& method, int level,
                           const std::string& boundary, std::optional<int> reference_level,
                           std::optional<std::int64_t> max_memory, int degree, int tiles, int threads,
                           const RuleNames& rules) {
    return naming_source(mesh, [&] {
        const SchemeKind kind = scheme_from(scheme);
        LIMSURF_CHECK(kind == SchemeKind::Loop || kind == SchemeKind::CatmullClark, InputError,
                      "parameterize: scheme must be 'loop' or 'catmull-clark', got '", scheme, "'");
        ParameterizationOptions o;
        o.method = parse_laplacian_method(method);
        o.level = level;
        o.boundary = parse_parameterization_boundary(boundary);
        o.scheme_options = rules_for(mesh.mesh, rules);
        o.distortion = DistortionOptions{degree, tiles, threads};
        o.num_threads = threads;
        o.reference_level = reference_level;
        o.max_memory = max_memory;
        ParameterizationResult r;
        {
            const py::gil_scoped_release release;
            r = parameterize(mesh.mesh, kind, o);
        }
        const QuasiConformalDistortion& d = r.distortion;
        const bool sec = has_level(o.method);
        const bool free = r.boundary == ParameterizationBoundary::Free;
        py::dict out("scheme"_a = scheme, "method"_a = method, "level"_a = sec ? level : 0,
                     "boundary"_a = to_string(r.boundary), "vertices"_a = r.uv.rows(),
                     "boundary_vertices"_a = r.boundary_vertices, "boundary_loops"_a = r.boundary_loops,
                     "solver"_a = r.solver,
                     "eigenvalue"_a = free ? py::object(py::float_(*r.eigenvalue)) : py::object(py::none()),
                     "iterations"_a = r.iterations, "residual"_a = r.residual,
                     "boundary_length"_a = free ? py::object(py::none()) : py::object(py::float_(r.boundary_length)),
                     "u_min"_a = r.uv.col(0).minCoeff(), "u_max"_a = r.uv.col(0).maxCoeff(),
                     "v_min"_a = r.uv.col(1).minCoeff(), "v_max"_a = r.uv.col(1).maxCoeff(),
                     "distortion"_a = py::dict("mean"_a = d.mean, "max"_a = d.max, "flipped"_a = d.flipped,
                                               "flipped_area"_a = d.flipped_area, "degenerate"_a = d.degenerate,
                                               "samples"_a = d.samples, "area"_a = d.area,
                                               "quadrature"_a = py::dict("degree"_a = degree, "tiles"_a = tiles)),
                     "times"_a = py::dict("assembly"_a = r.times.assembly, "solve"_a = r.times.solve,
                                          "distortion"_a = r.times.distortion, "reference"_a = r.times.reference),
                     "uv"_a = to_numpy(r.uv));
        if (r.reference) {
            out["reference"] = reference_dict(*r.reference);
        }
        return out;
    });
}

}  // namespace

void bind_parameterization(py::module_& m) {
    m.def(
        "parameterize",
        [](const Mesh& mesh, const std::string& scheme, const std::string& method, std::optional<int> given_level,
           const std::string& boundary, std::optional<int> reference_level, std::optional<std::int64_t> max_memory,
           int degree, int tiles, int threads, std::optional<std::string> boundary_rule,
           std::optional<std::string> creasing, std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            return parameterize_mesh(mesh, scheme, method, level, boundary, reference_level, max_memory, degree, tiles,
                                     threads, RuleNames{boundary_rule, creasing, triangles});
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "boundary"_a = "free",
        "reference_level"_a = py::none(), "max_memory"_a = py::none(), "degree"_a = 6, "tiles"_a = 3, "threads"_a = 0,
        "boundary_rule"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Maps the limit surface of an open mesh to the plane, (u, v) per control vertex (SEC §4.1), as
`limsurf parameterize` does, with the same numbers as its --json.

boundary='free': spectral conformal parameterisation (Mullen et al. 2008, SEC Eq. 17): the generalised
eigenvector of the smallest non-zero λ of L_C U = λ B U, L_C = diag(L, L) − A (conformal energy, L of the
inner products of `method`: 'dec', 'decsnap', 'sec', 'secsnap' at `level`; 'iga': the limit basis'
Galerkin stiffness and the area form ∫ du ∧ dv of the limit surface), B = 1 on boundary vertices
(Mullen's choice), the constants deflated; centred (boundary mean 0), scaled so the parameter area is the
surface's area, rotated so the first boundary vertex lies on +u.
boundary='circle': a topological disk; the limit boundary on the unit circle by limit arc length, the
interior harmonic; reference_level=K compares with DEC on the K-times subdivided mesh (L2 in the level-K
mass and L∞, relative).

Returns a dict: uv (numpy #V × 2), eigenvalue (free) or boundary_length (circle), residual, distortion
{mean, max, flipped, flipped_area, degenerate, samples, area} — σ1/σ2 of the map on the limit surface
(1: conformal), area-weighted, by quadrature of `degree` with `tiles` levels towards extraordinary
vertices — times, and reference {level, l2_relative, linf_relative} when asked. Boundary rules of the
scheme: boundary_rule, creasing, triangles. Raises InputError for a closed or disconnected mesh, a
circle on a mesh that is not a disk, a reference with the free boundary.)");
}

}  // namespace limsurf::python
