// limsurf info MESH [--json]: counts, histograms, boundary, genus, bounding
// box, sharpness and the validation report of a mesh file.
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/statistics.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct InfoOptions {
    std::string mesh;
    bool json = false;
    bool strict_isolated = false;
};

nlohmann::json histogram_json(const std::map<Index, Index>& histogram) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, count] : histogram) {
        out[std::to_string(key)] = count;
    }
    return out;
}

std::string histogram_text(const std::map<Index, Index>& histogram) {
    std::ostringstream out;
    for (const auto& [key, count] : histogram) {
        out << (out.tellp() > 0 ? ", " : "") << key << " ×" << count;
    }
    return histogram.empty() ? "none" : out.str();
}

nlohmann::json hints_json(const SchemeHints& hints) {
    nlohmann::json out = nlohmann::json::object();
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

nlohmann::json info_json(const std::string& file, const ControlMesh& mesh, const ValidationReport& report) {
    const Topology& t = mesh.topology();
    const MeshStatistics stats = statistics(mesh);
    const SharpnessSummary& s = stats.sharpness;
    std::map<Index, Index> all_valences = stats.interior_valences;
    for (const auto& [valence, count] : stats.boundary_valences) {
        all_valences[valence] += count;
    }
    return {{"file", file},
            {"num_vertices", t.num_vertices()},
            {"num_edges", t.num_edges()},
            {"num_faces", t.num_faces()},
            {"num_corners", t.num_corners()},
            {"euler_characteristic", t.euler_characteristic()},
            {"genus", t.genus()},
            {"num_components", t.num_components()},
            {"num_boundary_loops", t.num_boundary_loops()},
            {"boundary_loop_lengths", stats.boundary_loop_lengths},
            {"is_closed", t.is_closed()},
            {"face_degree_histogram", histogram_json(stats.face_degrees)},
            {"valence_histogram", histogram_json(all_valences)},
            {"interior_valence_histogram", histogram_json(stats.interior_valences)},
            {"boundary_valence_histogram", histogram_json(stats.boundary_valences)},
            {"bounding_box",
             {{"min", {stats.bounding_box_min.x(), stats.bounding_box_min.y(), stats.bounding_box_min.z()}},
              {"max", {stats.bounding_box_max.x(), stats.bounding_box_max.y(), stats.bounding_box_max.z()}}}},
            {"sharpness",
             {{"num_sharp_edges", s.num_sharp_edges},
              {"num_infinitely_sharp_edges", s.num_infinitely_sharp_edges},
              {"max_semi_sharp_edge", s.max_semi_sharp_edge},
              {"num_sharp_vertices", s.num_sharp_vertices},
              {"num_infinitely_sharp_vertices", s.num_infinitely_sharp_vertices},
              {"num_holes", s.num_holes}}},
            {"scheme_hints", hints_json(mesh.hints())},
            {"validation", report_json(report)}};
}

void print_info_text(const std::string& file, const ControlMesh& mesh, const ValidationReport& report) {
    const Topology& t = mesh.topology();
    const MeshStatistics stats = statistics(mesh);
    const SharpnessSummary& s = stats.sharpness;
    auto row = [](const char* key) -> std::ostream& { return std::cout << std::left << std::setw(22) << key; };
    row("mesh") << file << '\n';
    row("vertices") << t.num_vertices() << '\n';
    row("edges") << t.num_edges() << '\n';
    row("faces") << t.num_faces() << "  (degree " << histogram_text(stats.face_degrees) << ")\n";
    row("euler characteristic") << t.euler_characteristic() << '\n';
    row("genus") << t.genus() << '\n';
    row("components") << t.num_components() << '\n';
    if (t.is_closed()) {
        row("boundary") << "none (closed)\n";
    } else {
        row("boundary") << t.num_boundary_loops() << " loop" << (t.num_boundary_loops() == 1 ? "" : "s") << " of "
                        << histogram_text([&] {
                               std::map<Index, Index> h;
                               for (const Index n : stats.boundary_loop_lengths) {
                                   ++h[n];
                               }
                               return h;
                           }())
                        << " vertices\n";
    }
    row("valence (interior)") << histogram_text(stats.interior_valences) << '\n';
    if (!t.is_closed()) {
        row("valence (boundary)") << histogram_text(stats.boundary_valences) << '\n';
    }
    row("bounding box") << "[" << stats.bounding_box_min.transpose() << "] to [" << stats.bounding_box_max.transpose()
                        << "]\n";
    if (t.has_sharpness()) {
        row("sharp edges") << s.num_sharp_edges << " (" << s.num_infinitely_sharp_edges
                           << " infinitely sharp; largest semi-sharp value " << s.max_semi_sharp_edge << ")\n";
        row("sharp vertices") << s.num_sharp_vertices << " (" << s.num_infinitely_sharp_vertices
                              << " infinitely sharp)\n";
        row("holes") << s.num_holes << '\n';
    } else {
        row("sharpness") << "none\n";
    }
    if (!mesh.hints().empty()) {
        row("scheme hints") << hints_json(mesh.hints()).dump() << '\n';
    }
    row("validation") << (report.issues.empty() ? "ok" : std::to_string(report.num_warnings()) + " warnings") << '\n';
    for (const std::string& line : report_lines(report)) {
        std::cout << "  " << line << '\n';
    }
}

/// An invalid mesh: the full report on stdout, one error line on stderr.
int report_invalid(const std::string& file, const PolygonSoup& soup, const ValidationReport& report, bool json) {
    if (json) {
        std::cout << nlohmann::json{{"file", file},
                                    {"num_vertices", soup.num_vertices()},
                                    {"num_faces", soup.num_faces()},
                                    {"validation", report_json(report)}}
                         .dump(2)
                  << '\n';
    } else {
        std::cout << "mesh                  " << file << '\n'
                  << "validation            " << report.num_errors() << " errors, " << report.num_warnings()
                  << " warnings\n";
        for (const std::string& line : report_lines(report)) {
            std::cout << "  " << line << '\n';
        }
    }
    std::cerr << "error: " << report.summary() << '\n';
    return exit_bad_input;
}

int run_info(const InfoOptions& options) {
    const PolygonSoup soup = read_polygon_soup(options.mesh);
    const BuildOptions build{.isolated_vertices =
                                 options.strict_isolated ? IsolatedVertices::Error : IsolatedVertices::Drop};
    ValidationReport report = validate(soup, build.validation);
    if (options.strict_isolated) {
        for (Issue& issue : report.issues) {
            if (issue.problem == Problem::IsolatedVertex) {
                issue.severity = Severity::Error;
            }
        }
    }
    if (report.has_errors()) {
        return report_invalid(options.mesh, soup, report, options.json);
    }
    const BuildResult built = build_control_mesh(soup, build);
    if (options.json) {
        std::cout << info_json(options.mesh, built.mesh, built.report).dump(2) << '\n';
    } else {
        print_info_text(options.mesh, built.mesh, built.report);
    }
    return exit_ok;
}

}  // namespace

void add_info_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<InfoOptions>();
    CLI::App* info =
        app.add_subcommand("info", "Counts, histograms, genus, boundary, sharpness and validation of a mesh");
    info->add_option("mesh", options->mesh, "Mesh file (.obj, .off, .ply)")->required();
    info->add_flag("--json", options->json, "Print one JSON object instead of text");
    info->add_flag("--strict-isolated", options->strict_isolated,
                   "Treat vertices in no face as errors (default: dropped with a warning)");
    info->callback([options, &status] { status.exit_code = run_guarded([&] { return run_info(*options); }); });
}

}  // namespace limsurf::cli
