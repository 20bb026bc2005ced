// limsurf.subdivide: uniform refinement, with the sparse subdivision operators on request.
#include <utility>

#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/core/error.h"
#include "limsurf/refine/hierarchy.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

py::object subdivide(const Mesh& mesh, const std::string& scheme, int levels, bool operators, bool forms,
                     const RuleNames& rules, int threads, bool topology) {
    RefineOptions options;
    options.num_threads = threads;
    options.scheme = scheme_from(scheme);
    options.levels = levels;
    options.scheme_options = rules_for(mesh.mesh, rules);
    options.forms = forms;
    return naming_source(mesh, [&]() -> py::object {
        if (!topology && !operators && !forms) {  // (V, F) of the finest level: its face list only
            FinestFaces refined;
            {
                const py::gil_scoped_release release;
                refined = refine_finest_faces(mesh.mesh.topology(), mesh.mesh.positions(), options);
            }
            return py::make_tuple(to_numpy(refined.mesh.positions),
                                  faces_array(refined.mesh.face_offsets, refined.mesh.face_vertices));
        }
        if (!operators && !forms) {  // only the finest level is wanted: keep no other (refine_finest)
            FinestLevel refined;
            {
                const py::gil_scoped_release release;
                refined = refine_finest(mesh.mesh.topology(), mesh.mesh.positions(), options);
            }
            return py::cast(
                Mesh{ControlMesh(std::move(refined.topology), std::move(refined.positions), mesh.mesh.hints()),
                     SourceMap{}, ValidationReport{}});
        }
        // The operators: every step's S0 (S1, S2) kept; with topology=False no level's Topology past the
        // base (KeptTopologies::FinestFaces: the finest level's face list only).
        if (!topology) {
            options.kept_topologies = KeptTopologies::FinestFaces;
        }
        std::optional<Hierarchy> hierarchy;
        {
            const py::gil_scoped_release release;
            hierarchy.emplace(mesh.mesh.topology(), options, mesh.mesh.positions());  // positions carried
            (void)hierarchy->accumulated(levels);  // formed (and cached) without the GIL, on the threads
            if (forms) {
                (void)hierarchy->accumulated_form(1, levels);
                (void)hierarchy->accumulated_form(2, levels);
            }
        }
        py::object finest;
        if (topology) {
            finest =
                py::cast(Mesh{ControlMesh(hierarchy->topology(levels), hierarchy->positions(levels), mesh.mesh.hints()),
                              SourceMap{}, ValidationReport{}});
        } else {
            const PolygonSoup& faces = hierarchy->finest_faces();
            finest = py::make_tuple(to_numpy(hierarchy->positions(levels)),
                                    faces_array(faces.face_offsets, faces.face_vertices));
        }
        py::dict ops;
        ops["S0"] = to_scipy(hierarchy->accumulated(levels));
        if (forms) {
            ops["S1"] = to_scipy(hierarchy->accumulated_form(1, levels));
            ops["S2"] = to_scipy(hierarchy->accumulated_form(2, levels));
        }
        py::list steps;
        for (int level = 1; level <= levels; ++level) {
            const Level& step = hierarchy->step(level);
            py::dict one("S0"_a = to_scipy(step.S0));
            if (forms) {
                one["S1"] = to_scipy(step.S1);
                one["S2"] = to_scipy(step.S2);
            }
            steps.append(one);
        }
        ops["steps"] = steps;
        return py::make_tuple(finest, ops);
    });
}

}  // namespace

void bind_refine(py::module_& m) {
    m.def(
        "subdivide",
        [](const Mesh& mesh, const std::string& scheme, int levels, bool operators, bool forms,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles, int threads, bool topology) {
            return subdivide(mesh, scheme, levels, operators, forms, RuleNames{boundary, creasing, triangles}, threads,
                             topology);
        },
        "mesh"_a, "scheme"_a, "levels"_a = 1, py::kw_only(), "operators"_a = false, "forms"_a = false,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(), "threads"_a = 0,
        "topology"_a = true,
        R"(Refines the mesh `levels` times (0..16) by `scheme` ("catmull-clark", "loop", "doo-sabin", "c2g0",
"bilinear", "linear"). Rules: the keyword arguments, else the mesh's hints, else limsurf's defaults
(boundary "edge-and-corner", creasing "uniform", triangles "catmull-clark"), as the CLI.

Returns the finest Mesh; with operators=True (or forms=True) a pair (mesh, ops) where ops["S0"] is
the accumulated vertex operator A (#V_L × #V_0, scipy CSR: mesh.V == A @ V0), ops["steps"] the
per-step matrices, and with forms=True also ops["S1"] (#E_L × #E_0) and ops["S2"] (#F_L × #F_0),
the 1- and 2-form subdivision of SEC that commutes with d (Loop and Catmull–Clark).
`threads` (0: all cores): each step builds the child topology on a second thread while the first
builds the rows; the result does not depend on it.
With topology=False, returns the finest level as arrays (V, F) instead: its face list only, without
the edge and one-ring tables of a Mesh (as `limsurf subdivide` writes it; 2 M quads: a peak of 210
against 454 MiB); the same V and F as the Mesh's, sharpness tags not kept. With operators too, the
pair ((V, F), ops): the same operators, and no level's tables kept past the control mesh.
Raises InputError beyond the memory budget (checked before any work), UnsupportedError for a
scheme that cannot refine the mesh (Loop on a quad).)");
}

}  // namespace limsurf::python
