// limsurf membrane MESH --scheme c2g0|loop|catmull-clark --area A0 (--volume V0 | --reduced-volume v0)
//   [--mean-curvature M0 | --reduced-mean-curvature m0] [--spontaneous-curvature H0]
//   [--regularize-harmonic EPS [--regularization-hessian H]] [--max-iterations K] [--tolerance T]
//   [--hessian limited-memory|exact] [--continuation K] [--degree D] [--threads N]
//   -o OUT.obj [--field-output OUT.vtk] [--resolution N] [--intersection-resolution N] [--json]
// limsurf membrane MESH --scheme S --evaluate-only [--spontaneous-curvature H0] [--field-output OUT.vtk] [--json]:
// biomembrane shapes (c2g0-sphere-scheme-biomembranes §3; apps/membrane.h, docs/guide/membrane.md):
// the Canham or Helfrich problem (3.1) with hard constraints from the input mesh as initial guess,
// optionally followed by the harmonic-energy regularisation (3.12); or the shape functionals of the
// input. A progress line per solver iteration goes to stderr, the summary to stdout.
//
// A solve that does not converge is not an error (there is no convention for it among the other
// commands, whose solvers are direct): exit 0, "converged": false with the residuals in the JSON,
// a warning on stderr, and the last iterate (finite) written. Every run also reports whether the
// limit surface passes through itself (apps/self_intersection.h; a warning after a solve when it does:
// the shape is then no membrane, whatever its energy).
#include "limsurf/apps/membrane.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
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
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/apps/self_intersection.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/render/tessellation.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct MembraneCommandOptions {
    std::string input;
    std::string scheme;
    std::optional<double> area;
    std::optional<double> volume;
    std::optional<double> reduced_volume;
    std::optional<double> mean_curvature;
    std::optional<double> reduced_mean_curvature;
    std::optional<double> spontaneous_curvature;
    std::optional<double> regularize_harmonic;
    int max_iterations = 1000;
    double tolerance = 1e-8;
    double objective_tolerance = 1e-7;
    std::string hessian = "limited-memory";
    std::string regularization_hessian;  // empty: --hessian's
    int continuation_steps = 1;
    int degree = 8;
    int threads = 0;
    bool evaluate_only = false;
    bool dense_kernels = false;  ///< --no-sum-factorisation
    std::string output;
    std::string field_output;
    int resolution = 0;               // 0: automatic, about field_points points
    int intersection_resolution = 0;  // 0: automatic (SelfIntersectionOptions)
    bool json = false;
};

/// Points of the --field-output tessellation by default: fine enough to see curvature in ParaView,
/// small enough for an ASCII file of a few megabytes.
constexpr Index field_points = 100000;

/// JSON null for an absent value.
nlohmann::json optional_json(const std::optional<double>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

/// The functionals of one surface, under the names of limsurf.shape_functionals in Python.
nlohmann::json values_json(const ShapeValues& values, const std::optional<double>& spontaneous_curvature) {
    nlohmann::json out{{"area", values.area},
                       {"volume", values.volume},
                       {"mean_curvature", values.mean_curvature},
                       {"willmore", values.willmore},
                       {"gaussian", values.gaussian},
                       {"harmonic", values.harmonic},
                       {"reduced_volume", values.reduced_volume()},
                       {"reduced_mean_curvature", values.reduced_mean_curvature()}};
    if (spontaneous_curvature) {
        out["helfrich"] = values.helfrich(*spontaneous_curvature);
    }
    return out;
}

/// One stage: the functionals reached, the targets, the residuals and the solver's report.
nlohmann::json stage_json(const MembraneProblem& problem, const MembraneResult& result,
                          const std::optional<double>& spontaneous_curvature) {
    nlohmann::json out = values_json(result.values, spontaneous_curvature);
    const std::optional<double> volume = problem.volume;
    const std::optional<double> mean = problem.mean_curvature;
    out["objective"] = to_string(problem.objective);
    out["objective_value"] = result.objective;
    out["targets"] = {
        {"area", problem.area},
        {"volume", optional_json(volume)},
        {"reduced_volume", volume ? nlohmann::json(*volume / volume_from_reduced(1.0, problem.area)) : nullptr},
        {"mean_curvature", optional_json(mean)},
        {"reduced_mean_curvature",
         mean ? nlohmann::json(*mean / mean_curvature_from_reduced(1.0, problem.area)) : nullptr}};
    out["residuals"] = {{"area", result.area_residual},
                        {"volume", volume ? nlohmann::json(result.volume_residual) : nullptr},
                        {"mean_curvature", mean ? nlohmann::json(result.mean_curvature_residual) : nullptr}};
    if (problem.willmore_bound) {
        out["targets"]["willmore_bound"] = *problem.willmore_bound;
        out["residuals"]["willmore_excess"] = result.willmore_excess;
    }
    out["max_relative_residual"] = max_relative_residual(problem, result);
    out["iterations"] = result.iterations;
    out["seconds"] = result.seconds;
    out["converged"] = result.converged;
    out["projected"] = result.projected;
    out["status"] = result.status;
    return out;
}

/// Whether the limit surface of @p X passes through itself, and where.
nlohmann::json self_intersection_json(const MembraneCommandOptions& options, const LimitBasis& basis, const Points& X) {
    SelfIntersectionOptions check;
    check.resolution = options.intersection_resolution;
    check.num_threads = options.threads;
    const SelfIntersections found = limit_self_intersections(basis, X, check);
    return {{"intersects", found.intersects()},
            {"intersecting_pairs", found.intersecting_pairs},
            {"control_faces", found.control_faces},
            {"resolution", found.resolution},
            {"triangles", found.triangles}};
}

void print_self_intersection_text(const nlohmann::json& s) {
    std::cout << "  self-intersection: ";
    if (s.at("intersects").get<bool>()) {
        std::cout << "YES, " << s.at("intersecting_pairs") << " triangle pairs over " << s.at("control_faces").size()
                  << " control faces";
    } else {
        std::cout << "none";
    }
    std::cout << " (tessellation of " << s.at("triangles") << " triangles, resolution " << s.at("resolution") << ")\n";
}

MembraneRequest request_of(const MembraneCommandOptions& options) {
    LIMSURF_CHECK(options.area.has_value(), InputError, "--area is required (except with --evaluate-only)");
    LIMSURF_CHECK(!options.output.empty(), InputError,
                  "-o OUT.obj is required: where to write the optimised control mesh");
    MembraneRequest request;
    request.area = *options.area;
    request.volume = options.volume;
    request.reduced_volume = options.reduced_volume;
    request.mean_curvature = options.mean_curvature;
    request.reduced_mean_curvature = options.reduced_mean_curvature;
    request.spontaneous_curvature = options.spontaneous_curvature;
    request.regularize_harmonic = options.regularize_harmonic;
    request.max_iterations = options.max_iterations;
    request.tolerance = options.tolerance;
    request.objective_tolerance = options.objective_tolerance;
    request.hessian = parse_membrane_hessian(options.hessian);
    request.continuation_steps = options.continuation_steps;
    if (!options.regularization_hessian.empty()) {
        request.regularization_hessian = parse_membrane_hessian(options.regularization_hessian);
    }
    return request;
}

/// Checks the output paths before any work: not an input, a format limsurf writes.
void check_outputs(const MembraneCommandOptions& options) {
    check_output_paths({options.output, options.field_output}, {options.input});
    if (!options.output.empty()) {
        (void)output_format(options.output, "");
    }
    if (!options.field_output.empty()) {
        const std::string ext = lower_extension(options.field_output);
        LIMSURF_CHECK(ext == ".vtk" || ext == ".vtu", InputError, options.field_output, ": unknown field format '", ext,
                      "' (expected .vtk or .vtu)");
    }
}

/// The limit surface of @p X as triangles with the mean and Gaussian curvature at each point.
struct FieldSurface {
    PolygonSoup soup;
    std::vector<VertexField> fields;
};

FieldSurface field_surface(const LimitBasis& basis, const Points& X, int resolution, int threads) {
    TessellationOptions tess;
    tess.num_threads = threads;
    tess.resolution = resolution > 0 ? resolution : automatic_resolution(basis, field_points);
    const LimitTessellation t = tessellate_limit_surface(basis, X, tess);
    FieldSurface out;
    out.soup.positions = t.positions;
    for (Index i = 0; i < t.num_triangles(); ++i) {
        for (int k = 0; k < 3; ++k) {
            out.soup.face_vertices.push_back(t.triangles(i, k));
        }
        out.soup.face_offsets.push_back(static_cast<Index>(out.soup.face_vertices.size()));
    }
    out.fields = {{"mean_curvature", t.mean_curvature}, {"gaussian_curvature", t.gaussian_curvature}};
    return out;
}

/// Writes the mesh, then the fields; the mesh is removed again when the fields cannot be written,
/// so that a failed command leaves no file behind (each write is atomic).
void write_outputs(const MembraneCommandOptions& options, const ControlMesh& mesh,
                   const std::optional<FieldSurface>& surface) {
    if (!options.output.empty()) {
        print_warnings(write_mesh(options.output, mesh));
    }
    if (!surface) {
        return;
    }
    try {
        write_vertex_data(options.field_output, surface->soup, surface->fields);
    } catch (...) {
        if (!options.output.empty()) {
            std::error_code ignored;
            std::filesystem::remove(options.output, ignored);
        }
        throw;
    }
}

void print_progress(MembraneStage stage, const MembraneIteration& it) {
    std::ostringstream line;
    line << std::setprecision(10) << to_string(stage) << " iteration " << std::setw(4) << it.iteration
         << (it.restoration ? "r" : (it.watchdog ? "w" : " ")) << " objective " << it.objective << std::setprecision(3)
         << std::scientific << "  violation " << it.constraint_violation << "  dual " << it.dual_infeasibility
         << "  step " << it.step << '\n';
    std::cerr << line.str() << std::flush;
}

void print_stage_text(const char* title, const nlohmann::json& s) {
    std::cout << std::setprecision(10) << title << ' ' << s.at("objective").get<std::string>() << ", "
              << s.at("iterations") << " iterations, " << std::setprecision(3) << s.at("seconds").get<double>()
              << " s, " << (s.at("converged").get<bool>() ? "converged" : "NOT converged") << " ("
              << s.at("status").get<std::string>() << ")\n"
              << std::setprecision(10) << "  W " << s.at("willmore").get<double>() << "  A "
              << s.at("area").get<double>() << "  V " << s.at("volume").get<double>() << "  M "
              << s.at("mean_curvature").get<double>() << "\n  v " << s.at("reduced_volume").get<double>() << "  m "
              << s.at("reduced_mean_curvature").get<double>() << "  gaussian " << s.at("gaussian").get<double>()
              << "  harmonic " << s.at("harmonic").get<double>() << "\n  max relative residual " << std::setprecision(3)
              << s.at("max_relative_residual").get<double>() << '\n';
}

int evaluate_and_report(const MembraneCommandOptions& options, const ControlMesh& mesh, const LimitBasis& basis,
                        const ShapeFunctionals& functionals) {
    nlohmann::json out{{"scheme", options.scheme},
                       {"vertices", mesh.num_vertices()},
                       {"samples", functionals.num_samples()},
                       {"degree", options.degree},
                       {"sum_factorised_elements", functionals.num_sum_factorised_elements()},
                       {"volume_is_exact", functionals.volume_is_exact()}};
    out.update(values_json(functionals.evaluate(mesh.positions()), options.spontaneous_curvature));
    out["self_intersection"] = self_intersection_json(options, basis, mesh.positions());
    std::optional<FieldSurface> surface;
    if (!options.field_output.empty()) {
        surface = field_surface(basis, mesh.positions(), options.resolution, options.threads);
        out["field_output"] = options.field_output;
    }
    require_finite(out);
    write_outputs(options, mesh, surface);
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << std::setprecision(12) << "membrane    " << options.scheme << ", " << mesh.num_vertices()
              << " vertices, " << functionals.num_samples() << " samples\n";
    for (const char* key : {"area", "volume", "mean_curvature", "willmore", "gaussian", "harmonic", "reduced_volume",
                            "reduced_mean_curvature", "helfrich"}) {
        if (out.contains(key)) {
            std::cout << "  " << std::left << std::setw(24) << key << std::right << out.at(key).get<double>() << '\n';
        }
    }
    std::cout << "  (volume " << (functionals.volume_is_exact() ? "exact, trilinear forms" : "by quadrature") << ")\n";
    print_self_intersection_text(out["self_intersection"]);
    if (!options.field_output.empty()) {
        std::cout << "wrote       " << options.field_output << '\n';
    }
    return exit_ok;
}

int solve_and_report(const MembraneCommandOptions& options, const MembraneRequest& request, const ControlMesh& mesh,
                     const LimitBasis& basis, const ShapeFunctionals& functionals) {
    const MembraneRun run = solve_membrane_problem(functionals, mesh.positions(), request,
                                                   [](MembraneStage stage, const MembraneIteration& it) {
                                                       print_progress(stage, it);
                                                       return true;
                                                   });
    nlohmann::json out{{"scheme", options.scheme},
                       {"vertices", mesh.num_vertices()},
                       {"unknowns", 3 * mesh.num_vertices()},
                       {"samples", functionals.num_samples()},
                       {"degree", options.degree},
                       {"sum_factorised_elements", functionals.num_sum_factorised_elements()},
                       {"volume_is_exact", functionals.volume_is_exact()},
                       {"hessian", options.hessian},
                       {"initial_area", run.initial_area},
                       {"scale", run.scale},
                       {"spontaneous_curvature", optional_json(request.spontaneous_curvature)}};
    out.update(stage_json(run.problem, run.shape, request.spontaneous_curvature));
    out["continuation"] = nlohmann::json::array();
    for (const MembraneContinuationStep& step : run.continuation) {
        out["continuation"].push_back(stage_json(step.problem, step.result, request.spontaneous_curvature));
    }
    out["regularization"] = nullptr;
    if (run.regularization) {
        out["regularization"] =
            stage_json(*run.regularization_problem, *run.regularization, request.spontaneous_curvature);
        out["regularization"]["epsilon"] = *request.regularize_harmonic;
        out["regularization"]["hessian"] = to_string(request.regularization_hessian.value_or(request.hessian));
    }
    out["output"] = options.output;
    const MembraneResult& answer = run.final_result();
    out["self_intersection"] = self_intersection_json(options, basis, answer.positions);
    std::optional<FieldSurface> surface;
    if (!options.field_output.empty()) {
        surface = field_surface(basis, answer.positions, options.resolution, options.threads);
        out["field_output"] = options.field_output;
    }
    require_finite(out);  // before anything is written
    write_outputs(options, mesh.with_positions(answer.positions), surface);
    // What the file holds when a stage stopped short: its last iterate, or a feasible point it met.
    const auto held = [](const MembraneResult& r) {
        return r.projected ? "a point that meets the constraints (see the status), not a minimiser"
                           : "its last iterate; see the residuals";
    };
    if (!run.shape.converged) {
        print_warnings({"the solver did not converge (" + run.shape.status + "): '" + options.output + "' holds " +
                        held(run.shape)});
        if (request.regularize_harmonic) {
            print_warnings({"the harmonic regularisation (3.12) was not run: it starts from a converged shape"});
        }
    } else if (run.regularization && !run.regularization->converged) {
        print_warnings({"the harmonic regularisation did not converge (" + run.regularization->status + "): '" +
                        options.output + "' holds " + held(*run.regularization)});
    }
    if (out["self_intersection"]["intersects"].get<bool>()) {
        print_warnings({"the limit surface of '" + options.output + "' passes through itself (" +
                        std::to_string(out["self_intersection"]["intersecting_pairs"].get<std::size_t>()) +
                        " triangle pairs of its tessellation meet; see \"self_intersection\" in the JSON)"});
    }
    if (options.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << "membrane    " << options.scheme << ", " << mesh.num_vertices() << " vertices ("
              << 3 * mesh.num_vertices() << " unknowns), initial guess scaled by " << std::setprecision(6) << run.scale
              << '\n';
    if (!run.continuation.empty()) {
        int iterations = 0;
        for (const MembraneContinuationStep& step : run.continuation) {
            iterations += step.result.iterations;
        }
        std::cout << "continued   in " << run.continuation.size() + 1 << " steps, the first " << run.continuation.size()
                  << " taking " << iterations << " iterations\n";
    }
    print_stage_text("shape      ", out);
    if (run.regularization) {
        print_stage_text("regularized", out["regularization"]);
    }
    print_self_intersection_text(out["self_intersection"]);
    std::cout << "wrote       " << options.output << '\n';
    if (!options.field_output.empty()) {
        std::cout << "wrote       " << options.field_output << '\n';
    }
    return exit_ok;
}

int run_membrane(const MembraneCommandOptions& options) {
    check_outputs(options);
    std::optional<MembraneRequest> request;
    if (!options.evaluate_only) {
        request = request_of(options);
        (void)membrane_problem(*request);        // a bad request fails before the mesh is read
    } else if (options.spontaneous_curvature) {  // what membrane_problem checks of a request
        LIMSURF_CHECK(std::isfinite(*options.spontaneous_curvature), InputError,
                      "--spontaneous-curvature: H0 must be a finite number, not ", *options.spontaneous_curvature);
    }
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    return naming_file(built.source, {options.output, options.field_output}, [&] {
        LimitSchemeOptions limit_options;
        limit_options.scheme = options.scheme;
        const LimitBasis basis = make_limit_basis(built.mesh, limit_options);
        ShapeOptions shape;
        shape.degree = options.degree;
        shape.num_threads = options.threads;
        shape.sum_factorisation = !options.dense_kernels;
        const ShapeFunctionals functionals(basis, shape);
        if (options.evaluate_only) {
            return evaluate_and_report(options, built.mesh, basis, functionals);
        }
        return solve_and_report(options, *request, built.mesh, basis, functionals);
    });
}

}  // namespace

void add_membrane_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<MembraneCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "membrane",
        "Biomembrane shapes: minimise the bending energy under hard area/volume[/mean curvature] constraints "
        "(Canham, Helfrich; optional harmonic regularisation), or evaluate the shape functionals");
    cmd->footer("The input mesh is the initial guess; it is first scaled about the centroid of its control points so "
                "that its limit area is A0. Progress (one line per iteration) goes to stderr. A solve that does not "
                "converge exits 0 with \"converged\": false in the JSON and a warning. See docs/guide/membrane.md.");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply): closed, the initial guess")->required();
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme: c2g0, loop or catmull-clark")
        ->required()
        ->check(CLI::IsMember(names_of(limit_schemes())));
    CLI::Option* area = cmd->add_option("--area", options->area, "Target area A0 (> 0)");
    CLI::Option* volume = cmd->add_option("--volume", options->volume, "Target enclosed volume V0");
    CLI::Option* reduced_volume = cmd->add_option("--reduced-volume", options->reduced_volume,
                                                  "Target reduced volume v0 = V0 / ((4pi/3)(A0/4pi)^(3/2)), in (0, 1]");
    volume->excludes(reduced_volume);
    CLI::Option* mean = cmd->add_option("--mean-curvature", options->mean_curvature,
                                        "Also constrain the total mean curvature M = int H dA to M0 (Helfrich)");
    CLI::Option* reduced_mean =
        cmd->add_option("--reduced-mean-curvature", options->reduced_mean_curvature,
                        "Also constrain the reduced total mean curvature m = M / (4pi (A0/4pi)^(1/2)) to m0");
    mean->excludes(reduced_mean);
    cmd->add_option("--spontaneous-curvature", options->spontaneous_curvature,
                    "Minimise the Helfrich energy int (H - H0)^2 dA instead of W = int H^2 dA");
    CLI::Option* regularize =
        cmd->add_option("--regularize-harmonic", options->regularize_harmonic,
                        "Then minimise the harmonic energy s.t. the same constraints and W <= W0 + EPS (3.12)");
    CLI::Option* iterations =
        cmd->add_option("--max-iterations", options->max_iterations, "Solver iterations per stage (default 1000)");
    CLI::Option* tolerance =
        cmd->add_option("--tolerance", options->tolerance, "Relative KKT tolerance of the solver (default 1e-8)");
    CLI::Option* objective_tolerance = cmd->add_option(
        "--objective-tolerance", options->objective_tolerance,
        "Also converged when the objective's relative change stays below this for 15 iterations with the "
        "constraints met (default 1e-7; 0: the KKT tolerance only)");
    CLI::Option* hessian =
        cmd->add_option("--hessian", options->hessian,
                        "Second derivatives of the solver: limited-memory (BFGS from the gradients) or exact "
                        "(Newton steps; docs/membrane.md)")
            ->check(CLI::IsMember({"limited-memory", "exact"}));
    CLI::Option* regularization_hessian =
        cmd->add_option("--regularization-hessian", options->regularization_hessian,
                        "The same for the regularisation (3.12) only (default: --hessian's)")
            ->check(CLI::IsMember({"limited-memory", "exact"}));
    regularization_hessian->needs(regularize);
    CLI::Option* continuation =
        cmd->add_option("--continuation", options->continuation_steps,
                        "Reach the volume (and mean curvature) targets in K steps from the start's, each a solve "
                        "from the last (default 1: at once; docs/guide/membrane.md)")
            ->check(CLI::Range(1, max_continuation_steps));
    cmd->add_option("--degree", options->degree, "Quadrature degree per tile (default 8)");
    cmd->add_flag("--no-sum-factorisation", options->dense_kernels,
                  "Evaluate regular Catmull-Clark faces through their dense kernels as every other face (for "
                  "checking; the same numbers to rounding, slower)");
    add_threads_option(cmd, options->threads);
    CLI::Option* evaluate = cmd->add_flag(
        "--evaluate-only", options->evaluate_only,
        "Print the shape functionals of the input (no scaling, no solve); with --spontaneous-curvature also "
        "the Helfrich energy");
    CLI::Option* output =
        cmd->add_option("-o,--output", options->output, "The optimised control mesh (.obj, .off, .ply)");
    cmd->add_option("--field-output", options->field_output,
                    "The limit surface as triangles with mean_curvature and gaussian_curvature per point (.vtk, .vtu)");
    cmd->add_option("--resolution", options->resolution,
                    "Segments per ptex face edge of --field-output (1..256; default: about 100000 points)")
        ->check(CLI::Range(1, 256));
    cmd->add_option("--intersection-resolution", options->intersection_resolution,
                    "Segments per ptex face edge of the tessellation the self-intersection check searches "
                    "(1..256; default: about 40000 points)")
        ->check(CLI::Range(1, 256));
    for (CLI::Option* solve_only : {area, volume, reduced_volume, mean, reduced_mean, regularize, iterations, tolerance,
                                    objective_tolerance, hessian, regularization_hessian, continuation, output}) {
        evaluate->excludes(solve_only);
    }
    cmd->add_flag("--json", options->json, "Print JSON on stdout (progress still goes to stderr)");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_membrane(*options); }); });
}

}  // namespace limsurf::cli
