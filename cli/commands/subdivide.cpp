// limsurf subdivide IN --scheme S --levels N [options] -o OUT [--json]:
// uniform refinement; writes the finest level (positions = A^L · X) with its
// sharpness carried, in the format of OUT's extension.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/ply_encoding_option.h"
#include "commands/threads_option.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct SubdivideOptions {
    std::string input;
    std::string output;
    std::string scheme;
    int levels = 1;
    std::string boundary;   // empty: the file's hint, else edge-and-corner
    std::string creasing;   // empty: the file's hint, else uniform
    std::string triangles;  // empty: the file's hint, else catmull-clark
    std::string weights;    // cup | saddle | FILE
    std::int64_t max_faces = RefineOptions{}.max_faces;
    std::string max_memory;
    std::string format;
    std::string ply_encoding;  ///< empty: ascii
    bool json = false;
    int threads = 0;
};

const std::map<std::string, SchemeKind> schemes{
    {"catmull-clark", SchemeKind::CatmullClark}, {"loop", SchemeKind::Loop},     {"doo-sabin", SchemeKind::DooSabin},
    {"bilinear", SchemeKind::Bilinear},          {"linear", SchemeKind::Linear}, {"c2g0", SchemeKind::C2g0}};
const std::map<std::string, BoundaryInterpolation> boundaries{
    {"none", BoundaryInterpolation::None},
    {"edge-only", BoundaryInterpolation::EdgeOnly},
    {"edge-and-corner", BoundaryInterpolation::EdgeAndCorner}};
const std::map<std::string, CreasingMethod> creasings{{"uniform", CreasingMethod::Uniform},
                                                      {"chaikin", CreasingMethod::Chaikin}};
const std::map<std::string, TriangleSubdivision> triangle_rules{{"catmull-clark", TriangleSubdivision::CatmullClark},
                                                                {"smooth", TriangleSubdivision::Smooth}};

/// Command-line value if given, else the file's hint, else the library default.
template <class T>
T choose(const std::string& flag, const std::map<std::string, T>& names, const std::optional<T>& hint, T fallback) {
    if (!flag.empty()) {
        return names.at(flag);
    }
    return hint.value_or(fallback);
}

RefineOptions refine_options(const SubdivideOptions& options, const SchemeHints& hints) {
    RefineOptions refine;
    refine.scheme = schemes.at(options.scheme);
    refine.levels = options.levels;
    refine.max_faces = options.max_faces;
    refine.max_memory = memory_budget(options.max_memory);
    refine.num_threads = options.threads;
    const SchemeOptions defaults;
    refine.scheme_options.boundary = choose(options.boundary, boundaries, hints.boundary, defaults.boundary);
    refine.scheme_options.creasing = choose(options.creasing, creasings, hints.creasing, defaults.creasing);
    refine.scheme_options.triangles = choose(options.triangles, triangle_rules, hints.triangles, defaults.triangles);
    if (!options.weights.empty()) {
        LIMSURF_CHECK(refine.scheme == SchemeKind::CatmullClark, InputError,
                      "--weights applies to --scheme catmull-clark only");
        refine.weights = options.weights == "cup" || options.weights == "saddle"
                             ? TunedWeights::preset(options.weights)
                             : TunedWeights::from_file(options.weights);
    }
    return refine;
}

nlohmann::json size_json(const Topology& t) {
    return {{"num_vertices", t.num_vertices()}, {"num_edges", t.num_edges()}, {"num_faces", t.num_faces()}};
}

int run_subdivide(const SubdivideOptions& options) {
    const MeshFormat format = output_format(options.output, options.format);  // refused before any work
    check_output_paths({options.output}, {options.input, options.weights});
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    RefineOptions refine = refine_options(options, built.mesh.hints());
    return naming_file(built.source, {options.output, options.weights}, [&] {
        // Only the finest level is kept (each step's S0 and parent are dropped once used), and of it
        // only the face list (no edges or one-rings): it is written, not computed on.
        const std::vector<LevelSize> sizes = predict_sizes(built.mesh.topology(), refine.scheme, refine.levels);
        const auto start = std::chrono::steady_clock::now();
        FinestFaces refined = refine_finest_faces(built.mesh.topology(), built.mesh.positions(), refine);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

        // Record the rules used, so that the output refines the same way.
        refined.mesh.hints.boundary = refine.scheme_options.boundary;
        refined.mesh.hints.creasing = refine.scheme_options.creasing;
        refined.mesh.hints.triangles = refine.scheme_options.triangles;
        print_warnings(write_mesh(options.output, refined.mesh,
                                  {.ply_encoding = ply_encoding_from(options.ply_encoding, format), .format = format}));

        if (options.json) {
            nlohmann::json levels = nlohmann::json::array();
            for (const auto& [v, e, f] : refined.counts) {
                levels.push_back({{"num_vertices", v}, {"num_edges", e}, {"num_faces", f}});
            }
            print_json({{"scheme", options.scheme},
                        {"levels", options.levels},
                        {"boundary", to_string(refine.scheme_options.boundary)},
                        {"creasing", to_string(refine.scheme_options.creasing)},
                        {"triangles", to_string(refine.scheme_options.triangles)},
                        {"tuned_weights", !refine.weights.is_catmull_clark()},
                        {"input", size_json(built.mesh.topology())},
                        {"output", levels.back()},
                        {"per_level", levels},
                        {"output_file", options.output},
                        {"estimated_peak_bytes", estimated_finest_peak_bytes(sizes, true)},
                        {"seconds", seconds}});
        }
        return exit_ok;
    });
}

template <class T>
std::vector<std::string> keys(const std::map<std::string, T>& names) {
    std::vector<std::string> out;
    for (const auto& [name, value] : names) {
        out.push_back(name);
    }
    return out;
}

}  // namespace

void add_subdivide_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<SubdivideOptions>();
    CLI::App* cmd = app.add_subcommand("subdivide", "Uniform subdivision; writes the finest level");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    cmd->add_option("-o,--output", options->output, "Output mesh (.obj, .off, .ply); written atomically")->required();
    add_format_option(cmd, options->format);
    cmd->add_option("--scheme", options->scheme, "Subdivision scheme")->required()->check(CLI::IsMember(keys(schemes)));
    cmd->add_option("--levels", options->levels, "Refinement steps (0..16)")->check(CLI::Range(0, 16));
    cmd->add_option("--boundary", options->boundary,
                    "Boundary rule (default: the file's interpolateboundary tag, else edge-and-corner)")
        ->check(CLI::IsMember(keys(boundaries)));
    cmd->add_option("--creasing", options->creasing, "Semi-sharp crease decay (default: the file's tag, else uniform)")
        ->check(CLI::IsMember(keys(creasings)));
    cmd->add_option("--triangles", options->triangles,
                    "Catmull-Clark rule for triangles (default: the file's tag, else catmull-clark)")
        ->check(CLI::IsMember(keys(triangle_rules)));
    cmd->add_option("--weights", options->weights,
                    "Tuned Catmull-Clark weights: cup, saddle (Zhang-Sabin-Cirak Table 1) or a file of "
                    "'valence alpha beta gamma' / 'vertex I alpha beta gamma' lines");
    cmd->add_option("--max-faces", options->max_faces, "Refuse when the finest level would have more faces")
        ->check(positive_number());
    add_memory_option(cmd, options->max_memory);
    add_ply_encoding_option(cmd, options->ply_encoding);
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--json", options->json, "Print a JSON summary");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_subdivide(*options); }); });
}

}  // namespace limsurf::cli
