// limsurf.measure and limsurf.volume: area, exact enclosed volume, centroids, inertia.
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
}

}  // namespace limsurf::python
