// Pictures and viewers: the tessellation of the limit surface, rendered images as numpy arrays
// (the pixels `limsurf render` writes), PNG and glTF files.
#include <algorithm>
#include <cctype>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/io/gltf.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/render/render.h"
#include "limsurf/render/tessellation.h"

namespace limsurf::python {
namespace {

std::string lower_case(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

using namespace pybind11::literals;

py::array_t<Index> triangles_of(const Eigen::Matrix<Index, Eigen::Dynamic, 3>& triangles) {
    py::array_t<Index> out({static_cast<py::ssize_t>(triangles.rows()), py::ssize_t{3}});
    auto view = out.mutable_unchecked<2>();
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
        for (int k = 0; k < 3; ++k) {
            view(t, k) = triangles(t, k);
        }
    }
    return out;
}

LimitTessellation tessellation_of(const Mesh& mesh, const std::string& scheme, int resolution, bool curvature,
                                  const Points& X, int threads, const RuleNames& rules) {
    const LimitBasis basis(mesh.mesh.topology(), scheme_from(scheme), rules_for(mesh.mesh, rules));
    TessellationOptions options;
    LIMSURF_CHECK(resolution >= 0, InputError, "resolution: expected 0 (automatic) or 1..1024, got ", resolution);
    check_threads(threads);
    options.resolution = resolution > 0 ? resolution : automatic_resolution(basis);
    options.curvature = curvature;
    options.num_threads = threads;
    const py::gil_scoped_release release;
    return tessellate_limit_surface(basis, X, options);
}

py::dict tessellation_dict(const LimitTessellation& t) {
    py::array_t<Index> faces(static_cast<py::ssize_t>(t.points.size()));
    py::array_t<double> u(static_cast<py::ssize_t>(t.points.size()));
    py::array_t<double> v(static_cast<py::ssize_t>(t.points.size()));
    for (std::size_t p = 0; p < t.points.size(); ++p) {
        faces.mutable_data()[p] = t.points[p].face;
        u.mutable_data()[p] = t.points[p].u;
        v.mutable_data()[p] = t.points[p].v;
    }
    py::array_t<bool> estimated(static_cast<py::ssize_t>(t.estimated.size()));
    std::copy(t.estimated.data(), t.estimated.data() + t.estimated.size(), estimated.mutable_data());
    py::dict out("positions"_a = to_numpy(t.positions), "normals"_a = to_numpy(t.normals),
                 "triangles"_a = triangles_of(t.triangles), "faces"_a = faces, "u"_a = u, "v"_a = v,
                 "estimated"_a = estimated, "value_weights"_a = to_scipy(t.value_weights),
                 "resolution"_a = t.resolution);
    if (t.mean_curvature.size() > 0) {
        out["mean_curvature"] = to_numpy(t.mean_curvature);
        out["gaussian_curvature"] = to_numpy(t.gaussian_curvature);
    }
    return out;
}

/// The field to colour by: a curvature of the tessellation, or control values carried through the limit basis.
Eigen::VectorXd field_values(const py::handle& field, const LimitTessellation& t, Index num_vertices,
                             std::string& name) {
    if (field.is_none()) {
        return {};
    }
    if (py::isinstance<py::str>(field)) {
        name = field.cast<std::string>();
        LIMSURF_CHECK(name == "mean-curvature" || name == "gaussian-curvature", InputError,
                      "field: expected "
                      "'mean-curvature', 'gaussian-curvature' or #V values at the control vertices, got '",
                      name, "'");
        name = name == "mean-curvature" ? "mean_curvature" : "gaussian_curvature";
        return name == "mean_curvature" ? t.mean_curvature : t.gaussian_curvature;
    }
    name = "field";
    return evaluate_vertex_field(t, vector_from(field, "field", num_vertices));
}

std::array<int, 2> size_from(const py::handle& size) {
    const auto wh = cast_as<std::array<int, 2>>(size, "size", "(width, height), two integers");
    LIMSURF_CHECK(wh[0] >= 16 && wh[0] <= 8192 && wh[1] >= 16 && wh[1] <= 8192, InputError,
                  "size: expected (width, height), each in 16..8192, got (", wh[0], ", ", wh[1], ")");
    return wh;
}

View view_from(const py::handle& view) {
    if (py::isinstance<py::str>(view)) {
        return parse_view(view.cast<std::string>());
    }
    const auto ae = cast_as<std::array<double, 2>>(view, "view", "iso, front, top or (azimuth, elevation) in degrees");
    return parse_view(std::to_string(ae[0]) + "," + std::to_string(ae[1]));
}

py::dict render(const Mesh& mesh, const std::string& scheme, const py::handle& field, bool control_mesh, int isolines,
                const py::handle& view, const py::handle& size, int resolution,
                const std::optional<std::array<double, 2>>& range, const std::string& colormap, int supersampling,
                bool color_bar, const std::optional<std::filesystem::path>& output, int threads,
                const RuleNames& rules) {
    check_threads(threads);
    // As `limsurf render -o`: the extension says the format (a .bmp or .jpg got PNG bytes).
    const std::string extension = output ? lower_case(output->extension().string()) : std::string();
    LIMSURF_CHECK(!output || extension == ".png" || extension == ".glb", InputError, "output: ", output->string(),
                  ": unknown format '", extension, "' (expected .png or .glb)");
    RenderOptions options;
    options.num_threads = threads;
    options.view = view_from(view);
    const std::array<int, 2> wh = size_from(size);
    options.width = wh[0];
    options.height = wh[1];
    options.range = range;
    options.colormap = colormap_from_name(colormap);
    options.isolines = isolines;
    options.supersampling = supersampling;
    options.color_bar = color_bar;
    const bool curvature = py::isinstance<py::str>(field);
    return naming_source(mesh, [&] {
        const LimitTessellation t =
            tessellation_of(mesh, scheme, resolution, curvature, mesh.mesh.positions(), threads, rules);
        std::string name;
        const Eigen::VectorXd values = field_values(field, t, mesh.mesh.num_vertices(), name);
        const bool glb = extension == ".glb";
        py::dict out(
            "resolution"_a = t.resolution, "points"_a = t.num_points(), "triangles"_a = t.num_triangles(),
            "field"_a = values.size() > 0 ? py::object(py::str(name)) : py::object(py::none()),
            "field_min"_a = values.size() > 0 ? py::object(py::float_(values.minCoeff())) : py::object(py::none()),
            "field_max"_a = values.size() > 0 ? py::object(py::float_(values.maxCoeff())) : py::object(py::none()));
        if (glb) {
            write_glb(*output,
                      triangle_surface(t, values, name.empty() ? "field" : name, options.colormap, options.range));
            return out;
        }
        const ControlPolygon overlay =
            control_mesh ? control_polygon(mesh.mesh.topology(), mesh.mesh.positions()) : ControlPolygon{};
        RenderResult picture;
        {
            const py::gil_scoped_release release;
            picture = render_tessellation(t, values, options, overlay);
        }
        if (output) {
            write_png(*output, picture.image);
        }
        py::array_t<std::uint8_t> image({picture.image.height, picture.image.width, 3});
        std::copy(picture.image.pixels.begin(), picture.image.pixels.end(), image.mutable_data());
        out["image"] = image;
        out["coverage"] = picture.coverage;
        out["range"] =
            picture.has_field ? py::object(py::make_tuple(picture.range[0], picture.range[1])) : py::object(py::none());
        return out;
    });
}

void write_glb_arrays(const std::filesystem::path& path, const py::handle& positions, const py::handle& triangles,
                      const py::handle& normals, const py::handle& colors, const py::handle& scalar,
                      const std::string& scalar_name) {
    const std::string extension = lower_case(path.extension().string());
    LIMSURF_CHECK(extension == ".glb", InputError, "path: ", path.string(),
                  ": expected a .glb file (glTF binary), got '", extension, "'");
    TriangleSurface s;
    s.positions = points_from(positions, "positions");
    const auto n = static_cast<Index>(s.positions.rows());
    PolygonSoup soup;  // the triangles' checks (integers, range) are those of faces
    faces_into(triangles, "triangles", n, soup);
    LIMSURF_CHECK(soup.face_vertices.size() == 3 * static_cast<std::size_t>(soup.num_faces()), InputError,
                  "triangles: expected shape (t, 3)");
    s.triangles = Eigen::Map<const Eigen::Matrix<Index, Eigen::Dynamic, 3, Eigen::RowMajor>>(soup.face_vertices.data(),
                                                                                             soup.num_faces(), 3);
    if (!normals.is_none()) {
        s.normals = points_from(normals, "normals");
    }
    if (!colors.is_none()) {
        require_real_numbers(colors, "colors");
        const auto c = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(colors);
        LIMSURF_CHECK(c && c.ndim() == 2 && (c.shape(1) == 3 || c.shape(1) == 4) && c.shape(0) == n, InputError,
                      "colors: expected shape (", n, ", 3) or (", n, ", 4), sRGB in [0, 1]");
        s.colors.resize(n, 4);
        for (Index p = 0; p < n; ++p) {
            for (int k = 0; k < 4; ++k) {
                s.colors(p, k) = k < c.shape(1) ? c.at(p, k) : 1.0f;
            }
        }
    }
    if (!scalar.is_none()) {
        s.scalar = vector_from(scalar, "scalar", n);
        s.scalar_name = scalar_name;
    }
    write_glb(path, s);
}

}  // namespace

void bind_render(py::module_& m) {
    m.def(
        "tessellate",
        [](const Mesh& mesh, const std::string& scheme, int resolution, bool curvature, const py::handle& X,
           int threads, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            return naming_source(mesh, [&] {
                const Points P = X.is_none() ? mesh.mesh.positions() : points_from(X, "X");
                return tessellation_dict(tessellation_of(mesh, scheme, resolution, curvature, P, threads,
                                                         RuleNames{boundary, creasing, triangles}));
            });
        },
        "mesh"_a, "scheme"_a, py::kw_only(), "resolution"_a = 0, "curvature"_a = true, "X"_a = py::none(),
        "threads"_a = 0, "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(Triangles on the exact limit surface: per ptex face an N × N grid (resolution N, 0 = about 250 000
points in all), as `limsurf render` draws it. Returns 'positions', 'normals' (#P × 3), 'triangles'
(#T × 3 int32, counter-clockwise), the ptex points 'faces', 'u', 'v', 'mean_curvature' and
'gaussian_curvature' (with curvature=True), 'estimated' (normal and curvature taken from a nearby
point: at extraordinary vertices), 'value_weights' (#P × #V CSR: positions = W @ V, and a control
field u has the limit values W @ u) and 'resolution'.)");
    m.def(
        "render",
        [](const Mesh& mesh, const std::string& scheme, const py::handle& field, bool control_mesh, int isolines,
           const py::handle& view, const py::handle& size, int resolution, std::optional<std::array<double, 2>> range,
           const std::string& colormap, int supersampling, bool color_bar, std::optional<std::filesystem::path> output,
           int threads, std::optional<std::string> boundary, std::optional<std::string> creasing,
           std::optional<std::string> triangles) {
            return render(mesh, scheme, field, control_mesh, isolines, view, size, resolution, range, colormap,
                          supersampling, color_bar, output, threads, RuleNames{boundary, creasing, triangles});
        },
        "mesh"_a, "scheme"_a, "field"_a = py::none(), py::kw_only(), "control_mesh"_a = false, "isolines"_a = 0,
        "view"_a = "iso", "size"_a = py::make_tuple(1200, 900), "resolution"_a = 0, "range"_a = py::none(),
        "colormap"_a = "viridis", "supersampling"_a = 2, "color_bar"_a = true, "output"_a = py::none(), "threads"_a = 0,
        "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(),
        R"(A picture of the limit surface: the pixels `limsurf render` writes, with the same options.

field: None, 'mean-curvature', 'gaussian-curvature', or #V values at the control vertices (carried to
the surface through the limit basis, u_h = Σ u_i φ_i). view: 'iso', 'front', 'top' or (azimuth,
elevation) in degrees. size: (width, height). range: the field values at the colour map's ends
(default min..max; ±max|f| for 'coolwarm'). output: also write it, .png (the picture) or .glb (the
tessellation for Blender and web viewers: normals, colours, the field as attribute "_NAME").
threads: for the tessellation and the shading, 0 = all cores (the picture does not depend on it).
Returns 'image' (height × width × 3 uint8, RGB, top row first; not for .glb), 'coverage', 'range',
'field', 'field_min', 'field_max', 'resolution', 'points', 'triangles'.)");
    m.def("write_glb", &write_glb_arrays, "path"_a, "positions"_a, "triangles"_a, py::kw_only(),
          "normals"_a = py::none(), "colors"_a = py::none(), "scalar"_a = py::none(), "scalar_name"_a = "field",
          R"(Writes a triangle surface as glTF 2.0 binary (.glb), atomically: positions (#P × 3), triangles
(#T × 3, counter-clockwise), optional unit normals (#P × 3), colours (#P × 3 or 4, sRGB in [0, 1];
stored linear, as glTF wants) and a scalar (#P) written as the attribute "_" + upper-cased scalar_name.
Coordinates are stored as float32 (docs/io.md "glTF").)");
}

}  // namespace limsurf::python
