// Plane elasticity (apps/elasticity.h): limsurf.elasticity, the numbers of `limsurf elasticity --json`
// (homogenised stress, effective stiffness, bounds per level) with the displacement's control values
// and, when asked, the fields on the limit surface as numpy arrays.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "common.h"
#include "limsurf/apps/elasticity.h"

namespace limsurf::python {
namespace {

using namespace pybind11::literals;

/// A Mesh from arrays, through limsurf.Mesh (the same validation and warnings).
Mesh mesh_from(const py::handle& V, const py::handle& F) {
    return py::module_::import("limsurf._limsurf").attr("Mesh")(V, F).cast<Mesh>();
}

/// The keyword arguments of limsurf.elasticity, as given.
struct ElasticityArgs {
    double E = 1.0;
    double nu = 0.3;
    bool plane_stress = false;
    std::string boundary = "periodic";
    py::object macro_deformation;
    py::object face_material;
    py::object materials;
    int levels = 0;
    int quadrature = 6;
    bool effective_stiffness = true;
    bool crease_interfaces = false;
    py::object clamp;
    py::object tractions;
    py::object body_force;
    int resolution = 0;
    int threads = 0;
};

ElasticBoundary boundary_from(const std::string& name) {
    if (name == "periodic") {
        return ElasticBoundary::Periodic;
    }
    if (name == "affine") {
        return ElasticBoundary::Affine;
    }
    LIMSURF_CHECK(name == "loaded", InputError, "boundary: expected 'periodic', 'affine' or 'loaded', got '", name,
                  "'");
    return ElasticBoundary::Loaded;
}

Eigen::Vector2d pair_from(const py::handle& x, const std::string& name) {
    const Eigen::VectorXd v = vector_from(x, name, 2);
    return {v[0], v[1]};
}

Eigen::Matrix2d matrix2_from(const py::handle& x, const std::string& name) {
    require_real_numbers(x, name);  // before the cast below, which would drop an imaginary part
    const py::array a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(x);
    LIMSURF_CHECK(a && a.ndim() == 2 && a.shape(0) == 2 && a.shape(1) == 2, InputError, name,
                  ": expected a 2 x 2 matrix (rows)");
    const Eigen::VectorXd v = vector_from(a.attr("reshape")(4), name, 4);
    Eigen::Matrix2d F;
    F << v[0], v[1], v[2], v[3];
    return F;
}

/// The materials of the body: material 0 is (E, ν) for the faces marked -1 (left out when no face is),
/// then materials[k] for the faces marked k. Returns the name of each body material ("default" or k).
std::vector<std::string> body_from(const ElasticityArgs& args, Index num_faces, ElasticBody& body) {
    body.model = args.plane_stress ? PlaneModel::Stress : PlaneModel::Strain;
    body.materials = {ElasticMaterial{args.E, args.nu}};
    if (args.face_material.is_none()) {
        LIMSURF_CHECK(args.materials.is_none(), InputError,
                      "materials: needs face_material (which faces are made of each material)");
        return {"default"};
    }
    LIMSURF_CHECK(!args.materials.is_none(), InputError,
                  "face_material: needs materials, the list of (E, nu) its entries index");
    std::vector<ElasticMaterial> listed;
    for (const py::handle item : args.materials) {
        const Eigen::Vector2d m = pair_from(item, "materials[" + std::to_string(listed.size()) + "]");
        listed.push_back({m[0], m[1]});
    }
    const py::array a = py::array::ensure(args.face_material);
    LIMSURF_CHECK(a && (a.dtype().kind() == 'i' || a.dtype().kind() == 'u'), InputError,
                  "face_material: expected an integer array");
    LIMSURF_CHECK(a.ndim() == 1 && a.shape(0) == num_faces, InputError, "face_material: expected ", num_faces,
                  " entries (one per face), got shape ", std::string(py::str(a.attr("shape"))));
    const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    const auto view = values.unchecked<1>();
    bool any_default = false;
    for (py::ssize_t f = 0; f < view.shape(0); ++f) {
        LIMSURF_CHECK(view(f) >= -1 && view(f) < static_cast<std::int64_t>(listed.size()), InputError, "face_material[",
                      f, "] = ", view(f), ": expected -1 (E, nu) or an index into materials (", listed.size(),
                      " of them)");
        any_default = any_default || view(f) == -1;
    }
    const Index shift = any_default ? 1 : 0;
    std::vector<std::string> names;
    if (!any_default) {
        body.materials.clear();
    } else {
        names.push_back("default");
    }
    for (std::size_t k = 0; k < listed.size(); ++k) {
        body.materials.push_back(listed[k]);
        names.push_back(std::to_string(k));
    }
    body.face_material.resize(static_cast<std::size_t>(num_faces));
    for (py::ssize_t f = 0; f < view.shape(0); ++f) {
        body.face_material[static_cast<std::size_t>(f)] = static_cast<Index>(view(f)) + shift;
    }
    return names;
}

ElasticityStudyOptions study_from(const ElasticityArgs& args, Index num_faces, std::vector<std::string>& names) {
    ElasticityStudyOptions study;
    names = body_from(args, num_faces, study.body);
    for (std::size_t k = 0; k < study.body.materials.size(); ++k) {
        try {
            (void)elasticity_matrix(study.body.materials[k], study.body.model);
        } catch (const InputError& error) {
            throw InputError((names[k] == "default" ? std::string("E, nu") : "materials[" + names[k] + "]") + ": " +
                             error.what());
        }
    }
    study.boundary = boundary_from(args.boundary);
    if (!args.macro_deformation.is_none()) {
        study.macro_deformation = matrix2_from(args.macro_deformation, "macro_deformation");
    }
    for (const py::handle side : args.clamp) {
        study.clamped.push_back(
            parse_rectangle_side(cast_as<std::string>(side, "clamp", "a side name (left, right, bottom, top)")));
    }
    for (const py::handle item : args.tractions) {
        LIMSURF_CHECK(py::isinstance<py::sequence>(item) && py::len(item) == 2, InputError,
                      "tractions: expected (side, (tx, ty)) pairs");
        const py::sequence pair = py::reinterpret_borrow<py::sequence>(item);
        study.tractions.push_back(
            {parse_rectangle_side(cast_as<std::string>(pair[0], "tractions", "a side name (left, right, bottom, top)")),
             pair_from(pair[1], "tractions (tx, ty)")});
    }
    const bool loaded = study.boundary == ElasticBoundary::Loaded;
    LIMSURF_CHECK(loaded || (study.clamped.empty() && study.tractions.empty()), InputError,
                  "clamp and tractions need boundary='loaded'");
    study.body_force = pair_from(args.body_force, "body_force");
    study.levels = args.levels;
    LIMSURF_CHECK(args.threads >= 0, InputError, "threads: expected 0 (all cores) or a positive count, got ",
                  args.threads);
    study.quadrature = SamplerOptions{args.quadrature, 6, args.threads};
    study.effective_stiffness = args.effective_stiffness && !loaded;
    study.crease_interfaces = args.crease_interfaces;
    return study;
}

py::array_t<double> vector3(const Eigen::Vector3d& v) {
    return to_numpy(Eigen::VectorXd(v));
}

/// The control values (u_x, u_y) per vertex as a (#V, 2) array.
py::array_t<double> displacement_array(const Eigen::VectorXd& u) {
    const Index n = u.size() / 2;
    Eigen::MatrixXd out(n, 2);
    for (Index i = 0; i < n; ++i) {
        out(i, 0) = u[2 * i];
        out(i, 1) = u[2 * i + 1];
    }
    return to_numpy(out);
}

py::dict level_dict(const ElasticityLevel& level) {
    const ElasticAverages& a = level.averages;
    py::dict out("level"_a = level.level, "vertices"_a = level.topology.num_vertices(),
                 "faces"_a = level.topology.num_faces(), "residual"_a = level.solution.residual,
                 "energy"_a = level.solution.energy, "solver"_a = level.solution.solver, "area"_a = a.area,
                 "homogenised_stress"_a = vector3(a.stress), "mean_strain"_a = vector3(a.strain),
                 "material_area"_a = a.material_area, "seconds"_a = level.seconds);
    out["effective_stiffness"] = level.effective_stiffness
                                     ? py::object(to_numpy(Eigen::MatrixXd(*level.effective_stiffness)))
                                     : py::object(py::none());
    out["u"] = displacement_array(level.solution.u);
    out["mesh"] = py::cast(Mesh{ControlMesh(level.topology, level.X), SourceMap{}, ValidationReport{}});
    return out;
}

py::object bounds_dict(const std::optional<StiffnessBounds>& bounds) {
    if (!bounds) {
        return py::none();
    }
    const auto pair = [](const std::optional<std::array<double, 2>>& p) {
        return p ? py::object(py::make_tuple((*p)[0], (*p)[1])) : py::object(py::none());
    };
    return py::dict("voigt"_a = to_numpy(Eigen::MatrixXd(bounds->voigt)),
                    "reuss"_a = to_numpy(Eigen::MatrixXd(bounds->reuss)),
                    "bulk_hashin_shtrikman"_a = pair(bounds->bulk_hashin_shtrikman),
                    "shear_hashin_shtrikman"_a = pair(bounds->shear_hashin_shtrikman));
}

py::dict fields_dict(const ElasticityFields& fields) {
    const LimitTessellation& t = fields.tessellation;
    py::array_t<std::int32_t> triangles({static_cast<py::ssize_t>(t.num_triangles()), py::ssize_t{3}});
    auto tri = triangles.mutable_unchecked<2>();
    for (Index i = 0; i < t.num_triangles(); ++i) {
        for (int j = 0; j < 3; ++j) {
            tri(i, j) = static_cast<std::int32_t>(t.triangles(i, j));
        }
    }
    py::array_t<std::int32_t> material(static_cast<py::ssize_t>(fields.material.size()));
    for (Index i = 0; i < fields.material.size(); ++i) {
        material.mutable_data()[i] = fields.material[i];
    }
    return py::dict("positions"_a = to_numpy(t.positions), "triangles"_a = triangles,
                    "displacement"_a = to_numpy(Eigen::MatrixXd(fields.displacement)),
                    "strain"_a = to_numpy(fields.strain), "stress"_a = to_numpy(fields.stress),
                    "von_mises"_a = to_numpy(fields.von_mises), "material"_a = material, "resolution"_a = t.resolution);
}

py::dict elasticity(const Mesh& mesh, const ElasticityArgs& args) {
    return naming_source(mesh, [&] {
        LIMSURF_CHECK(args.resolution >= 0 && args.resolution <= 64, InputError,
                      "resolution: expected 0 (no fields) or 1..64, got ", args.resolution);
        std::vector<std::string> names;
        const ElasticityStudyOptions study = study_from(args, mesh.mesh.num_faces(), names);
        ElasticityStudy r;
        std::optional<ElasticityFields> fields;
        {
            const py::gil_scoped_release release;
            r = solve_elasticity_levels(mesh.mesh.topology(), mesh.mesh.positions(), study);
            if (args.resolution > 0) {
                ElasticBody body = study.body;
                body.face_material = r.levels.back().face_material;
                fields = elasticity_fields(r.levels.back(), body, args.resolution, args.threads);
            }
        }
        py::list materials;
        for (std::size_t k = 0; k < study.body.materials.size(); ++k) {
            Index faces = 0;
            for (Index f = 0; f < mesh.mesh.num_faces(); ++f) {
                faces += study.body.face_material.empty() ||
                         study.body.face_material[static_cast<std::size_t>(f)] == static_cast<Index>(k);
            }
            materials.append(py::dict("name"_a = names[k], "E"_a = study.body.materials[k].E,
                                      "nu"_a = study.body.materials[k].nu, "faces"_a = faces));
        }
        py::list levels;
        for (const ElasticityLevel& level : r.levels) {
            levels.append(level_dict(level));
        }
        const bool macro = study.boundary != ElasticBoundary::Loaded;
        py::dict out("model"_a = to_string(study.body.model), "boundary"_a = to_string(study.boundary),
                     "crease_interfaces"_a = study.crease_interfaces,
                     "macro_deformation"_a = macro ? py::object(to_numpy(Eigen::MatrixXd(study.macro_deformation)))
                                                   : py::object(py::none()),
                     "body_force"_a = py::make_tuple(study.body_force[0], study.body_force[1]),
                     "materials"_a = materials,
                     "quadrature"_a = py::dict("degree"_a = study.quadrature.degree,
                                               "tile_levels"_a = study.quadrature.subdivide_near_extraordinary),
                     "rectangle"_a = py::dict("x0"_a = r.x0, "y0"_a = r.y0, "x1"_a = r.x1, "y1"_a = r.y1),
                     "levels"_a = levels, "bounds"_a = bounds_dict(r.bounds), "warnings"_a = r.warnings);
        if (r.cell) {
            py::array_t<std::int32_t> pairs({static_cast<py::ssize_t>(r.cell->pairs.size()), py::ssize_t{2}});
            auto p = pairs.mutable_unchecked<2>();
            for (std::size_t i = 0; i < r.cell->pairs.size(); ++i) {
                p(static_cast<py::ssize_t>(i), 0) = static_cast<std::int32_t>(r.cell->pairs[i].first);
                p(static_cast<py::ssize_t>(i), 1) = static_cast<std::int32_t>(r.cell->pairs[i].second);
            }
            out["cell"] = py::dict("pairs"_a = pairs, "pinned"_a = r.cell->pinned);
        } else {
            out["cell"] = py::none();
        }
        const py::dict finest = levels[levels.size() - 1].cast<py::dict>();
        out["u"] = finest["u"];
        out["effective_stiffness"] = finest["effective_stiffness"];
        out["mesh"] = finest["mesh"];
        if (fields) {
            out["fields"] = fields_dict(*fields);
        }
        return out;
    });
}

constexpr const char* elasticity_doc = R"(Plane linear elasticity on the limit surface of a planar (z = 0)
Catmull–Clark control mesh, on the mesh and on it refined 1..levels times (0..6): `limsurf elasticity
--json`'s numbers under the same keys (docs/guide/elasticity.md).

mesh: a Mesh, or the arrays V, F. E, nu: the material of the faces marked -1 in face_material (of every
face without it); plane_stress: σ_zz = 0 (a thin sheet) instead of plane strain (ε_zz = 0).
face_material: an integer array (#F): -1 for (E, nu), k for materials[k] ((E, nu) pairs), e.g. from
read_mesh(path, groups=True). boundary: 'periodic' (u = (Fᵐ − I) x + ũ, ũ periodic between opposite sides,
which must carry boundary vertices at the same heights and abscissae; ũ = 0 at the bottom-left corner),
'affine' (u = (Fᵐ − I) x on the boundary) or 'loaded' (clamp: sides 'left', 'right', 'bottom', 'top'
held at u = 0; tractions: [(side, (tx, ty)), ...], force per length). macro_deformation: Fᵐ as a 2 × 2
array (default [[1, 0.05], [0.05, 1]], the seed's shear). body_force: (fx, fy) per area. quadrature:
degree per tile. effective_stiffness: also solve the three unit macroscopic strains (periodic, affine). crease_interfaces:
tag the edges between faces of different materials as infinitely sharp creases first (the displacement may
kink there; C* converges much faster, the interface becomes the B-spline of its control vertices).
resolution > 0: also the fields of the finest level on its limit tessellation.

Returns 'model' ('strain' or 'stress'), 'boundary', 'macro_deformation' (None when loaded), 'body_force',
'materials' (per body material: 'name' ('default' or the index into materials), 'E', 'nu', 'faces'),
'quadrature', 'rectangle', 'cell' ('pairs' (image, source) control vertices and the 'pinned' corner; None
unless periodic), 'levels' (per level: 'level', 'vertices', 'faces', 'residual', 'energy', 'solver',
'area', 'homogenised_stress' (σ_xx, σ_yy, σ_xy averaged over the body), 'mean_strain' (ε_xx, ε_yy, γ_xy),
'material_area', 'effective_stiffness' (3 × 3 Voigt matrix C*, column j the homogenised stress under unit
strain j; None when not computed), 'seconds', 'u' (#V, 2) control values of the displacement, 'mesh'),
'bounds' (with two or more materials: 'voigt', 'reuss', 'bulk_hashin_shtrikman' and
'shear_hashin_shtrikman' (lower, upper) or None), 'warnings', and the finest level's 'u',
'effective_stiffness', 'mesh', with resolution > 0 also 'fields' ('positions' (#P, 3), 'triangles'
(#T, 3), 'displacement' (#P, 2), 'strain' and 'stress' (#P, 3), 'von_mises', 'material' (#P)). The solve
runs without the GIL; threads: for the quadrature, the assembly and the fields, 0 = all cores (the numbers
do not depend on it). Raises InputError for E ≤ 0, ν outside (−1, 0.5), a non-planar or closed mesh,
periodic sides that do not match (naming the vertex), a face_material of the wrong size or out of
range, a loaded body without a clamped side; NumericalError for a folded or degenerate map.)";

}  // namespace

void bind_elasticity(py::module_& m) {
    const auto run = [](const Mesh& mesh, double E, double nu, bool plane_stress, const std::string& boundary,
                        const py::object& macro_deformation, const py::object& face_material,
                        const py::object& materials, int levels, int quadrature, bool effective_stiffness,
                        bool crease_interfaces, const py::object& clamp, const py::object& tractions,
                        const py::object& body_force, int resolution, int threads) {
        return elasticity(mesh, ElasticityArgs{E, nu, plane_stress, boundary, macro_deformation, face_material,
                                               materials, levels, quadrature, effective_stiffness, crease_interfaces,
                                               clamp, tractions, body_force, resolution, threads});
    };
    m.def("elasticity", run, "mesh"_a, py::kw_only(), "E"_a = 1.0, "nu"_a = 0.3, "plane_stress"_a = false,
          "boundary"_a = "periodic", "macro_deformation"_a = py::none(), "face_material"_a = py::none(),
          "materials"_a = py::none(), "levels"_a = 0, "quadrature"_a = 6, "effective_stiffness"_a = true,
          "crease_interfaces"_a = false, "clamp"_a = py::tuple(), "tractions"_a = py::tuple(),
          "body_force"_a = py::make_tuple(0.0, 0.0), "resolution"_a = 0, "threads"_a = 0, elasticity_doc);
    m.def(
        "elasticity",
        [run](const py::object& V, const py::object& F, double E, double nu, bool plane_stress,
              const std::string& boundary, const py::object& macro_deformation, const py::object& face_material,
              const py::object& materials, int levels, int quadrature, bool effective_stiffness, bool crease_interfaces,
              const py::object& clamp, const py::object& tractions, const py::object& body_force, int resolution,
              int threads) {
            return run(mesh_from(V, F), E, nu, plane_stress, boundary, macro_deformation, face_material, materials,
                       levels, quadrature, effective_stiffness, crease_interfaces, clamp, tractions, body_force,
                       resolution, threads);
        },
        "V"_a, "F"_a, py::kw_only(), "E"_a = 1.0, "nu"_a = 0.3, "plane_stress"_a = false, "boundary"_a = "periodic",
        "macro_deformation"_a = py::none(), "face_material"_a = py::none(), "materials"_a = py::none(), "levels"_a = 0,
        "quadrature"_a = 6, "effective_stiffness"_a = true, "crease_interfaces"_a = false, "clamp"_a = py::tuple(),
        "tractions"_a = py::tuple(), "body_force"_a = py::make_tuple(0.0, 0.0), "resolution"_a = 0, "threads"_a = 0);
}

}  // namespace limsurf::python
