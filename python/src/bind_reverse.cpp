// limsurf.reverse_catmull_clark: the coarse control mesh of a subdivided mesh (refine/reverse.h),
// with the numbers `limsurf reverse --json` prints.
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "common.h"
#include "limsurf/refine/reverse.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

py::tuple reverse(const Mesh& mesh, int levels, double tolerance, const RuleNames& rules) {
    const SchemeOptions options = rules_for(mesh.mesh, rules);
    return naming_source(mesh, [&] {
        std::optional<ReverseResult> result;
        {
            const py::gil_scoped_release release;
            result.emplace(reverse_catmull_clark(mesh.mesh, levels, options, tolerance));
        }
        py::list steps;
        for (const ReverseStep& step : result->steps) {
            steps.append(py::dict("fine_vertices"_a = step.fine_vertices, "fine_faces"_a = step.fine_faces,
                                  "coarse_vertices"_a = step.coarse_vertices, "coarse_faces"_a = step.coarse_faces,
                                  "residual_max"_a = step.residual_max, "residual_rms"_a = step.residual_rms,
                                  "unique"_a = step.unique, "fine_vertex"_a = step.fine_vertex));
        }
        py::dict info("method"_a = "least-squares", "levels_reversed"_a = result->levels_reversed,
                      "per_level"_a = steps);
        return py::make_tuple(py::cast(Mesh{result->coarse, SourceMap{}, ValidationReport{}}), info);
    });
}

}  // namespace

void bind_reverse(py::module_& m) {
    m.def(
        "reverse_catmull_clark",
        [](const Mesh& mesh, int levels, double tolerance, std::optional<std::string> boundary,
           std::optional<std::string> creasing, std::optional<std::string> triangles) {
            return reverse(mesh, levels, tolerance, RuleNames{boundary, creasing, triangles});
        },
        "mesh"_a, "levels"_a = -1, py::kw_only(), "tolerance"_a = 1e-9, "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Reverse Catmull–Clark (iga-with-catmull-clark §3): the coarse control mesh that refines to `mesh`,
`levels` times (>= 1) or, with -1, as many as possible (the first level always; later ones while their
residual is at most `tolerance` × the bounding-box diagonal). Positions by least squares on S0.
Rules: the keyword arguments, else the mesh's hints, else limsurf's defaults (as `subdivide`).

Returns (coarse Mesh, info): info["levels_reversed"], info["method"] ("least-squares") and
info["per_level"], one dict per level (finest first) with fine/coarse vertex and face counts,
residual_max (max over fine vertices of ‖S0 P − P_fine‖), residual_rms, unique (False when several
coarse meshes refine to the same one, e.g. the cube) and fine_vertex (the fine vertex of each coarse
vertex) — the numbers of `limsurf reverse --json`.
Raises InputError naming the file and line of the element when the mesh is not a subdivided
topology (a non-quad face, an edge point of the wrong valence, ...).)");
}

}  // namespace limsurf::python
