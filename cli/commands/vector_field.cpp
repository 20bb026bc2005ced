// limsurf vector-field MESH --scheme S [--method M] [--level L] [--source V:s[:w]]... [--sink V:s[:w]]...
//   [--vorticity F:c[:w]]... [--stroke V0,V1,...:s[:w]]... [--weight W] [--sample-level S]
//   [--reference-level K] [--threads N] [--save-one-form FILE] [-o FIELD.vtk] [--png OUT.png] [--json]:
// designs the smoothest tangent field (Fisher et al. 2007; SEC §4.3) under soft constraints with the inner
// products of --method, and writes it as vectors on the limit surface (apps/vector_field.h).
#include "limsurf/apps/vector_field.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/render/render.h"
#include "limsurf/render/tessellation.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct VectorFieldCommandOptions {
    std::string input;
    LimitSchemeOptions scheme;
    std::string method = "sec";
    int level = 3;
    std::string vertex_mass = "exact";
    std::vector<std::string> sources, sinks, vortices, strokes;
    double weight = 1000.0;
    int sample_level = 2;
    int reference_level = -1;
    std::string save_one_form;
    std::string output;
    std::string png;
    int threads = 0;
    bool json = false;
};

/// "A:B[:C]" split at ':'.
std::vector<std::string> split(const std::string& text, char sep) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    std::string part;
    while (std::getline(in, part, sep)) {
        parts.push_back(part);
    }
    return parts;
}

double number(const std::string& text, const std::string& flag, const std::string& whole) {
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    LIMSURF_CHECK(used == text.size() && !text.empty(), InputError, flag, " '", whole, "': '", text,
                  "' is not a number");
    LIMSURF_CHECK(std::isfinite(value), InputError, flag, " '", whole, "': '", text, "' is not a finite number");
    return value;
}

Index index_of(const std::string& text, const std::string& flag, const std::string& whole) {
    const double v = number(text, flag, whole);
    LIMSURF_CHECK(v == static_cast<double>(static_cast<long long>(v)) && v >= -1e9 && v <= 1e9, InputError, flag, " '",
                  whole, "': '", text, "' is not an index");
    return static_cast<Index>(v);
}

/// "ELEMENT:VALUE[:WEIGHT]" → (element text, value, weight).
struct Spec {
    std::string element;
    double value = 0.0;
    double weight = 0.0;
};

Spec parse_spec(const std::string& text, const std::string& flag, double default_weight) {
    const std::vector<std::string> parts = split(text, ':');
    LIMSURF_CHECK(parts.size() == 2 || parts.size() == 3, InputError, flag, " '", text,
                  "': expected ELEMENT:VALUE or ELEMENT:VALUE:WEIGHT");
    return Spec{parts[0], number(parts[1], flag, text),
                parts.size() == 3 ? number(parts[2], flag, text) : default_weight};
}

VectorFieldConstraints constraints_of(const VectorFieldCommandOptions& o) {
    VectorFieldConstraints c;
    for (const std::string& s : o.sources) {
        const Spec spec = parse_spec(s, "--source", o.weight);
        c.sources.push_back({index_of(spec.element, "--source", s), spec.value, spec.weight});
    }
    for (const std::string& s : o.sinks) {
        const Spec spec = parse_spec(s, "--sink", o.weight);
        c.sources.push_back({index_of(spec.element, "--sink", s), -spec.value, spec.weight});
    }
    for (const std::string& s : o.vortices) {
        const Spec spec = parse_spec(s, "--vorticity", o.weight);
        c.vortices.push_back({index_of(spec.element, "--vorticity", s), spec.value, spec.weight});
    }
    for (const std::string& s : o.strokes) {
        const Spec spec = parse_spec(s, "--stroke", o.weight);
        StrokeConstraint stroke;
        for (const std::string& v : split(spec.element, ',')) {
            stroke.vertices.push_back(index_of(v, "--stroke", s));
        }
        stroke.strength = spec.value;
        stroke.weight = spec.weight;
        c.strokes.push_back(std::move(stroke));
    }
    return c;
}

/// The limit surface coloured by the vectors' magnitude at the level-S vertices (carried by the limit basis
/// of the level-S mesh, whose limit surface is the same).
/// The picture of --png, in memory: it is drawn before any file is written.
Image draw_picture(const OneFormVectors& v, SchemeKind scheme, const SchemeOptions& rules, int threads) {
    const LimitBasis basis(v.level_topology, scheme, rules);
    TessellationOptions tess;
    tess.resolution = std::max(2, automatic_resolution(basis, 120000));
    tess.curvature = false;
    tess.num_threads = threads;
    const LimitTessellation surface = tessellate_limit_surface(basis, v.level_control_points, tess);
    const Eigen::VectorXd magnitude = v.level_vectors.rowwise().norm();
    RenderOptions render;
    render.width = 900;
    render.height = 700;
    render.num_threads = threads;
    return render_tessellation(surface, evaluate_vertex_field(surface, magnitude), render).image;
}

int design_and_report(const BuildResult& built, const VectorFieldCommandOptions& o) {
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    const SchemeKind scheme = limit_schemes().at(o.scheme.scheme);
    VectorFieldOptions options;
    options.inner_products.method = parse_inner_product_method(o.method);
    options.inner_products.level = o.level;
    options.inner_products.num_threads = o.threads;
    options.vertex_mass = parse_vertex_mass_inverse(o.vertex_mass);
    options.scheme_options = scheme_rules(mesh, o.scheme);
    if (o.reference_level >= 0) {
        options.reference_level = o.reference_level;
    }
    const VectorFieldConstraints constraints = constraints_of(o);
    const VectorFieldResult r = design_vector_field(t, mesh.positions(), scheme, constraints, options);
    const OneFormVectors vectors =
        one_form_vectors(t, mesh.positions(), scheme, r.w, o.sample_level, options.scheme_options);
    const bool sec = uses_subdivision(options.inner_products.method);
    nlohmann::json constraint_list = nlohmann::json::array();
    for (const ConstraintReport& c : r.constraints) {
        constraint_list.push_back({{"kind", c.kind},
                                   {"element", c.element},
                                   {"target", c.target},
                                   {"achieved", c.achieved},
                                   {"weight", c.weight}});
    }
    const Eigen::VectorXd magnitude = vectors.vectors.rowwise().norm();
    nlohmann::json out{{"scheme", o.scheme.scheme},
                       {"method", o.method},
                       {"level", sec ? o.level : 0},
                       {"vertices", t.num_vertices()},
                       {"edges", t.num_edges()},
                       {"faces", t.num_faces()},
                       {"closed", t.is_closed()},
                       {"genus", t.genus()},
                       {"solver", r.solver},
                       {"vertex_mass", o.vertex_mass},
                       {"solver_steps", r.solver_steps},
                       {"energy", r.energy},
                       {"w_norm", r.w.norm()},
                       {"max_residual", r.max_residual},
                       {"source_imbalance", r.source_imbalance},
                       {"vorticity_imbalance", r.vorticity_imbalance},
                       {"constraints", constraint_list},
                       {"warnings", r.warnings},
                       {"samples",
                        {{"level", vectors.level},
                         {"count", vectors.points.rows()},
                         {"fit_residual", vectors.fit_residual},
                         {"magnitude_min", magnitude.minCoeff()},
                         {"magnitude_max", magnitude.maxCoeff()},
                         {"magnitude_mean", magnitude.mean()}}}};
    if (r.reference) {
        out["reference"] = {{"level", r.reference->level},
                            {"method", "dec"},
                            {"edges", r.reference->edges},
                            {"l2_relative", r.reference->l2_relative},
                            {"energy", r.reference->energy}};
    }
    for (const auto& [key, path] : {std::pair{"output", o.output}, {"png", o.png}, {"one_form", o.save_one_form}}) {
        if (!path.empty()) {
            out[key] = path;
        }
    }
    require_finite(out);  // before anything is written
    const std::optional<Image> picture =
        o.png.empty() ? std::nullopt
                      : std::optional<Image>(draw_picture(vectors, scheme, options.scheme_options, o.threads));
    if (!o.save_one_form.empty()) {
        write_values(o.save_one_form, r.w);
    }
    if (!o.output.empty()) {
        write_one_form_vtk(o.output, {{"field", &vectors}});
    }
    if (picture) {
        write_png(o.png, *picture);
    }
    print_warnings(r.warnings);
    if (o.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << std::setprecision(6) << "vector-field " << o.method << (sec ? " level " + std::to_string(o.level) : "")
              << ", " << t.num_edges() << " edges, " << r.solver
              << (r.solver_steps > 0          ? ", exact M0^-1 in " + std::to_string(r.solver_steps) + " CG steps"
                  : o.vertex_mass == "lumped" ? ", lumped M0"
                                              : "")
              << "\nenergy       " << r.energy << "  (anti-holomorphic, ½ wᵀ L1 w)\n";
    for (const ConstraintReport& c : r.constraints) {
        std::cout << "constraint   " << std::left << std::setw(10) << c.kind << std::right
                  << (c.kind == "source"      ? " vertex "
                      : c.kind == "vorticity" ? " face "
                                              : " edge ")
                  << c.element << ": target " << c.target << ", achieved " << c.achieved << '\n';
    }
    std::cout << "residual     " << r.max_residual << " (largest relative misfit)\n"
              << "vectors      " << vectors.points.rows() << " samples on level " << vectors.level << ", |v| "
              << magnitude.minCoeff() << " .. " << magnitude.maxCoeff() << ", fit residual " << vectors.fit_residual
              << '\n';
    if (r.reference) {
        std::cout << "reference    dec on level " << r.reference->level << " (" << r.reference->edges
                  << " edges): relative L2 " << r.reference->l2_relative << '\n';
    }
    for (const std::string& path : {o.save_one_form, o.output, o.png}) {
        if (!path.empty()) {
            std::cout << "wrote        " << path << '\n';
        }
    }
    return exit_ok;
}

}  // namespace

void add_vector_field_command(CLI::App& app, CommandStatus& status) {
    auto o = std::make_shared<VectorFieldCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "vector-field", "Design a smooth tangent vector field (Fisher et al. 2007) with DEC or SEC (SEC §4.3)");
    cmd->add_option("input", o->input, "Input mesh (.obj, .off, .ply)")->required();
    add_limit_scheme_options(cmd, o->scheme);
    add_inner_product_options(cmd, o->method, o->level);
    cmd->add_option("--vertex-mass", o->vertex_mass,
                    "M0^-1 in the divergence energy: exact (default; conjugate gradients when M0 is not "
                    "diagonal, as for sec) or lumped (diag(M0 1)^-1, one sparse solve)")
        ->check(CLI::IsMember({"exact", "lumped"}));
    cmd->add_option("--source", o->sources, "Source V:s[:w]: divergence s > 0 at vertex V (repeatable)");
    cmd->add_option("--sink", o->sinks, "Sink V:s[:w]: divergence -s at vertex V (repeatable)");
    cmd->add_option("--vorticity", o->vortices, "Vortex F:c[:w]: circulation c around face F (repeatable)");
    cmd->add_option("--stroke", o->strokes,
                    "Stroke V0,V1,...:s[:w]: flow of speed s along a path of edges (repeatable)");
    cmd->add_option("--weight", o->weight, "Default weight of the soft constraints (default 1000)");
    cmd->add_option("--sample-level", o->sample_level,
                    "Level of the faces the vectors are sampled at (0..6, default 2)")
        ->check(CLI::Range(0, 6));
    cmd->add_option("--reference-level", o->reference_level,
                    "Also design with DEC on the K-times subdivided mesh and report the difference (1..6)")
        ->check(CLI::Range(1, 6));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--save-one-form", o->save_one_form, "Write the 1-form: one value per edge, one per line");
    cmd->add_option("-o,--output", o->output, "Write the vectors on the limit surface (.vtk: glyphs, streamlines)");
    cmd->add_option("--png", o->png, "Picture of the limit surface coloured by the field's magnitude (.png)");
    cmd->add_flag("--json", o->json, "Print JSON");
    cmd->callback([o, cmd, &status] {
        status.exit_code = run_guarded([&] {
            check_level_option(*cmd, o->method);
            check_output_paths({o->output, o->png, o->save_one_form}, {o->input});
            const BuildResult built = read_mesh(o->input);
            print_warnings(built.report);
            return naming_file(built.source, {o->output, o->png, o->save_one_form},
                               [&] { return design_and_report(built, *o); });
        });
    });
}

}  // namespace limsurf::cli
