// limsurf elasticity MESH [--E E] [--nu NU] [--plane-stress] [--boundary periodic|affine|loaded | --periodic]
//   [--macro-strain "F11,F12;F21,F22"] [--material NAME:E,NU]... [--face-materials FILE] [--clamp SIDE]...
//   [--traction SIDE:TX,TY]... [--body-force FX,FY] [--levels L] [--quadrature D] [--threads N] [--no-stiffness]
//   [--crease-interfaces]
//   [-o fields.vtk|.vtu] [--png sxx.png [--png-field F] [--resolution N] [--size WxH]] [--json]:
// plane linear elasticity on the limit surface of a planar Catmull–Clark control mesh
// (iga-with-catmull-clark §6; docs/guide/elasticity.md). Periodic (the default) and affine boundaries
// impose the macroscopic deformation gradient Fᵐ (--macro-strain, the name for it) and report
// the homogenised stress and the effective stiffness per level; loaded bodies are clamped on sides of
// the bounding rectangle with tractions and a body force. Faces of an OBJ group (g/usemtl) or of a
// per-face file take their own material. Parsing and printing only: the levels are
// solve_elasticity_levels (apps/elasticity.h).
#include "limsurf/apps/elasticity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/threads_option.h"
#include "limsurf/io/face_groups.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vtk.h"
#include "limsurf/render/image.h"
#include "limsurf/render/render.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct ElasticityCommandOptions {
    std::string input;
    double E = 1.0;
    double nu = 0.3;
    bool plane_stress = false;
    std::string boundary;  // empty: periodic
    bool periodic = false;
    std::string macro_strain;  // empty: the seed's Fᵐ
    std::vector<std::string> materials;
    std::string face_materials;
    std::vector<std::string> clamps;
    std::vector<std::string> tractions;
    std::string body_force;
    int levels = 0;
    int quadrature = 6;
    bool no_stiffness = false;
    bool crease_interfaces = false;
    std::string output;
    std::string png;
    std::string png_field = "sxx";
    int resolution = 0;  // 0: automatic
    std::string size = "1200x1000";
    int threads = 0;
    bool json = false;
};

/// "a,b,..." as exactly @p count finite numbers; @p what names the option in the error.
Eigen::VectorXd parse_numbers(const std::string& what, const std::string& text, int count, const char* form) {
    std::stringstream in(text);
    Eigen::VectorXd out(count);
    bool ok = true;
    for (int i = 0; i < count && ok; ++i) {
        char comma = 0;
        ok = static_cast<bool>(in >> out[i]) && (i + 1 == count || ((in >> comma) && comma == ','));
    }
    ok = ok && (in >> std::ws).eof();
    LIMSURF_CHECK(ok && out.allFinite(), InputError, what, " '", text, "': expected ", count, " finite numbers ", form);
    return out;
}

/// "F11,F12;F21,F22": Fᵐ by rows.
Eigen::Matrix2d parse_matrix(const std::string& what, const std::string& text) {
    const auto semicolon = text.find(';');
    LIMSURF_CHECK(semicolon != std::string::npos && text.find(';', semicolon + 1) == std::string::npos, InputError,
                  what, " '", text, "': expected a 2 x 2 matrix by rows, 'F11,F12;F21,F22'");
    Eigen::Matrix2d F;
    F.row(0) = parse_numbers(what, text.substr(0, semicolon), 2, "F11,F12 in the first row").transpose();
    F.row(1) = parse_numbers(what, text.substr(semicolon + 1), 2, "F21,F22 in the second row").transpose();
    return F;
}

/// @p material checked as elasticity_matrix checks it, the error naming the option that gave it.
ElasticMaterial checked_material(const std::string& what, double E, double nu) {
    const ElasticMaterial material{E, nu};
    try {
        (void)elasticity_matrix(material, PlaneModel::Strain);
    } catch (const InputError& error) {
        throw InputError(what + ": " + error.what());
    }
    return material;
}

/// One --material: the faces of group `name` are made of `material`.
struct GroupMaterial {
    std::string name;
    ElasticMaterial material;
};

GroupMaterial parse_group_material(const std::string& text) {
    const auto colon = text.rfind(':');
    LIMSURF_CHECK(colon != std::string::npos && colon > 0, InputError, "--material '", text,
                  "': expected NAME:E,NU (a face group of the mesh or of --face-materials)");
    const Eigen::VectorXd values = parse_numbers("--material", text.substr(colon + 1), 2, "E,NU");
    return {text.substr(0, colon), checked_material("--material " + text, values[0], values[1])};
}

SideTraction parse_traction(const std::string& text) {
    const auto colon = text.find(':');
    LIMSURF_CHECK(colon != std::string::npos, InputError, "--traction '", text, "': expected SIDE:TX,TY");
    const Eigen::VectorXd t = parse_numbers("--traction", text.substr(colon + 1), 2, "TX,TY");
    return {parse_rectangle_side(text.substr(0, colon)), Eigen::Vector2d(t[0], t[1])};
}

ElasticBoundary boundary_of(const ElasticityCommandOptions& options) {
    const std::string name = options.boundary.empty() ? "periodic" : options.boundary;
    LIMSURF_CHECK(!options.periodic || name == "periodic", InputError, "--periodic contradicts --boundary ", name);
    if (name == "affine") {
        return ElasticBoundary::Affine;
    }
    return name == "loaded" ? ElasticBoundary::Loaded : ElasticBoundary::Periodic;
}

/// The options of the study from the command line, without the face assignment (it needs the mesh).
ElasticityStudyOptions study_options(const ElasticityCommandOptions& options) {
    ElasticityStudyOptions study;
    study.boundary = boundary_of(options);
    const bool loaded = study.boundary == ElasticBoundary::Loaded;
    LIMSURF_CHECK(!loaded || options.macro_strain.empty(), InputError,
                  "--macro-strain applies to --boundary periodic or affine, not loaded");
    LIMSURF_CHECK(loaded || (options.clamps.empty() && options.tractions.empty()), InputError,
                  "--clamp and --traction need --boundary loaded");
    if (!options.macro_strain.empty()) {
        study.macro_deformation = parse_matrix("--macro-strain", options.macro_strain);
    }
    study.body.model = options.plane_stress ? PlaneModel::Stress : PlaneModel::Strain;
    study.body.materials = {checked_material("--E/--nu", options.E, options.nu)};
    for (const std::string& side : options.clamps) {
        study.clamped.push_back(parse_rectangle_side(side));
    }
    for (const std::string& traction : options.tractions) {
        study.tractions.push_back(parse_traction(traction));
    }
    if (!options.body_force.empty()) {
        const Eigen::VectorXd b = parse_numbers("--body-force", options.body_force, 2, "FX,FY");
        study.body_force = Eigen::Vector2d(b[0], b[1]);
    }
    study.levels = options.levels;
    study.quadrature = SamplerOptions{options.quadrature, 6, options.threads};
    study.effective_stiffness = !options.no_stiffness && !loaded;
    study.crease_interfaces = options.crease_interfaces;
    return study;
}

/// What the materials are called in the output: "--E/--nu" for material 0, the group for the others.
struct MaterialNames {
    std::vector<std::string> names{"default"};
    std::vector<Index> faces;  ///< control faces of each material
};

/// Materials 1.. of the body from --material, by the face groups of the mesh or of --face-materials.
/// @throws InputError for a group that does not exist (listing those that do) or is named twice
MaterialNames assign_materials(const ElasticityCommandOptions& options, const std::vector<GroupMaterial>& listed,
                               const FaceGroups& groups, Index num_faces, ElasticBody& body,
                               std::vector<std::string>& warnings) {
    MaterialNames names;
    if (listed.empty()) {
        if (!options.face_materials.empty() || !groups.empty()) {
            warnings.push_back("no --material given: every face is made of the --E/--nu material");
        }
        names.faces = {num_faces};
        return names;
    }
    const std::string where = options.face_materials.empty() ? options.input : options.face_materials;
    body.face_material.assign(static_cast<std::size_t>(num_faces), 0);
    for (const GroupMaterial& m : listed) {
        LIMSURF_CHECK(std::find(names.names.begin(), names.names.end(), m.name) == names.names.end(), InputError,
                      "--material: group '", m.name, "' is given twice");
        const Index group = groups.find(m.name);
        if (group < 0) {
            std::string known;
            for (const std::string& name : groups.names) {
                known += (known.empty() ? "" : ", ") + name;
            }
            throw InputError(where + ": --material '" + m.name + "': no face group of that name (" +
                             (known.empty() ? std::string("the file has no face groups: OBJ g/usemtl lines or "
                                                          "--face-materials FILE give them")
                                            : "the groups are: " + known) +
                             ")");
        }
        const auto index = static_cast<Index>(body.materials.size());
        body.materials.push_back(m.material);
        names.names.push_back(m.name);
        for (Index f = 0; f < num_faces; ++f) {
            if (groups.group_of(f) == group) {
                body.face_material[static_cast<std::size_t>(f)] = index;
            }
        }
    }
    names.faces.assign(body.materials.size(), 0);
    for (const Index k : body.face_material) {
        ++names.faces[static_cast<std::size_t>(k)];
    }
    if (names.faces[0] == 0) {
        // Every face has its --material: leave out the unused default (it would count in the bounds).
        body.materials.erase(body.materials.begin());
        names.names.erase(names.names.begin());
        names.faces.erase(names.faces.begin());
        for (Index& k : body.face_material) {
            --k;
        }
    }
    for (std::size_t k = 0; k < names.faces.size(); ++k) {
        if (names.faces[k] == 0 && names.names[k] != "default") {
            warnings.push_back("--material '" + names.names[k] + "': the group has no faces");
        }
    }
    return names;
}

nlohmann::json vector_json(const Eigen::Vector3d& v) {
    return nlohmann::json{v[0], v[1], v[2]};
}

nlohmann::json matrix_json(const Eigen::MatrixXd& A) {
    nlohmann::json rows = nlohmann::json::array();
    for (Index i = 0; i < A.rows(); ++i) {
        nlohmann::json row = nlohmann::json::array();
        for (Index j = 0; j < A.cols(); ++j) {
            row.push_back(A(i, j));
        }
        rows.push_back(row);
    }
    return rows;
}

nlohmann::json level_json(const ElasticityLevel& level) {
    const ElasticAverages& a = level.averages;
    return {{"level", level.level},
            {"vertices", level.topology.num_vertices()},
            {"faces", level.topology.num_faces()},
            {"residual", level.solution.residual},
            {"energy", level.solution.energy},
            {"solver", level.solution.solver},
            {"area", a.area},
            {"homogenised_stress", vector_json(a.stress)},
            {"mean_strain", vector_json(a.strain)},
            {"material_area", a.material_area},
            {"effective_stiffness",
             level.effective_stiffness ? matrix_json(*level.effective_stiffness) : nlohmann::json(nullptr)},
            {"seconds", level.seconds}};
}

nlohmann::json bounds_json(const StiffnessBounds& bounds) {
    const auto pair_json = [](const std::optional<std::array<double, 2>>& p) {
        return p ? nlohmann::json{(*p)[0], (*p)[1]} : nlohmann::json(nullptr);
    };
    return {{"voigt", matrix_json(bounds.voigt)},
            {"reuss", matrix_json(bounds.reuss)},
            {"bulk_hashin_shtrikman", pair_json(bounds.bulk_hashin_shtrikman)},
            {"shear_hashin_shtrikman", pair_json(bounds.shear_hashin_shtrikman)}};
}

/// Segments per ptex face side: about 100000 points over the finest level, 2..16.
int automatic_field_resolution(const Topology& topology) {
    Index ptex = 0;
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const Index d = topology.face_degree(f);
        ptex += d == 4 ? 1 : d;
    }
    const double n = std::sqrt(100000.0 / static_cast<double>(std::max<Index>(ptex, 1)));
    return std::clamp(static_cast<int>(n), 2, 16);
}

/// The tessellation's points and triangles, as a soup for write_vertex_data.
PolygonSoup tessellation_soup(const LimitTessellation& t) {
    PolygonSoup soup;
    soup.positions = t.positions;
    for (Index i = 0; i < t.num_triangles(); ++i) {
        const Index corners[3] = {t.triangles(i, 0), t.triangles(i, 1), t.triangles(i, 2)};
        soup.add_face(corners);
    }
    return soup;
}

std::vector<VertexField> field_list(const ElasticityFields& fields) {
    const Index n = fields.tessellation.num_points();
    Eigen::MatrixXd displacement = Eigen::MatrixXd::Zero(n, 3);
    displacement.leftCols(2) = fields.displacement;
    return {{"displacement", displacement},
            {"strain_xx", fields.strain.col(0)},
            {"strain_yy", fields.strain.col(1)},
            {"strain_gamma_xy", fields.strain.col(2)},
            {"stress_xx", fields.stress.col(0)},
            {"stress_yy", fields.stress.col(1)},
            {"stress_xy", fields.stress.col(2)},
            {"von_mises", fields.von_mises},
            {"material", fields.material.cast<double>()}};
}

/// The --png-field values and the colour map that suits them.
Eigen::VectorXd picture_field(const ElasticityFields& fields, const std::string& name) {
    if (name == "sxx" || name == "syy" || name == "sxy") {
        return fields.stress.col(name == "sxx" ? 0 : name == "syy" ? 1 : 2);
    }
    if (name == "ux" || name == "uy") {
        return fields.displacement.col(name == "ux" ? 0 : 1);
    }
    return fields.von_mises;
}

/// The colour map's range over the 0.5–99.5 percentiles of @p field (a diverging map: ±the 99.5th
/// percentile of |f|): the stresses at material corners are singular in the exact solution and would
/// otherwise leave one colour for the rest of the picture; values beyond the range take the end colours.
std::array<double, 2> robust_range(const Eigen::VectorXd& field, Colormap colormap) {
    std::vector<double> values(field.data(), field.data() + field.size());
    const auto percentile = [&values](double q) {
        const auto k = static_cast<std::size_t>(q * static_cast<double>(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
        return values[k];
    };
    if (values.empty()) {
        return {0.0, 0.0};
    }
    if (is_diverging(colormap)) {
        for (double& v : values) {
            v = std::abs(v);
        }
        const double top = percentile(0.995);
        return {-top, top};
    }
    const double lo = percentile(0.005);
    return {lo, percentile(0.995)};
}

/// Writes -o and --png (the picture rendered before any file is written, so that a refused picture
/// leaves no file; a failed second write removes the first).
nlohmann::json write_outputs(const ElasticityCommandOptions& options, const ElasticityStudy& result,
                             const ElasticBody& study_body) {
    nlohmann::json out;
    const ElasticityLevel& finest = result.levels.back();
    ElasticBody body = study_body;
    body.face_material = finest.face_material;
    const int resolution = options.resolution > 0 ? options.resolution : automatic_field_resolution(finest.topology);
    const ElasticityFields fields = elasticity_fields(finest, body, resolution, options.threads);
    std::optional<RenderResult> picture;
    if (!options.png.empty()) {
        RenderOptions render;
        render.view = parse_view("top");
        render.num_threads = options.threads;
        parse_size(options.size, render.width, render.height);
        render.colormap = options.png_field == "von-mises" ? Colormap::Viridis : Colormap::CoolWarm;
        const Eigen::VectorXd field = picture_field(fields, options.png_field);
        render.range = robust_range(field, render.colormap);
        picture = render_tessellation(fields.tessellation, field, render);
    }
    if (!options.output.empty()) {
        write_vertex_data(options.output, tessellation_soup(fields.tessellation), field_list(fields));
        out["output"] = options.output;
    }
    if (picture) {
        try {
            write_png(options.png, picture->image);
        } catch (const Error&) {
            if (!options.output.empty()) {
                std::error_code ignored;
                std::filesystem::remove(options.output, ignored);
            }
            throw;
        }
        out["png"] = {{"path", options.png},
                      {"field", options.png_field},
                      {"width", picture->image.width},
                      {"height", picture->image.height},
                      {"range", {picture->range[0], picture->range[1]}}};
    }
    out["field_resolution"] = resolution;
    out["field_points"] = fields.tessellation.num_points();
    return out;
}

void print_matrix(const char* label, const Eigen::Matrix3d& C) {
    for (int i = 0; i < 3; ++i) {
        std::cout << (i == 0 ? label : "            ") << "[" << C(i, 0) << ", " << C(i, 1) << ", " << C(i, 2) << "]\n";
    }
}

void print_text(const nlohmann::json& out, const ElasticityStudy& result) {
    std::cout << std::setprecision(8) << "elasticity  plane " << out["model"].get<std::string>() << ", "
              << out["boundary"].get<std::string>();
    if (!out["macro_deformation"].is_null()) {
        const auto& F = out["macro_deformation"];
        std::cout << ", Fm = [[" << F[0][0] << ", " << F[0][1] << "], [" << F[1][0] << ", " << F[1][1] << "]]";
    }
    std::cout << '\n';
    for (const auto& m : out["materials"]) {
        std::cout << "material    " << m["name"].get<std::string>() << ": E = " << m["E"] << ", nu = " << m["nu"]
                  << " (" << m["faces"] << " faces)\n";
    }
    if (result.cell) {
        std::cout << "cell        [" << result.x0 << ", " << result.x1 << "] x [" << result.y0 << ", " << result.y1
                  << "], " << result.cell->pairs.size() << " periodic pairs, pinned vertex " << result.cell->pinned
                  << '\n';
    }
    for (const ElasticityLevel& level : result.levels) {
        const Eigen::Vector3d& s = level.averages.stress;
        std::cout << "level " << level.level << " (" << level.topology.num_vertices() << " vertices): stress (" << s[0]
                  << ", " << s[1] << ", " << s[2] << "), " << std::setprecision(3) << level.seconds << " s"
                  << std::setprecision(8) << '\n';
        if (level.effective_stiffness) {
            print_matrix("  C*        ", *level.effective_stiffness);
        }
    }
    if (result.bounds) {
        print_matrix("Voigt       ", result.bounds->voigt);
        print_matrix("Reuss       ", result.bounds->reuss);
        if (result.bounds->bulk_hashin_shtrikman) {
            const auto& k = *result.bounds->bulk_hashin_shtrikman;
            std::cout << "HS bulk     [" << k[0] << ", " << k[1] << "]\n";
        }
        if (result.bounds->shear_hashin_shtrikman) {
            const auto& g = *result.bounds->shear_hashin_shtrikman;
            std::cout << "HS shear    [" << g[0] << ", " << g[1] << "]\n";
        }
    }
    if (out.contains("output")) {
        std::cout << "wrote       " << out["output"].get<std::string>() << '\n';
    }
    if (out.contains("png")) {
        std::cout << "wrote       " << out["png"]["path"].get<std::string>() << " (" << out["png"]["field"] << ")\n";
    }
}

int run_elasticity(const ElasticityCommandOptions& options) {
    check_output_paths({options.output, options.png}, {options.input, options.face_materials});
    LIMSURF_CHECK(options.output.empty() || lower_extension(options.output) == ".vtk" ||
                      lower_extension(options.output) == ".vtu",
                  InputError, options.output, ": unknown output format '", lower_extension(options.output),
                  "' (expected .vtk or .vtu)");
    LIMSURF_CHECK(options.png.empty() || lower_extension(options.png) == ".png", InputError, options.png,
                  ": expected a .png file");
    LIMSURF_CHECK(options.output.empty() || options.png.empty() || options.output != options.png, InputError,
                  "-o and --png name the same file");
    ElasticityStudyOptions study = study_options(options);
    std::vector<GroupMaterial> listed;
    for (const std::string& text : options.materials) {
        listed.push_back(parse_group_material(text));
    }
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    const Index num_faces = built.mesh.num_faces();
    const FaceGroups groups =
        options.face_materials.empty() ? built.groups : read_face_groups(options.face_materials, num_faces);
    return naming_file(built.source, {options.face_materials, options.output, options.png}, [&] {
        std::vector<std::string> warnings;
        const MaterialNames names = assign_materials(options, listed, groups, num_faces, study.body, warnings);
        const ElasticityStudy result = solve_elasticity_levels(built.mesh.topology(), built.mesh.positions(), study);
        warnings.insert(warnings.end(), result.warnings.begin(), result.warnings.end());
        print_warnings(warnings);

        nlohmann::json materials = nlohmann::json::array();
        for (std::size_t k = 0; k < study.body.materials.size(); ++k) {
            materials.push_back({{"name", names.names[k]},
                                 {"E", study.body.materials[k].E},
                                 {"nu", study.body.materials[k].nu},
                                 {"faces", names.faces[k]}});
        }
        nlohmann::json levels = nlohmann::json::array();
        for (const ElasticityLevel& level : result.levels) {
            levels.push_back(level_json(level));
        }
        const bool macro = study.boundary != ElasticBoundary::Loaded;
        nlohmann::json out{
            {"input", options.input},
            {"model", to_string(study.body.model)},
            {"boundary", to_string(study.boundary)},
            {"crease_interfaces", study.crease_interfaces},
            {"macro_deformation", macro ? matrix_json(study.macro_deformation) : nlohmann::json(nullptr)},
            {"body_force", {study.body_force[0], study.body_force[1]}},
            {"materials", materials},
            {"quadrature",
             {{"degree", study.quadrature.degree}, {"tile_levels", study.quadrature.subdivide_near_extraordinary}}},
            {"rectangle", {{"x0", result.x0}, {"y0", result.y0}, {"x1", result.x1}, {"y1", result.y1}}},
            {"cell", result.cell ? nlohmann::json{{"pairs", result.cell->pairs.size()}, {"pinned", result.cell->pinned}}
                                 : nlohmann::json(nullptr)},
            {"levels", levels},
            {"bounds", result.bounds ? bounds_json(*result.bounds) : nlohmann::json(nullptr)},
            {"warnings", warnings}};
        require_finite(out);
        if (!options.output.empty() || !options.png.empty()) {
            out.update(write_outputs(options, result, study.body));
        }
        if (options.json) {
            print_json(out);
        } else {
            print_text(out, result);
        }
        return exit_ok;
    });
}

}  // namespace

void add_elasticity_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<ElasticityCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "elasticity",
        "Plane linear elasticity on the limit surface of a planar catmull-clark control mesh: periodic cells "
        "(homogenised stress, effective stiffness), affine or loaded boundaries");
    cmd->add_option("input", options->input, "Planar control mesh (z = 0; .obj with g/usemtl groups, .off, .ply)")
        ->required();
    cmd->add_option("--E", options->E, "Young's modulus of faces without --material (default 1)");
    cmd->add_option("--nu", options->nu, "Poisson's ratio of faces without --material (default 0.3)");
    cmd->add_flag("--plane-stress", options->plane_stress, "Plane stress (a thin sheet; default plane strain)");
    cmd->add_option("--boundary", options->boundary,
                    "periodic (default: fluctuation periodic between opposite sides), affine "
                    "(u = (Fm - I) x on the boundary) or loaded (--clamp, --traction)")
        ->check(CLI::IsMember({"periodic", "affine", "loaded"}));
    cmd->add_flag("--periodic", options->periodic, "Same as --boundary periodic (the default)");
    cmd->add_option("--macro-strain,--macro-deformation", options->macro_strain,
                    "Macroscopic deformation gradient Fm by rows, 'F11,F12;F21,F22' (default '1,0.05;0.05,1')");
    cmd->add_option("--material", options->materials,
                    "NAME:E,NU: the faces of group NAME (OBJ g/usemtl, or an id of --face-materials) get this "
                    "material; repeatable")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_option("--face-materials", options->face_materials,
                    "One group per face, one per line (integers or names), instead of the mesh's groups");
    cmd->add_option("--clamp", options->clamps, "Side left|right|bottom|top held at u = 0 (--boundary loaded)")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_option("--traction", options->tractions,
                    "SIDE:TX,TY: a uniform traction (force per length) on a side (--boundary loaded); repeatable")
        ->allow_extra_args(false)
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    cmd->add_option("--body-force", options->body_force, "FX,FY: force per area on the whole body");
    cmd->add_option("--levels", options->levels, "Also solve on the control mesh refined 1..L times (0..6)")
        ->check(CLI::Range(0, 6));
    cmd->add_option("--quadrature", options->quadrature, "Quadrature degree per tile (1..60, default 6)")
        ->check(CLI::Range(1, 60));
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--no-stiffness", options->no_stiffness, "Skip the effective stiffness (three solves per level)");
    cmd->add_flag("--crease-interfaces", options->crease_interfaces,
                  "Tag the edges between faces of different materials as infinitely sharp creases (the displacement "
                  "may kink there: much faster convergence; the interface becomes the B-spline of its control "
                  "vertices)");
    cmd->add_option("-o,--output", options->output,
                    "Write the finest level's fields on its limit tessellation (.vtk, .vtu): displacement, strain, "
                    "stress, von_mises, material");
    cmd->add_option("--png", options->png, "Picture of a field on the limit surface, seen from the top (.png)");
    cmd->add_option("--png-field", options->png_field, "sxx (default), syy, sxy, von-mises, ux or uy")
        ->check(CLI::IsMember({"sxx", "syy", "sxy", "von-mises", "ux", "uy"}));
    cmd->add_option("--resolution", options->resolution,
                    "Segments per ptex face side of the field tessellation (1..64; default: about 100000 points)")
        ->check(CLI::Range(1, 64));
    cmd->add_option("--size", options->size, "Picture size WIDTHxHEIGHT, 16..8192 each (default 1200x1000)")
        ->check(size_validator());
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_elasticity(*options); }); });
}

}  // namespace limsurf::cli
