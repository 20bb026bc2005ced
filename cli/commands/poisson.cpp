// limsurf poisson MESH --scheme S --method M [--level L] (--rhs EXPR | --rhs-file FILE)
//   [--boundary-value EXPR] [--reference-level K] [--max-memory SIZE] [-o OUT.ply|.vtk|.vtu] [--json]:
// solves −Δu = f on the limit surface with the inner products of --method (dec, decsnap, sec,
// secsnap; SEC §3) or with --method iga, Galerkin with the limit basis (fem/galerkin.h), all
// unknowns on the control mesh. With --reference-level K it also solves with
// DEC on the K-times subdivided mesh (the paper's reference construction) and reports the L² and
// L∞ differences of the subdivided solution from it.
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "formula.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/sec/operators.h"
#include "limsurf/sec/reference_solution.h"
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
    bool json = false;
};

int solve_and_report(const BuildResult& built, const PoissonCommandOptions& options) {
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    const SchemeKind scheme = limit_schemes().at(options.scheme);
    LimitSchemeOptions limit_options;
    limit_options.scheme = options.scheme;
    const SchemeOptions rules = scheme_rules(mesh, limit_options);
    const bool iga = options.method == "iga";
    LIMSURF_CHECK(!iga || !options.lumped, InputError,
                  "--lumped applies to the inner products of dec and sec, not to iga");
    InnerProductOptions ip;
    if (!iga) {
        ip.method = parse_inner_product_method(options.method);
    }
    ip.level = options.level;
    ip.lumped = options.lumped;
    const auto rhs = [&](const Points& P) { return evaluate_formula("--rhs", options.rhs, P); };
    const auto boundary = [&](const Points& P) {
        return evaluate_formula("--boundary-value", options.boundary_value, P);
    };

    ReferenceProblem reference_problem{options.reference_level, rhs, boundary, rules,
                                       memory_budget(options.max_memory)};
    if (options.reference_level >= 0) {
        // A reference that cannot be had is refused now, not after the main solve.
        LIMSURF_CHECK(options.rhs_file.empty(), InputError,
                      "--reference-level needs --rhs (a formula to evaluate on the fine mesh)");
        check_reference(t, scheme, reference_problem);
    }
    PoissonProblem problem;
    if (t.has_boundary()) {
        problem.boundary_values = boundary(mesh.positions());
    }
    PoissonSolution solution;
    if (iga) {
        // Galerkin with the limit basis (docs/fem.md): f integrated at the quadrature points of the
        // limit surface; a per-vertex f is taken as control values, f_h = Σ f_i φ_i.
        const LimitBasis basis = make_limit_basis(mesh, limit_options);
        const LimitSampler sampler(basis, SamplerOptions{options.degree, options.tiles, 0});
        const GalerkinMatrices matrices = assemble_laplace_beltrami(sampler, mesh.positions());
        Eigen::VectorXd load;
        if (!options.rhs_file.empty()) {
            problem.f = read_vertex_values(options.rhs_file, t.num_vertices());
            load = matrices.mass * problem.f;
        } else {
            problem.f = rhs(mesh.positions());
            load = galerkin_load(sampler, mesh.positions(), rhs);
        }
        GalerkinPoissonSolution g = solve_galerkin_poisson(t, matrices, load, problem.boundary_values);
        solution.u = std::move(g.u);
        solution.residual = g.residual;
        solution.mean_removed = g.mean_removed;
        solution.solver = g.solver;
    } else {
        // Refuse what the scheme or the form rules cannot do before evaluating anything.
        const Operators ops(t, control_inner_products(t, mesh.positions(), scheme, ip, rules));
        if (!options.rhs_file.empty()) {
            problem.f = read_vertex_values(options.rhs_file, t.num_vertices());
        } else {
            problem.f = rhs(mesh.positions());
            // Integrate f where the inner products live (level L for sec), not at the control points.
            problem.load = load_vector(t, mesh.positions(), scheme, ip, rhs, rules);
        }
        solution = solve_poisson(t, ops, problem);
    }
    std::optional<ReferenceComparison> reference;
    if (options.reference_level >= 0) {
        reference = compare_with_reference(t, mesh.positions(), scheme, reference_problem, solution.u);
    }
    const Eigen::VectorXd& u = solution.u;
    const bool sec = !iga && (ip.method == InnerProductMethod::Sec || ip.method == InnerProductMethod::SecSnap);
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
        const std::vector<VertexField> fields{{"u", solution.u}, {"f", problem.f}};
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
    if (!options.output.empty()) {
        refuse_overwriting_inputs(options.output, {options.input, options.rhs_file});
    }
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
    cmd->add_option("--method", options->method,
                    "dec, decsnap, sec, secsnap (inner products, default sec) or iga (Galerkin with the limit basis)")
        ->check(CLI::IsMember({"dec", "decsnap", "sec", "secsnap", "iga"}));
    cmd->add_option("--degree", options->degree, "iga: quadrature degree per tile (1..60, default 8)")
        ->check(CLI::Range(1, 60));
    cmd->add_option("--tiles", options->tiles, "iga: tile levels towards extraordinary vertices (0..20, default 6)")
        ->check(CLI::Range(0, 20));
    cmd->add_option("--level", options->level, "Subdivision level L of sec and secsnap (0..8, default 3)")
        ->check(CLI::Range(0, 8));
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
    cmd->add_option("-o,--output", options->output, "Write the control mesh with fields u and f (.ply, .vtk, .vtu)");
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] {
        status.exit_code = run_guarded([&] {
            LIMSURF_CHECK(!options->rhs.empty() || !options->rhs_file.empty(), InputError,
                          "poisson needs --rhs or --rhs-file");
            return run_poisson(*options);
        });
    });
}

}  // namespace limsurf::cli
