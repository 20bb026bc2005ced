// limsurf.Mesh, read_mesh, write_mesh, info: meshes in and out as numpy arrays and files.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/statistics.h"
#include "limsurf/mesh/submesh.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

void warn_about(const ValidationReport& report) {
    const py::object warn = py::module_::import("warnings").attr("warn");
    const py::object category = py::module_::import("limsurf._limsurf").attr("MeshWarning");
    for (const Issue& issue : report.issues) {
        warn(issue.to_string(), category, 3);
    }
}

Mesh built_from(const PolygonSoup& soup, IsolatedVertices isolated) {
    BuildOptions options;
    options.isolated_vertices = isolated;
    BuildResult built = build_control_mesh(soup, options);
    warn_about(built.report);
    return Mesh{std::move(built.mesh), std::move(built.source), std::move(built.report)};
}

IsolatedVertices isolated_from(const std::string& name) {
    LIMSURF_CHECK(name == "error" || name == "drop", InputError, "isolated: expected 'error' or 'drop', got '", name,
                  "'");
    return name == "drop" ? IsolatedVertices::Drop : IsolatedVertices::Error;
}

void creases_into(const py::handle& creases, Index num_vertices, SharpnessTags& tags) {
    if (creases.is_none()) {
        return;
    }
    require_real_numbers(creases, "creases");
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(creases);
    LIMSURF_CHECK(a && a.ndim() == 2 && a.shape(1) == 3, InputError,
                  "creases: expected rows (vertex, vertex, sharpness), shape (k, 3)");
    const auto view = a.unchecked<2>();
    for (py::ssize_t i = 0; i < view.shape(0); ++i) {
        for (int j = 0; j < 2; ++j) {
            const double v = view(i, j);
            LIMSURF_CHECK(v >= 0 && v < num_vertices && v == static_cast<double>(static_cast<Index>(v)), InputError,
                          "creases[", i, ", ", j, "] = ", v, ": not a vertex index (V has ", num_vertices, " rows)");
        }
        tags.creases.push_back({static_cast<Index>(view(i, 0)), static_cast<Index>(view(i, 1)), view(i, 2), 0});
    }
}

void corners_into(const py::handle& corners, Index num_vertices, SharpnessTags& tags) {
    if (corners.is_none()) {
        return;
    }
    require_real_numbers(corners, "corners");
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(corners);
    LIMSURF_CHECK(a && a.ndim() == 2 && a.shape(1) == 2, InputError,
                  "corners: expected rows (vertex, sharpness), shape (k, 2)");
    const auto view = a.unchecked<2>();
    for (py::ssize_t i = 0; i < view.shape(0); ++i) {
        const double v = view(i, 0);
        LIMSURF_CHECK(v >= 0 && v < num_vertices && v == static_cast<double>(static_cast<Index>(v)), InputError,
                      "corners[", i, ", 0] = ", v, ": not a vertex index (V has ", num_vertices, " rows)");
        tags.corners.push_back({static_cast<Index>(v), view(i, 1), 0});
    }
}

Mesh mesh_from_arrays(const py::handle& V, const py::handle& F, const py::handle& creases, const py::handle& corners,
                      const py::handle& holes, const RuleNames& hints, const std::string& isolated) {
    PolygonSoup soup;
    soup.positions = points_from(V, "V");
    faces_into(F, "F", soup.num_vertices(), soup);
    creases_into(creases, soup.num_vertices(), soup.sharpness);
    corners_into(corners, soup.num_vertices(), soup.sharpness);
    if (!holes.is_none()) {
        for (const Index f : indices_from(holes, "holes", soup.num_faces())) {
            soup.sharpness.holes.push_back({f, 0});
        }
    }
    soup.hints = hints_from(hints);
    return built_from(soup, isolated_from(isolated));
}

py::array_t<Index> index_array(std::span<const Index> values) {
    py::array_t<Index> out(static_cast<py::ssize_t>(values.size()));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

/// F as one (faces × degree) array when every face has one degree, else a list of arrays.
py::object faces_of(const Topology& t) {
    return faces_array(t.face_offsets(), t.all_face_vertices());
}

py::array_t<Index> edges_of(const Topology& t) {
    py::array_t<Index> out({static_cast<py::ssize_t>(t.num_edges()), py::ssize_t{2}});
    auto view = out.mutable_unchecked<2>();
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ends = t.edge_vertices(e);
        view(e, 0) = ends[0];
        view(e, 1) = ends[1];
    }
    return out;
}

py::dict histogram(const std::map<Index, Index>& counts) {
    py::dict out;
    for (const auto& [key, count] : counts) {
        out[py::int_(key)] = count;
    }
    return out;
}

py::dict hints_dict(const SchemeHints& hints) {
    py::dict out;
    if (hints.boundary) {
        out["boundary"] = to_string(*hints.boundary);
    }
    if (hints.creasing) {
        out["creasing"] = to_string(*hints.creasing);
    }
    if (hints.triangles) {
        out["triangles"] = to_string(*hints.triangles);
    }
    return out;
}

/// The numbers of `limsurf info --json`, with the same keys (histogram keys are ints here).
py::dict info(const Mesh& m) {
    const Topology& t = m.mesh.topology();
    const MeshStatistics stats = statistics(m.mesh);
    const SharpnessSummary& s = stats.sharpness;
    std::map<Index, Index> all_valences = stats.interior_valences;
    for (const auto& [valence, count] : stats.boundary_valences) {
        all_valences[valence] += count;
    }
    py::list issues;
    for (const Issue& issue : m.report.issues) {
        issues.append(py::dict("severity"_a = issue.severity == Severity::Error ? "error" : "warning",
                               "problem"_a = problem_name(issue.problem), "location"_a = issue.location,
                               "message"_a = issue.message));
    }
    const auto vec = [](const Eigen::Vector3d& x) { return py::make_tuple(x.x(), x.y(), x.z()); };
    return py::dict(
        "file"_a = m.source.file.empty() ? py::object(py::none()) : py::str(m.source.file),
        "num_vertices"_a = t.num_vertices(), "num_edges"_a = t.num_edges(), "num_faces"_a = t.num_faces(),
        "num_corners"_a = t.num_corners(), "euler_characteristic"_a = t.euler_characteristic(), "genus"_a = t.genus(),
        "num_components"_a = t.num_components(), "num_boundary_loops"_a = t.num_boundary_loops(),
        "boundary_loop_lengths"_a = stats.boundary_loop_lengths, "is_closed"_a = t.is_closed(),
        "face_degree_histogram"_a = histogram(stats.face_degrees), "valence_histogram"_a = histogram(all_valences),
        "interior_valence_histogram"_a = histogram(stats.interior_valences),
        "boundary_valence_histogram"_a = histogram(stats.boundary_valences),
        "bounding_box"_a = py::dict("min"_a = vec(stats.bounding_box_min), "max"_a = vec(stats.bounding_box_max)),
        "sharpness"_a = py::dict(
            "num_sharp_edges"_a = s.num_sharp_edges, "num_infinitely_sharp_edges"_a = s.num_infinitely_sharp_edges,
            "max_semi_sharp_edge"_a = s.max_semi_sharp_edge, "num_sharp_vertices"_a = s.num_sharp_vertices,
            "num_infinitely_sharp_vertices"_a = s.num_infinitely_sharp_vertices, "num_holes"_a = s.num_holes),
        "scheme_hints"_a = hints_dict(m.mesh.hints()), "validation"_a = py::dict("issues"_a = issues));
}

PlyEncoding encoding_from(const std::string& name) {
    if (name == "ascii") {
        return PlyEncoding::Ascii;
    }
    if (name == "binary-le") {
        return PlyEncoding::BinaryLittleEndian;
    }
    LIMSURF_CHECK(name == "binary-be", InputError, "ply_encoding: expected ascii, binary-le or binary-be, got '", name,
                  "'");
    return PlyEncoding::BinaryBigEndian;
}

/// (face_group, names): int32 #F group numbers (-1: no group) and the group names; all -1 and []
/// when there are no groups.
py::tuple groups_tuple(const FaceGroups& groups, Index num_faces) {
    py::array_t<Index> face_group(static_cast<py::ssize_t>(num_faces));
    for (Index f = 0; f < num_faces; ++f) {
        face_group.mutable_data()[f] = groups.group_of(f);
    }
    return py::make_tuple(std::move(face_group), groups.names);
}

std::string repr(const Mesh& m) {
    const Topology& t = m.mesh.topology();
    return detail::concat("<limsurf.Mesh ", t.num_vertices(), " vertices, ", t.num_faces(), " faces, genus ", t.genus(),
                          t.is_closed() ? ", closed" : ", with boundary",
                          m.source.file.empty() ? std::string() : ", from " + m.source.file, ">");
}

/// The faces a caller keeps: a boolean or integer array of one entry per face (non-zero keeps).
std::vector<char> selection_from(const py::handle& keep, Index num_faces) {
    const py::array a = py::array::ensure(keep);
    LIMSURF_CHECK(a && (a.dtype().kind() == 'b' || a.dtype().kind() == 'i' || a.dtype().kind() == 'u'), InputError,
                  "keep: expected booleans or integers, one per face");
    LIMSURF_CHECK(a.ndim() == 1 && a.shape(0) == num_faces, InputError, "keep: expected shape (", num_faces,
                  ",), one entry per face, got ",
                  a.ndim() == 1 ? std::to_string(a.shape(0)) + " entries" : std::to_string(a.ndim()) + " dimensions");
    const auto b = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(a);
    const auto view = b.unchecked<1>();
    std::vector<char> selection(static_cast<std::size_t>(num_faces));
    for (py::ssize_t f = 0; f < view.shape(0); ++f) {
        selection[static_cast<std::size_t>(f)] = view(f) ? 1 : 0;
    }
    return selection;
}

py::array_t<Index> index_array(const std::vector<Index>& values) {
    py::array_t<Index> out(static_cast<py::ssize_t>(values.size()));
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::tuple submesh(const Mesh& mesh, const py::handle& keep) {
    const Topology& t = mesh.mesh.topology();
    Submesh sub = face_submesh(t, selection_from(keep, t.num_faces()));
    Points X(sub.topology.num_vertices(), 3);
    for (Index v = 0; v < sub.topology.num_vertices(); ++v) {
        X.row(v) = mesh.mesh.positions().row(sub.vertex_origin[static_cast<std::size_t>(v)]);
    }
    py::object part = py::cast(Mesh{ControlMesh(std::move(sub.topology), std::move(X)), {}, {}});
    return py::make_tuple(part, index_array(sub.vertex_origin), index_array(sub.face_origin));
}

}  // namespace

void bind_mesh(py::module_& m) {
    m.attr("MeshWarning") = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
        "limsurf.MeshWarning", "What validation noticed about a mesh that is still usable (a UserWarning).",
        PyExc_UserWarning, nullptr));
    py::class_<Mesh>(m, "Mesh", R"(A validated control mesh: positions V (#V × 3) and polygonal faces.

Immutable. Build one from arrays with Mesh(V, F) or read one with read_mesh(path).
Validation (manifoldness, orientation, degenerate faces) raises limsurf.TopologyError or
limsurf.InputError naming the face and the problem; warnings go through Python's warnings
module (limsurf.MeshWarning).)")
        .def(py::init([](const py::handle& V, const py::handle& F, const py::handle& creases, const py::handle& corners,
                         const py::handle& holes, std::optional<std::string> boundary,
                         std::optional<std::string> creasing, std::optional<std::string> triangles,
                         const std::string& isolated) {
                 return mesh_from_arrays(V, F, creases, corners, holes, RuleNames{boundary, creasing, triangles},
                                         isolated);
             }),
             "V"_a, "F"_a, py::kw_only(), "creases"_a = py::none(), "corners"_a = py::none(), "holes"_a = py::none(),
             "boundary"_a = py::none(), "creasing"_a = py::none(), "triangles"_a = py::none(), "isolated"_a = "error",
             R"(Builds a mesh from arrays.

V: (n, 3) real array (any dtype or strides; copied). F: (m, k) integer array (all faces of
degree k) or a list of integer sequences (polygons of any degree), counter-clockwise seen from
outside. creases: rows (v0, v1, sharpness); corners: rows (v, sharpness); holes: face indices
(sharpness >= 10 is infinitely sharp, OpenSubdiv's convention). boundary / creasing / triangles:
scheme hints as a file's tags give them ("edge-and-corner", "chaikin", "smooth"...).
isolated: "error" refuses vertices no face uses; "drop" removes them (renumbering V) with a warning.
Raises InputError naming the array, row and problem; TopologyError for unusable connectivity.)")
        .def_property_readonly(
            "V", [](const py::object& self) { return read_only_view(self.cast<const Mesh&>().mesh.positions(), self); },
            "Positions (#V × 3 float64): a read-only view of the mesh's memory (keeps the mesh alive).")
        .def_property_readonly(
            "F", [](const Mesh& self) { return faces_of(self.mesh.topology()); },
            "Faces: an int32 array (#F × k) when all faces have degree k, else a list of int32 arrays (a copy).")
        .def_property_readonly(
            "face_offsets", [](const Mesh& self) { return index_array(self.mesh.topology().face_offsets()); },
            "int32 array (#F + 1): face f's corners are face_vertices[face_offsets[f]:face_offsets[f + 1]].")
        .def_property_readonly(
            "face_vertices", [](const Mesh& self) { return index_array(self.mesh.topology().all_face_vertices()); },
            "int32 array: the corners of all faces, concatenated.")
        .def_property_readonly(
            "edges", [](const Mesh& self) { return edges_of(self.mesh.topology()); },
            "int32 array (#E × 2), lower vertex first: the edge numbering of 1-forms (d0, M1).")
        .def_property_readonly("num_vertices", [](const Mesh& self) { return self.mesh.num_vertices(); })
        .def_property_readonly("num_edges", [](const Mesh& self) { return self.mesh.num_edges(); })
        .def_property_readonly("num_faces", [](const Mesh& self) { return self.mesh.num_faces(); })
        .def_property_readonly("genus", [](const Mesh& self) { return self.mesh.topology().genus(); })
        .def_property_readonly("is_closed", [](const Mesh& self) { return self.mesh.topology().is_closed(); })
        .def_property_readonly(
            "boundary_loops",
            [](const Mesh& self) {
                const Topology& t = self.mesh.topology();
                py::list loops;
                for (Index i = 0; i < t.num_boundary_loops(); ++i) {
                    loops.append(index_array(t.boundary_loop(i)));
                }
                return loops;
            },
            "The boundary loops as int32 arrays of vertex indices, in loop order.")
        .def_property_readonly(
            "creases",
            [](const Mesh& self) {
                const SharpnessTags tags = self.mesh.topology().sharpness_tags();
                Eigen::MatrixXd out(static_cast<Eigen::Index>(tags.creases.size()), 3);
                for (std::size_t i = 0; i < tags.creases.size(); ++i) {
                    const CreaseTag& c = tags.creases[i];
                    out.row(static_cast<Eigen::Index>(i)) << c.v0, c.v1, c.sharpness;
                }
                return to_numpy(out);
            },
            "Sharp edges as rows (v0, v1, sharpness) (float64).")
        .def_property_readonly(
            "corners",
            [](const Mesh& self) {
                const SharpnessTags tags = self.mesh.topology().sharpness_tags();
                Eigen::MatrixXd out(static_cast<Eigen::Index>(tags.corners.size()), 2);
                for (std::size_t i = 0; i < tags.corners.size(); ++i) {
                    out.row(static_cast<Eigen::Index>(i)) << tags.corners[i].vertex, tags.corners[i].sharpness;
                }
                return to_numpy(out);
            },
            "Sharp vertices as rows (v, sharpness) (float64).")
        .def_property_readonly(
            "file",
            [](const Mesh& self) { return self.source.file.empty() ? std::optional<std::string>() : self.source.file; },
            "The file the mesh was read from, or None.")
        .def(
            "with_positions",
            [](const Mesh& self, const py::handle& V) {
                return naming_source(self, [&] {
                    return Mesh{self.mesh.with_positions(points_from(V, "V")), self.source, self.report};
                });
            },
            "V"_a, "The same connectivity and tags with new positions V (#V × 3).")
        .def("__repr__", &repr);

    m.def(
        "read_mesh",
        [](const std::filesystem::path& path, const std::string& isolated, bool groups) -> py::object {
            BuildOptions options;
            options.isolated_vertices = isolated_from(isolated);
            BuildResult built = read_mesh(path, options);
            warn_about(built.report);
            const Index num_faces = built.mesh.num_faces();
            py::object mesh = py::cast(Mesh{std::move(built.mesh), std::move(built.source), std::move(built.report)});
            if (!groups) {
                return mesh;
            }
            const py::tuple g = groups_tuple(built.groups, num_faces);
            return py::make_tuple(mesh, g[0], g[1]);
        },
        "path"_a, py::kw_only(), "isolated"_a = "drop", "groups"_a = false,
        "Reads an OBJ, OFF or PLY mesh with its subdivision tags (OpenSubdiv's t crease/corner/hole lines).\n"
        "groups=True returns (mesh, face_group, group_names): face_group is an int32 array (#F) of indices\n"
        "into group_names (the OBJ's usemtl, else g, names), -1 for a face in no group; all -1 and [] for\n"
        "a file without groups.\n"
        "Raises InputError or TopologyError with 'file:line: element: problem'.");
    m.def(
        "write_mesh",
        [](const std::filesystem::path& path, const Mesh& mesh, const std::string& ply_encoding) {
            WriteOptions options;
            options.ply_encoding = encoding_from(ply_encoding);
            const std::vector<std::string> warnings = write_mesh(path, mesh.mesh, options);
            const py::object warn = py::module_::import("warnings").attr("warn");
            for (const std::string& w : warnings) {
                warn(w, py::handle(PyExc_UserWarning), 2);
            }
        },
        "path"_a, "mesh"_a, py::kw_only(), "ply_encoding"_a = "ascii",
        "Writes the mesh atomically as .obj, .off or .ply (by extension) with its tags; ply_encoding is\n"
        "'ascii', 'binary-le' or 'binary-be'.");
    m.def("submesh", &submesh, "mesh"_a, "keep"_a,
          "The faces with keep[f] true (a bool or integer array, one entry per face) as a mesh of their own:\n"
          "(part, vertex_origin, face_origin), the origins int32 arrays into the mesh's vertices and faces.\n"
          "A vertex where kept faces meet without sharing an edge becomes one vertex per fan, so the part is\n"
          "always a manifold; kept faces keep their order and orientation; tags are not carried.");
    m.def("info", &info, "mesh"_a,
          "Counts, histograms, boundary, genus, bounding box, sharpness and validation warnings: the numbers of\n"
          "`limsurf info --json` under the same keys.");
}

}  // namespace limsurf::python
