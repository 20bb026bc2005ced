// limsurf.measure and limsurf.volume: area, exact enclosed volume, centroids, inertia.
#include <cstdint>
#include <limits>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/volume/enclosed_volume.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

py::tuple vec(const Eigen::Vector3d& x) {
    return py::make_tuple(x.x(), x.y(), x.z());
}

py::object matrix3(const Eigen::Matrix3d& m) {
    return to_numpy(Eigen::MatrixXd(m));
}

/// The numbers of `limsurf measure --json` under the same keys (vectors as tuples, the inertia
/// tensor as a 3 × 3 array); volume, centroid and inertia are None for an open surface.
py::dict measure(const Mesh& mesh, const std::string& scheme, int degree, int tiles, const RuleNames& rules) {
    return naming_source(mesh, [&] {
        const LimitBasis basis(mesh.mesh.topology(), scheme_from(scheme), rules_for(mesh.mesh, rules));
        MeasureReport r;
        {
            const py::gil_scoped_release release;
            r = measure_with_error(basis, mesh.mesh.positions(), SamplerOptions{degree, tiles, 0});
        }
        const auto closed_only = [&](py::object value) { return r.closed ? value : py::object(py::none()); };
        py::dict errors("area"_a = r.error.area, "surface_centroid"_a = r.error.surface_centroid,
                        "volume"_a = closed_only(py::float_(r.error.volume)),
                        "centroid"_a = closed_only(py::float_(r.error.centroid)),
                        "inertia"_a = closed_only(py::float_(r.error.inertia)));
        return py::dict(
            "closed"_a = r.closed, "area"_a = r.value.area, "surface_centroid"_a = vec(r.value.surface_centroid),
            "error_estimate"_a = errors, "degree"_a = degree, "tiles"_a = tiles,
            "reference"_a = py::dict("degree"_a = r.finer.degree, "tiles"_a = r.finer.subdivide_near_extraordinary),
            "volume"_a = closed_only(py::float_(r.value.volume)), "centroid"_a = closed_only(vec(r.value.centroid)),
            "inertia"_a = closed_only(matrix3(r.value.inertia)));
    });
}

py::object volume(const Mesh& mesh, const std::string& scheme, bool gradient, const py::handle& X,
                  const RuleNames& rules) {
    return naming_source(mesh, [&]() -> py::object {
        const Points P = X.is_none() ? mesh.mesh.positions() : points_from(X, "X");
        double value = 0.0;
        Points g;
        {
            const py::gil_scoped_release release;
            const EnclosedVolume forms(mesh.mesh.topology(), scheme_from(scheme), rules_for(mesh.mesh, rules));
            value = gradient ? forms.volume_and_gradient(P, g) : forms.volume(P);
        }
        if (!gradient) {
            return py::float_(value);
        }
        return py::make_tuple(value, to_numpy(g));
    });
}

py::list polyhedral_volumes(const Mesh& mesh, const std::string& scheme, int levels, std::int64_t max_faces,
                            const RuleNames& rules) {
    return naming_source(mesh, [&] {
        LIMSURF_CHECK(max_faces >= 1 && max_faces <= std::numeric_limits<Index>::max(), InputError,
                      "max_faces must be 1..", std::numeric_limits<Index>::max(), " (got ", max_faces, ")");
        std::vector<PolyhedralVolume> levels_out;
        {
            const py::gil_scoped_release release;
            levels_out =
                limsurf::polyhedral_volumes(mesh.mesh.topology(), mesh.mesh.positions(), scheme_from(scheme), levels,
                                            static_cast<Index>(max_faces), rules_for(mesh.mesh, rules));
        }
        py::list out;
        for (const PolyhedralVolume& l : levels_out) {
            out.append(py::dict("level"_a = l.level, "faces"_a = l.faces, "volume"_a = l.volume));
        }
        return out;
    });
}

}  // namespace

void bind_measure(py::module_& m) {
    m.def(
        "measure",
        [](const Mesh& mesh, const std::string& scheme, int degree, int tiles, std::optional<std::string> boundary,
           std::optional<std::string> creasing, std::optional<std::string> triangles) {
            return measure(mesh, scheme, degree, tiles, RuleNames{boundary, creasing, triangles});
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "degree"_a = 12, "tiles"_a = 10, "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Area, enclosed volume, centroids and the solid's inertia tensor (about its centroid, unit
density) of the limit surface by quadrature, each with an error estimate (the difference to degree + 4
and one more tile level): the numbers of `limsurf measure --json` under the same keys. volume,
centroid and inertia are None when the limit surface is not closed.)");
    m.def(
        "volume",
        [](const Mesh& mesh, const std::string& scheme, bool gradient, const py::handle& X,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            return volume(mesh, scheme, gradient, X, RuleNames{boundary, creasing, triangles});
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "gradient"_a = false, "X"_a = py::none(), "boundary"_a = py::none(),
        "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The exact volume enclosed by the limit surface (trilinear forms; Catmull–Clark, Loop, Doo–Sabin;
closed meshes without tags), `limsurf volume`'s number. With gradient=True a pair (volume,
dV/dX (#V × 3)), exact. X: other control points for the same mesh.)");
    m.def(
        "polyhedral_volumes",
        [](const Mesh& mesh, const std::string& scheme, int levels, std::int64_t max_faces,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            return polyhedral_volumes(mesh, scheme, levels, max_faces, RuleNames{boundary, creasing, triangles});
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "levels"_a = 3, "max_faces"_a = std::int64_t{1} << 22,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(The volumes enclosed by the control polyhedra of subdivision levels 0..levels, as dicts
{level, faces, volume}: they approach the limit surface's volume (`volume`), the comparison
`limsurf volume` prints. Stops before a level of more than max_faces faces or beyond the memory
budget, so the list can be shorter. Any scheme, open meshes included (their polyhedral volume is
that of the fan of each face to the mean point).)");
}

}  // namespace limsurf::python
