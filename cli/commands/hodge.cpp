// limsurf hodge MESH --scheme S [--method M] [--level L] (--one-form FILE | --random SEED | --field "X;Y;Z")
//   [--reference-level K] [--threads N] [--no-basis] [--sample-level S] [--save-parts PREFIX] [-o PARTS.vtk] [--json]:
// the Helmholtz–Hodge decomposition w = dα + δβ + h of a 1-form in the inner products of --method (SEC §2.3,
// §4.3), the norms of the parts, their orthogonality, and the dimension of the harmonic space found
// numerically against b1 from the Euler characteristic (apps/hodge.h).
#include "limsurf/apps/hodge.h"

#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "formula.h"
#include "limsurf/apps/vector_field.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct HodgeCommandOptions {
    std::string input;
    LimitSchemeOptions scheme;
    std::string method = "sec";
    int level = 3;
    std::string one_form;
    long long random = -1;
    std::string field;
    int reference_level = -1;
    bool no_basis = false;
    int sample_level = 2;
    std::string save_parts;
    std::string output;
    int threads = 0;
    bool json = false;
};

Eigen::VectorXd input_form(const ControlMesh& mesh, const HodgeCommandOptions& o) {
    const Topology& t = mesh.topology();
    if (!o.one_form.empty()) {
        return read_vertex_values(o.one_form, t.num_edges(), ValuesPer::Edge);
    }
    if (o.random >= 0) {
        return random_one_form(t, mesh.positions(), static_cast<std::uint64_t>(o.random));
    }
    std::vector<std::string> parts;
    std::stringstream in(o.field);
    std::string part;
    while (std::getline(in, part, ';')) {
        parts.push_back(part);
    }
    LIMSURF_CHECK(parts.size() == 3, InputError, "--field '", o.field,
                  "': expected three formulas separated by ';' (the x, y and z components)");
    return integrate_one_form(t, mesh.positions(), [&](const Points& P) {
        Points V(P.rows(), 3);
        for (int k = 0; k < 3; ++k) {
            V.col(k) = evaluate_formula("--field", parts[static_cast<std::size_t>(k)], P);
        }
        return V;
    });
}

int decompose_and_report(const BuildResult& built, const HodgeCommandOptions& o) {
    const ControlMesh& mesh = built.mesh;
    const Topology& t = mesh.topology();
    const SchemeKind scheme = limit_schemes().at(o.scheme.scheme);
    HodgeOptions options;
    options.inner_products.method = parse_inner_product_method(o.method);
    options.inner_products.level = o.level;
    options.inner_products.num_threads = o.threads;
    options.scheme_options = scheme_rules(mesh, o.scheme);
    options.basis = !o.no_basis;
    if (o.reference_level >= 0) {
        options.reference_level = o.reference_level;
    }
    const Eigen::VectorXd w = input_form(mesh, o);
    const HodgeResult r = hodge_decomposition(t, mesh.positions(), scheme, w, options);
    const bool sec = uses_subdivision(options.inner_products.method);
    const int b1 =
        t.is_closed() ? static_cast<int>(2 - t.euler_characteristic()) : static_cast<int>(1 - t.euler_characteristic());
    nlohmann::json out{{"scheme", o.scheme.scheme},
                       {"method", o.method},
                       {"level", sec ? o.level : 0},
                       {"vertices", t.num_vertices()},
                       {"edges", t.num_edges()},
                       {"faces", t.num_faces()},
                       {"closed", t.is_closed()},
                       {"genus", r.genus},
                       {"boundary_loops", r.boundary_loops},
                       {"betti_1", b1},
                       {"solver", r.solver},
                       {"norm", r.norm},
                       {"exact_norm", r.exact_norm},
                       {"coexact_norm", r.coexact_norm},
                       {"harmonic_norm", r.harmonic_norm},
                       {"orthogonality",
                        {{"exact_coexact", r.exact_coexact},
                         {"exact_harmonic", r.exact_harmonic},
                         {"coexact_harmonic", r.coexact_harmonic}}},
                       {"sum_residual", r.sum_residual},
                       {"curl_of_exact", r.curl_of_exact},
                       {"divergence_of_coexact", r.divergence_of_coexact},
                       {"harmonic_curl", r.harmonic_curl},
                       {"harmonic_divergence", r.harmonic_divergence}};
    if (r.basis) {
        std::vector<double> eigenvalues(r.basis->gram_eigenvalues.data(),
                                        r.basis->gram_eigenvalues.data() + r.basis->gram_eigenvalues.size());
        out["harmonic_dimension"] = r.basis->dimension;
        out["harmonic_gap"] = r.basis->gap;
        out["gram_eigenvalues"] = eigenvalues;
    }
    if (r.reference) {
        out["reference"] = {{"level", r.reference->level},
                            {"method", "dec"},
                            {"edges", r.reference->edges},
                            {"exact_l2_relative", r.reference->exact},
                            {"coexact_l2_relative", r.reference->coexact},
                            {"harmonic_l2_relative", r.reference->harmonic},
                            {"l2_relative", r.reference->total}};
    }
    if (!o.output.empty()) {
        out["output"] = o.output;
    }
    require_finite(out);  // before anything is written
    // Every output is computed before the first is written: a failure leaves no file behind.
    std::vector<OneFormVectors> sampled;
    if (!o.output.empty()) {
        for (const Eigen::VectorXd* form : {&w, &r.parts.exact, &r.parts.coexact, &r.parts.harmonic}) {
            sampled.push_back(
                one_form_vectors(t, mesh.positions(), scheme, *form, o.sample_level, options.scheme_options));
        }
    }
    if (!o.save_parts.empty()) {
        write_values(o.save_parts + "exact.txt", r.parts.exact);
        write_values(o.save_parts + "coexact.txt", r.parts.coexact);
        write_values(o.save_parts + "harmonic.txt", r.parts.harmonic);
    }
    if (!o.output.empty()) {
        write_one_form_vtk(
            o.output,
            {{"field", &sampled[0]}, {"exact", &sampled[1]}, {"coexact", &sampled[2]}, {"harmonic", &sampled[3]}});
    }
    if (o.json) {
        print_json(out);
        return exit_ok;
    }
    std::cout << std::setprecision(6) << "hodge       " << o.method << (sec ? " level " + std::to_string(o.level) : "")
              << ", " << t.num_edges() << " edges, genus " << r.genus << ", " << r.boundary_loops << " boundary loops, "
              << r.solver << "\nnorms (M1)  |w| " << r.norm << " = |dα| " << r.exact_norm << " (+) |δβ| "
              << r.coexact_norm << " (+) |h| " << r.harmonic_norm << "\northogonal  <dα,δβ> " << r.exact_coexact
              << "  <dα,h> " << r.exact_harmonic << "  <δβ,h> " << r.coexact_harmonic
              << "  (relative to |w|²)\nsum         " << r.sum_residual << "\nidentities  d1 dα " << r.curl_of_exact
              << ", div δβ " << r.divergence_of_coexact << ", d1 h " << r.harmonic_curl << ", div h "
              << r.harmonic_divergence << '\n';
    if (r.basis) {
        std::cout << "harmonic    dimension " << r.basis->dimension << " (b1 = " << b1 << "), gap " << r.basis->gap
                  << '\n';
    }
    if (r.reference) {
        std::cout << "reference   dec on level " << r.reference->level << " (" << r.reference->edges
                  << " edges): relative L2 exact " << r.reference->exact << ", co-exact " << r.reference->coexact
                  << ", harmonic " << r.reference->harmonic << ", all " << r.reference->total << '\n';
    }
    if (!o.output.empty()) {
        std::cout << "wrote       " << o.output << '\n';
    }
    return exit_ok;
}

}  // namespace

void add_hodge_command(CLI::App& app, CommandStatus& status) {
    auto o = std::make_shared<HodgeCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "hodge", "Helmholtz-Hodge decomposition of a 1-form and the harmonic basis (SEC §2.3, §4.3)");
    cmd->add_option("input", o->input, "Input mesh (.obj, .off, .ply)")->required();
    add_limit_scheme_options(cmd, o->scheme);
    add_inner_product_options(cmd, o->method, o->level);
    auto* file = cmd->add_option("--one-form", o->one_form, "The 1-form: one value per edge, one per line");
    auto* random = cmd->add_option("--random", o->random, "A random 1-form with this seed (>= 0)")
                       ->check(CLI::Range(0LL, 1LL << 62));
    auto* field = cmd->add_option("--field", o->field,
                                  "A vector field \"X;Y;Z\" (three formulas of x, y, z), integrated along the edges");
    file->excludes(random)->excludes(field);
    random->excludes(field);
    cmd->add_option("--reference-level", o->reference_level,
                    "Also decompose with DEC on the K-times subdivided mesh and compare the parts (1..6)")
        ->check(CLI::Range(1, 6));
    cmd->add_flag("--no-basis", o->no_basis, "Skip the harmonic basis (dimension and gap)");
    cmd->add_option("--sample-level", o->sample_level, "Level of the faces the vectors of -o are sampled at (0..6)")
        ->check(CLI::Range(0, 6));
    add_threads_option(cmd, o->threads);
    cmd->add_option("--save-parts", o->save_parts,
                    "Write the parts as PREFIXexact.txt, PREFIXcoexact.txt, PREFIXharmonic.txt (one value per edge)");
    cmd->add_option("-o,--output", o->output, "Write the input and its parts as vectors (.vtk)");
    cmd->add_flag("--json", o->json, "Print JSON");
    cmd->callback([o, cmd, &status] {
        status.exit_code = run_guarded([&] {
            check_level_option(*cmd, o->method);
            LIMSURF_CHECK(!o->one_form.empty() || o->random >= 0 || !o->field.empty(), InputError,
                          "hodge needs a 1-form: --one-form FILE, --random SEED or --field \"X;Y;Z\"");
            std::vector<std::string> outputs{o->output};
            if (!o->save_parts.empty()) {
                for (const char* part : {"exact.txt", "coexact.txt", "harmonic.txt"}) {
                    outputs.push_back(o->save_parts + part);
                }
            }
            check_output_paths(outputs, {o->input, o->one_form});
            const BuildResult built = read_mesh(o->input);
            print_warnings(built.report);
            return naming_file(built.source, {o->one_form, o->output}, [&] { return decompose_and_report(built, *o); });
        });
    });
}

}  // namespace limsurf::cli
