// limsurf poisson MESH --scheme S --method M [--level L] (--rhs EXPR | --rhs-file FILE)
//   [--boundary-value EXPR] [--reference-level K] [--max-memory SIZE] [--threads N]
//   [-o OUT.ply|.vtk|.vtu] [--json]:
// solves −Δu = f on the limit surface with the inner products of --method (dec, decsnap, sec,
// secsnap; SEC §3) or with --method iga, Galerkin with the limit basis (fem/galerkin.h), all
// unknowns on the control mesh. With --reference-level K it also solves with
// DEC on the K-times subdivided mesh (the paper's reference construction) and reports the L² and
// L∞ differences of the subdivided solution from it.
#include "limsurf/apps/poisson.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "formula.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct PoissonCommandOptions {
    std::string input;
    std::string scheme;
    std::string method = "sec";
    int level = 3;
    bool lumped = false;
    int degree = 8;  // iga: quadrature degree per tile
    int tiles = 6;   // iga: tile levels towards extraordinary vertices
    std::string rhs;
    std::string rhs_file;
    std::string boundary_value = "0";
    int reference_level = -1;
    std::string max_memory;
    std::string output;
    int threads = 0;
    bool json = false;
};

int solve_and_report(const BuildResult& built, const PoissonCommandOptions& options) {
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    LimitSchemeOptions limit_options;
    limit_options.scheme = options.scheme;
    SurfacePoissonOptions poisson;
    poisson.method = parse_laplacian_method(options.method);
    LIMSURF_CHECK(poisson.method != LaplacianMethod::Iga || !options.lumped, InputError,
                  "--lumped applies to the inner products of dec and sec, not to iga");
    poisson.level = options.level;
    poisson.lumped = options.lumped;
    poisson.degree = options.degree;
    poisson.tiles = options.tiles;
    poisson.num_threads = options.threads;
    poisson.scheme_options = scheme_rules(mesh, limit_options);
    if (options.reference_level >= 0) {
        LIMSURF_CHECK(options.rhs_file.empty(), InputError,
                      "--reference-level needs --rhs (a formula to evaluate on the fine mesh)");
        poisson.reference_level = options.reference_level;
    }
    poisson.max_memory = memory_budget(options.max_memory);
    SurfacePoissonData data;
    if (!options.rhs_file.empty()) {
        data.f_values = read_vertex_values(options.rhs_file, t.num_vertices());
    } else {
        data.f = [&](const Points& P) { return evaluate_formula("--rhs", options.rhs, P); };
    }
    data.boundary = [&](const Points& P) { return evaluate_formula("--boundary-value", options.boundary_value, P); };
    const SurfacePoissonResult result = solve_surface_poisson(mesh, limit_schemes().at(options.scheme), poisson, data);
    const PoissonSolution& solution = result.solution;
    const std::optional<ReferenceComparison>& reference = result.reference;
    const bool iga = poisson.method == LaplacianMethod::Iga;
    const Eigen::VectorXd& u = solution.u;
    const bool sec = poisson.method == LaplacianMethod::Sec || poisson.method == LaplacianMethod::SecSnap;
    nlohmann::json out{{"scheme", options.scheme},
                       {"method", options.method},
                       {"level", sec ? options.level : 0},
                       {"lumped", options.lumped},
                       {"vertices", t.num_vertices()},
                       {"closed", t.is_closed()},
                       {"solver", solution.solver},
                       {"residual", solution.residual},
                       {"mean_removed", solution.mean_removed},
                       {"quadrature", iga ? nlohmann::json{{"degree", options.degree}, {"tiles", options.tiles}}
                                          : nlohmann::json(nullptr)},
                       {"u_min", u.minCoeff()},
                       {"u_max", u.maxCoeff()}};
    if (reference) {
        out["reference"] = {{"level", reference->level},
                            {"method", "dec"},
                            {"vertices", reference->vertices},
                            {"l2_relative", reference->l2},
                            {"linf_relative", reference->linf}};
    }
    if (!options.output.empty()) {
        out["output"] = options.output;
    }
    require_finite(out);  // before anything is written
    if (!options.output.empty()) {
        const std::vector<VertexField> fields{{"u", solution.u}, {"f", result.f}};
        write_vertex_data(options.output, to_polygon_soup(mesh), fields);
    }
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << std::setprecision(6) << "poisson     " << options.method
              << (sec ? " level " + std::to_string(options.level) : std::string())
              << (options.lumped ? " (lumped)" : "") << ", " << t.num_vertices() << " unknowns, " << solution.solver
              << "\nresidual    " << solution.residual << "\nu           min " << u.minCoeff() << "  max "
              << u.maxCoeff() << '\n';
    if (t.is_closed()) {
        std::cout << "mean of f   " << solution.mean_removed << " (removed: a closed surface needs ∫f = 0)\n";
    }
    if (reference) {
        std::cout << "reference   dec on level " << reference->level << " (" << reference->vertices
                  << " vertices): relative L2 " << reference->l2 << ", relative Linf " << reference->linf << '\n';
    }
    if (!options.output.empty()) {
        std::cout << "wrote       " << options.output << '\n';
    }
    return exit_ok;
}

int run_poisson(const PoissonCommandOptions& options) {
    check_output_paths({options.output}, {options.input, options.rhs_file});
    if (options.rhs_file.empty()) {
        check_formula("--rhs", options.rhs);
    }
    check_formula("--boundary-value", options.boundary_value);  // also on a closed mesh, which does not use it
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.rhs_file, options.output},
                       [&] { return solve_and_report(built, options); });
}

}  // namespace

void add_poisson_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<PoissonCommandOptions>();
    CLI::App* cmd =
        app.add_subcommand("poisson", "Solve -Δu = f on the limit surface with DEC, SEC (SEC §3) or IGA (Galerkin)");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme")
        ->required()
        ->check(CLI::IsMember({"loop", "catmull-clark", "c2g0"}));
    add_laplacian_method_options(cmd, options->method, options->level);
    add_iga_quadrature_options(cmd, options->degree, options->tiles);
    cmd->add_flag("--lumped", options->lumped, "Lump M0 (and M2): diag(M 1) (SEC §3.5)");
    auto* rhs = cmd->add_option("--rhs", options->rhs, "Right-hand side f(x, y, z), a formula (muParser; pi known)");
    auto* rhs_file = cmd->add_option("--rhs-file", options->rhs_file, "Right-hand side: one value per vertex");
    rhs->excludes(rhs_file);
    cmd->add_option("--boundary-value", options->boundary_value,
                    "Dirichlet values g(x, y, z) at the boundary vertices of open meshes (default 0)");
    cmd->add_option("--reference-level", options->reference_level,
                    "Also solve with DEC on the K-times subdivided mesh and report the differences (0..7)")
        ->check(CLI::Range(0, 7));
    add_memory_option(cmd, options->max_memory);
    add_threads_option(cmd, options->threads);
    cmd->add_option("-o,--output", options->output, "Write the control mesh with fields u and f (.ply, .vtk, .vtu)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, cmd, &status] {
        status.exit_code = run_guarded([&] {
            check_method_options(*cmd, options->method);
            LIMSURF_CHECK(!options->rhs.empty() || !options->rhs_file.empty(), InputError,
                          "poisson needs --rhs or --rhs-file");
            return run_poisson(*options);
        });
    });
}

}  // namespace limsurf::cli
