// limsurf eval MESH --scheme S (--points FILE | --grid N) [--threads N] [--json] [-o OUT]:
// position, derivatives, normal and curvatures of the limit surface at ptex points.
#include <algorithm>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/core/input_file.h"
#include "limsurf/core/parallel.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/surface_frame.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct EvalOptions {
    std::string input;
    LimitSchemeOptions scheme;
    std::string points;
    int grid = 0;
    std::string output;
    bool json = false;
    int threads = 0;
};

/// Reads "face u v" lines ('#' starts a comment) and checks each point against @p basis.
std::vector<SurfacePoint> read_points(const std::string& path, const LimitBasis& basis) {
    std::ifstream in = open_input_file(path);
    std::vector<SurfacePoint> points;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const auto hash = line.find('#'); hash != std::string::npos) {
            line.erase(hash);
        }
        std::istringstream fields(line);
        std::string first;
        if (!(fields >> first)) {
            continue;
        }
        fields.str(line);
        fields.clear();
        long long face = 0;
        double u = 0.0;
        double v = 0.0;
        std::string extra;
        LIMSURF_CHECK((fields >> face >> u >> v) && !(fields >> extra) && std::isfinite(u) && std::isfinite(v),
                      InputError, path, ":", number, ": expected 'face u v', got '", line, "'");
        LIMSURF_CHECK(face >= 0 && face < basis.num_ptex_faces(), InputError, path, ":", number, ": ptex face ", face,
                      " out of range (the mesh has ", basis.num_ptex_faces(), " ptex faces)");
        const bool inside = basis.domain() == ParameterDomain::Quad ? u >= 0 && u <= 1 && v >= 0 && v <= 1
                                                                    : u >= 0 && v >= 0 && u + v <= 1;
        LIMSURF_CHECK(inside, InputError, path, ":", number, ": (u, v) = (", u, ", ", v, ") is outside the ",
                      basis.domain() == ParameterDomain::Quad ? "unit square" : "triangle u, v >= 0, u + v <= 1",
                      " of ptex face ", face);
        LIMSURF_CHECK(basis.has_limit_surface(static_cast<Index>(face)), InputError, path, ":", number, ": ptex face ",
                      face, " has no limit surface (a hole, or a boundary under --boundary none)");
        points.push_back({static_cast<Index>(face), u, v});
    }
    LIMSURF_CHECK(!in.bad(), InputError, path, ": read error");
    LIMSURF_CHECK(!points.empty(), InputError, path, ": no points (expected lines 'face u v')");
    return points;
}

std::vector<SurfacePoint> grid_points(int n, const LimitBasis& basis) {
    std::vector<SurfacePoint> points;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const double u = (i + 0.5) / n;
                const double v = (j + 0.5) / n;
                if (basis.domain() == ParameterDomain::Triangle && u + v > 1.0) {
                    continue;
                }
                points.push_back({p, u, v});
            }
        }
    }
    return points;
}

/// What is printed of a point's frame (a SurfaceFrame holds three times as much: 10⁶ points held
/// 0.5 GB more than they print).
struct PrintedFrame {
    Eigen::Vector3d normal;
    double gaussian_curvature = 0.0;
    double mean_curvature = 0.0;
};

struct Evaluated {
    SurfacePoint point;
    Eigen::Matrix<double, 6, 3> d;
    std::optional<PrintedFrame> frame;  // empty where the tangent plane is degenerate
    bool at_vertex = false;             // an extraordinary vertex itself: curvature not defined
};

nlohmann::json row_json(const Eigen::Matrix<double, 6, 3>& d, int row) {
    return {d(row, 0), d(row, 1), d(row, 2)};
}

nlohmann::json point_json(const Evaluated& r) {
    const char* names[] = {"position", "du", "dv", "duu", "duv", "dvv"};
    nlohmann::json p{{"face", r.point.face}, {"u", r.point.u}, {"v", r.point.v}};
    for (int row = 0; row < 6; ++row) {
        p[names[row]] = row_json(r.d, row);
    }
    if (r.frame) {
        p["normal"] = {r.frame->normal.x(), r.frame->normal.y(), r.frame->normal.z()};
        p["gaussian_curvature"] = r.at_vertex ? nlohmann::json(nullptr) : nlohmann::json(r.frame->gaussian_curvature);
        p["mean_curvature"] = r.at_vertex ? nlohmann::json(nullptr) : nlohmann::json(r.frame->mean_curvature);
    } else {
        p["normal"] = nullptr;
        p["gaussian_curvature"] = nullptr;
        p["mean_curvature"] = nullptr;
    }
    return p;
}

/// {"points": [...]} with a 2-space indent, the bytes nlohmann's dump(2) gives for the whole
/// document, written a point at a time (the document of 10⁵ points took 5× the memory of the
/// results). The caller has checked that every number is finite.
void write_points_json(std::ostream& out, const std::vector<Evaluated>& results) {
    if (results.empty()) {
        out << "{\n  \"points\": []\n}\n";
        return;
    }
    out << "{\n  \"points\": [\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const std::string text = point_json(results[i]).dump(2);
        std::string indented = "    ";  // each line two levels deeper
        indented.reserve(text.size() + text.size() / 8);
        for (const char c : text) {
            indented += c;
            if (c == '\n') {
                indented += "    ";
            }
        }
        indented += i + 1 < results.size() ? ",\n" : "\n";
        out.write(indented.data(), static_cast<std::streamsize>(indented.size()));
    }
    out << "  ]\n}\n";
}

bool all_finite(const std::vector<Evaluated>& results) {
    return std::all_of(results.begin(), results.end(), [](const Evaluated& r) {
        return std::isfinite(r.point.u) && std::isfinite(r.point.v) && r.d.allFinite() &&
               (!r.frame ||
                (r.frame->normal.allFinite() && (r.at_vertex || (std::isfinite(r.frame->gaussian_curvature) &&
                                                                 std::isfinite(r.frame->mean_curvature)))));
    });
}

void write_table(std::ostream& out, const std::vector<Evaluated>& results) {
    out << "# face u v  x y z  du(3) dv(3) duu(3) duv(3) dvv(3)  normal(3)  gaussian_curvature mean_curvature\n"
        << "# '-' where the tangent plane is degenerate, and for curvatures at an extraordinary vertex itself\n";
    const auto number = [&out](double value) {
        out << ' ';
        write_g17(out, value);
    };
    for (const Evaluated& r : results) {
        out << r.point.face;
        number(r.point.u);
        number(r.point.v);
        for (int row = 0; row < 6; ++row) {
            for (int c = 0; c < 3; ++c) {
                number(r.d(row, c));
            }
        }
        if (r.frame) {
            for (int c = 0; c < 3; ++c) {
                number(r.frame->normal(c));
            }
            if (r.at_vertex) {
                out << " - -\n";
            } else {
                number(r.frame->gaussian_curvature);
                number(r.frame->mean_curvature);
                out << '\n';
            }
        } else {
            out << " - - - - -\n";
        }
    }
}

/// Position, derivatives and frame at @p point; the frame is empty where the tangent plane is
/// degenerate. @throws NumericalError when the derivatives overflow a double
Evaluated evaluate_point(const LimitBasis& basis, const Points& X, const SurfacePoint& point) {
    LimitPoint values;
    basis.evaluate(X, point, values);
    Evaluated r{point, values.d, std::nullopt, values.at_extraordinary_vertex};
    LIMSURF_CHECK(r.d.allFinite(), NumericalError, "the limit surface's derivatives at ptex face ", point.face, " (",
                  point.u, ", ", point.v, ") overflow a double (the control points reach ", X.cwiseAbs().maxCoeff(),
                  "): rescale the mesh");
    if (has_tangent_plane(r.d)) {                       // else (e.g. at some extraordinary vertices) reported as null
        const SurfaceFrame frame = surface_frame(r.d);  // throws when a curvature overflows (a mesh ~1e-160 across)
        r.frame = PrintedFrame{frame.normal, frame.gaussian_curvature, frame.mean_curvature};
    }
    return r;
}

/// Every point, on @p threads threads (each point alone: the results do not depend on them); a
/// failure is reported for the first failing point in input order, whichever thread met it.
std::vector<Evaluated> evaluate_points(const LimitBasis& basis, const Points& X,
                                       const std::vector<SurfacePoint>& points, int threads) {
    std::vector<Evaluated> results(points.size());  // filled in place: no second copy of 10⁶ points
    std::mutex failure_mutex;
    std::size_t first_failed = points.size();
    std::exception_ptr failure;
    parallel_ranges(static_cast<Index>(points.size()), threads, [&](Index begin, Index end) {
        for (auto i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i) {
            try {
                results[i] = evaluate_point(basis, X, points[i]);
            } catch (...) {  // this range stops; the earliest failure over all ranges is rethrown
                const std::lock_guard<std::mutex> lock(failure_mutex);
                if (i < first_failed) {
                    first_failed = i;
                    failure = std::current_exception();
                }
                return;
            }
        }
    });
    if (failure) {
        std::rethrow_exception(failure);
    }
    return results;
}

int run_eval(const EvalOptions& options) {
    check_output_paths({options.output}, {options.input, options.points});
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    const std::vector<Evaluated> results = naming_file(built.source, {options.points}, [&] {
        const LimitBasis basis = make_limit_basis(built.mesh, options.scheme);
        const std::vector<SurfacePoint> points =
            options.points.empty() ? grid_points(options.grid, basis) : read_points(options.points, basis);
        return evaluate_points(basis, built.mesh.positions(), points, options.threads);
    });
    const bool json_file = std::filesystem::path(options.output).extension() == ".json";
    const bool as_json = options.output.empty() ? options.json : json_file;
    // Nothing non-finite is printed: the first such number is named as require_finite names it
    // (a point's JSON, only on that rare path).
    if (!all_finite(results)) {
        for (std::size_t i = 0; i < results.size(); ++i) {
            require_finite(point_json(results[i]), "points[" + std::to_string(i) + "]");
        }
    }
    const auto write = [&](std::ostream& out) {
        if (as_json) {
            write_points_json(out, results);
        } else {
            write_table(out, results);
        }
    };
    if (!options.output.empty()) {
        write_file_atomically(options.output, write);
    } else {
        write(std::cout);
    }
    return exit_ok;
}

}  // namespace

void add_eval_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<EvalOptions>();
    CLI::App* cmd = app.add_subcommand("eval", "Evaluate the limit surface: position, derivatives, normal, curvature");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    add_limit_scheme_options(cmd, options->scheme);
    auto* points = cmd->add_option("--points", options->points, "File of 'face u v' lines (ptex faces; '#' comments)");
    auto* grid = cmd->add_option("--grid", options->grid, "N x N points on every ptex face (u, v = (i + 0.5)/N)")
                     ->check(CLI::Range(1, 1000));
    points->excludes(grid);
    grid->excludes(points);
    cmd->add_option("-o,--output", options->output,
                    "Write the table (or JSON when OUT ends in .json) to OUT, atomically, instead of stdout");
    cmd->add_flag("--json", options->json, "Print JSON: {\"points\": [...]}");
    add_threads_option(cmd, options->threads);
    cmd->callback([options, &status, points, grid] {
        if (points->count() == 0 && grid->count() == 0) {
            std::cerr << "error: eval needs --points FILE or --grid N (see 'limsurf eval --help')\n";
            status.exit_code = exit_usage;
            return;
        }
        status.exit_code = run_guarded([&] { return run_eval(*options); });
    });
}

}  // namespace limsurf::cli
