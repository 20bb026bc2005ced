// Heat-method geodesics (SEC §4.2, apps/geodesics.h): limsurf.geodesic_distance (one field with the
// report of `limsurf geodesic --json`) and limsurf.HeatGeodesics (set up and factorised once, then
// one call per source set).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/geodesics.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

/// One vertex index or a sequence of them, as an index array: pybind11's vector cast of a 3-d array
/// raised numpy's "circular base" ValueError. Each must lie in [0, @p num_vertices): the message
/// names the argument, the element and the range (a negative index was once reported against
/// [0, 2147483647), the bound of the conversion, not of the mesh).
std::vector<Index> sources_from(const py::handle& sources, Index num_vertices, const std::string& name = "sources") {
    return indices_from(sources, name, num_vertices);
}

/// The keyword arguments method, level, degree and tiles (iga; None: the default).
struct MethodChoice {
    std::string method;
    int level = 3;
    std::optional<int> degree;
    std::optional<int> tiles;
};

/// The keyword arguments gradient, gradient_level and gradient_degree.
struct GradientChoice {
    std::string gradient = "auto";
    std::optional<int> level;
    int degree = 2;
};

HeatGeodesicsOptions heat_options(const Mesh& mesh, const MethodChoice& method, const GradientChoice& gradient,
                                  double time_factor, const RuleNames& rules) {
    HeatGeodesicsOptions options;
    options.method = parse_laplacian_method(method.method);
    options.level = method.level;
    require_iga_for_quadrature(options.method, method.method, method.degree, method.tiles);
    options.iga_quadrature.degree = method.degree.value_or(options.iga_quadrature.degree);
    options.iga_quadrature.subdivide_near_extraordinary =
        method.tiles.value_or(options.iga_quadrature.subdivide_near_extraordinary);
    options.gradient = parse_heat_gradient(gradient.gradient);
    // The library reads -1 as "not given": a -1 from Python would have been taken for None.
    LIMSURF_CHECK(!gradient.level || *gradient.level >= 0, InputError, "gradient_level must be >= 0 (or None), not ",
                  *gradient.level);
    options.gradient_level = gradient.level.value_or(-1);
    options.gradient_quadrature.degree = gradient.degree;
    options.time_factor = time_factor;
    options.scheme_options = rules_for(mesh.mesh, rules);
    return options;
}

py::dict report(const Mesh& mesh, const std::string& scheme, const HeatGeodesicsOptions& options,
                const std::vector<Index>& sources, const GeodesicResult& r) {
    const bool iga = options.method == LaplacianMethod::Iga;
    const py::object quadrature =
        iga ? py::object(py::dict("degree"_a = options.iga_quadrature.degree,
                                  "tiles"_a = options.iga_quadrature.subdivide_near_extraordinary))
            : py::object(py::none());
    py::dict out(
        "scheme"_a = scheme, "method"_a = to_string(options.method),
        "level"_a = has_level(options.method) ? options.level : 0, "quadrature"_a = quadrature,
        "gradient"_a = r.gradient,
        "gradient_level"_a = r.gradient_level ? py::object(py::int_(*r.gradient_level)) : py::object(py::none()),
        "vertices"_a = mesh.mesh.num_vertices(), "closed"_a = mesh.mesh.topology().is_closed(), "sources"_a = sources,
        "time_factor"_a = options.time_factor, "t"_a = r.time_step, "mean_edge_length"_a = r.mean_edge_length,
        "max_edge_length"_a = r.max_edge_length, "distance_min"_a = r.distance.minCoeff(),
        "distance_max"_a = r.distance.maxCoeff(), "limit_distance_min"_a = r.limit_distance.minCoeff(),
        "limit_distance_max"_a = r.limit_distance.maxCoeff(),
        "source_values"_a = std::vector<double>(r.source_values.begin(), r.source_values.end()),
        "seconds"_a = py::dict("setup"_a = r.setup_seconds, "factorisation"_a = r.factorisation_seconds,
                               "solve"_a = r.solve_seconds),
        "distance"_a = to_numpy(r.distance), "limit_distance"_a = to_numpy(r.limit_distance));
    if (r.reference) {
        out["reference"] = reference_dict(*r.reference);
    }
    return out;
}

}  // namespace

void bind_geodesics(py::module_& m) {
    m.def(
        "geodesic_distance",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& sources, const std::string& method,
           std::optional<int> given_level, std::optional<int> degree, std::optional<int> tiles,
           const std::string& gradient, std::optional<int> gradient_level, int gradient_degree, double time_factor,
           std::optional<int> reference_level, std::optional<std::int64_t> max_memory,
           std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            const int level = level_for(method, given_level);
            return naming_source(mesh, [&] {
                GeodesicOptions options;
                options.heat = heat_options(mesh, MethodChoice{method, level, degree, tiles},
                                            GradientChoice{gradient, gradient_level, gradient_degree}, time_factor,
                                            RuleNames{boundary, creasing, triangles});
                options.reference_level = reference_level;
                options.max_memory = max_memory;
                const std::vector<Index> list = sources_from(sources, mesh.mesh.num_vertices());
                const SchemeKind kind = scheme_from(scheme);
                GeodesicResult r;
                {
                    const py::gil_scoped_release release;
                    r = geodesic_distance(mesh.mesh, kind, list, options);
                }
                return report(mesh, scheme, options.heat, list, r);
            });
        },
        "mesh"_a, "scheme"_a, "sources"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(),
        "degree"_a = py::none(), "tiles"_a = py::none(), "gradient"_a = "auto", "gradient_level"_a = py::none(),
        "gradient_degree"_a = 2, "time_factor"_a = 1.0, "reference_level"_a = py::none(), "max_memory"_a = py::none(),
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Geodesic distance on the limit surface from `sources` (a control vertex or a list of them) by the
heat method (Crane et al. 2013) with the operators of `method` ('dec', 'decsnap', 'sec', 'secsnap';
SEC §4.2) or Galerkin with the limit basis ('iga', mass and stiffness integrated with `degree` per
tile and `tiles` levels towards extraordinary vertices; None: 8 and 6; other methods refuse them): the dict of `limsurf geodesic --json` plus
'distance' (#V: values at the control vertices for dec, control coefficients of the limit function
for sec and iga) and 'limit_distance' (#V: at the limit point of each control vertex). iga
normalises the heat gradient on the limit surface (quadrature of degree gradient_degree per face);
sec, secsnap there too (gradient='limit') or on the control mesh subdivided gradient_level times
(gradient='subdivided'); 'auto' takes subdivided when gradient_level is given or level < 3, else
limit (apps/geodesics.h says why). t = time_factor · (mean control edge length)²;
reference_level=K also runs the heat method with DEC on the K-times subdivided mesh (same t) and
reports 'reference'.
Raises limsurf.InputError for a source out of range, no source, or a disconnected mesh.)");

    py::class_<HeatGeodesics>(m, "HeatGeodesics",
                              R"(The heat method set up and factorised once for repeated queries:
HeatGeodesics(mesh, scheme, method='sec', level=None, degree=None, tiles=None, gradient='auto', gradient_level=None,
gradient_degree=2, time_factor=1.0).distance(sources)
costs two back-substitutions (three on open meshes) and one divergence per call.)")
        .def(py::init([](const Mesh& mesh, const std::string& scheme, const std::string& method,
                         std::optional<int> given_level, std::optional<int> degree, std::optional<int> tiles,
                         const std::string& gradient, std::optional<int> gradient_level, int gradient_degree,
                         double time_factor, std::optional<std::string> boundary, std::optional<std::string> creasing,
                         std::optional<std::string> triangles) {
                 const int level = level_for(method, given_level);
                 return naming_source(mesh, [&] {
                     const HeatGeodesicsOptions options =
                         heat_options(mesh, MethodChoice{method, level, degree, tiles},
                                      GradientChoice{gradient, gradient_level, gradient_degree}, time_factor,
                                      RuleNames{boundary, creasing, triangles});
                     const SchemeKind kind = scheme_from(scheme);
                     const py::gil_scoped_release release;
                     return HeatGeodesics(mesh.mesh, kind, options);
                 });
             }),
             "mesh"_a, "scheme"_a, py::kw_only(), "method"_a = "sec", "level"_a = py::none(), "degree"_a = py::none(),
             "tiles"_a = py::none(), "gradient"_a = "auto", "gradient_level"_a = py::none(), "gradient_degree"_a = 2,
             "time_factor"_a = 1.0, "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none())
        .def(
            "distance",
            [](const HeatGeodesics& self, const py::handle& sources) {
                const std::vector<Index> list = sources_from(sources, self.num_vertices());
                Eigen::VectorXd d;
                {
                    const py::gil_scoped_release release;
                    d = self.distance(list);
                }
                return to_numpy(d);
            },
            "sources"_a,
            "The distance (#V) from a control vertex or a list of them, as geodesic_distance()['distance'].")
        .def(
            "distances",
            [](const HeatGeodesics& self, const py::sequence& source_sets) {
                std::vector<std::vector<Index>> sets;
                sets.reserve(source_sets.size());
                // By index into owned objects: a py::sequence's range-for yields handles into
                // temporaries, and the items of a numpy array are new objects (a use after free).
                for (std::size_t k = 0; k < source_sets.size(); ++k) {
                    const py::object sources = source_sets[k];
                    sets.push_back(
                        sources_from(sources, self.num_vertices(), "source_sets[" + std::to_string(k) + "]"));
                }
                Eigen::MatrixXd d;
                {
                    const py::gil_scoped_release release;
                    d = self.distances(sets);
                }
                return to_numpy(d);
            },
            "source_sets"_a,
            "distance() for each entry of source_sets (a vertex or a list of vertices each) in one pass: "
            "an array #V × len(source_sets), column k for source_sets[k], several times cheaper per set.")
        .def(
            "source_values",
            [](const HeatGeodesics& self, const py::handle& phi, const py::handle& sources) {
                const std::vector<Index> list = sources_from(sources, self.num_vertices());
                const Eigen::VectorXd values = vector_from(phi, "phi", self.num_vertices());
                return to_numpy(self.source_values(values, list));
            },
            "phi"_a, "sources"_a,
            "The values of a distance at the sources as the method measures them (control or limit values).")
        .def_property_readonly("time_step", &HeatGeodesics::time_step, "t")
        .def_property_readonly("mean_edge_length", &HeatGeodesics::mean_edge_length,
                               "Mean edge length of the control mesh")
        .def_property_readonly("max_edge_length", &HeatGeodesics::max_edge_length, "Longest edge of the control mesh")
        .def_property_readonly("gradient", &HeatGeodesics::gradient,
                               "Where the gradient is normalised: 'control' (dec), 'limit' or 'subdivided' (sec)")
        .def_property_readonly("gradient_level", &HeatGeodesics::gradient_level,
                               "Level of the mesh the gradient is normalised on (0 for dec, None for the limit "
                               "gradient)")
        .def_property_readonly("setup_seconds", &HeatGeodesics::setup_seconds,
                               "Seconds spent on the inner products, operators and gradient mesh")
        .def_property_readonly("factorisation_seconds", &HeatGeodesics::factorisation_seconds,
                               "Seconds spent on the Cholesky factorisations");
}

}  // namespace limsurf::python
