// limsurf volume MESH --scheme S [--moments] [--levels L] [--json]: the exact volume enclosed
// by the limit surface (trilinear forms), the polyhedral volumes of the first subdivision
// levels for comparison, and with --moments the centroid and inertia tensor of the solid by
// quadrature of the limit surface, with error estimates.
#include <algorithm>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/refine/refine.h"
#include "limsurf/volume/enclosed_volume.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct VolumeCommandOptions {
    std::string input;
    LimitSchemeOptions scheme;
    int levels = 3;
    bool moments = false;
    int degree = 12;
    int tiles = 10;
    bool json = false;
};

/// Polyhedral volumes are computed only up to this many faces.
constexpr Index max_polyhedral_faces = Index{1} << 22;

struct PolyhedralLevel {
    int level = 0;
    Index faces = 0;
    double volume = 0.0;
};

std::vector<PolyhedralLevel> polyhedral_levels(const ControlMesh& mesh, SchemeKind scheme, int levels) {
    std::vector<PolyhedralLevel> out{{0, mesh.num_faces(), polyhedral_volume(mesh.topology(), mesh.positions())}};
    Topology t = mesh.topology();
    Points X = mesh.positions();
    for (int l = 1; l <= levels; ++l) {
        // Catmull–Clark makes one quad per face corner, Loop four triangles, Doo–Sabin F + E + V faces.
        const Index next = scheme == SchemeKind::CatmullClark ? t.num_corners()
                           : scheme == SchemeKind::Loop       ? 4 * t.num_faces()
                                                              : t.num_faces() + t.num_edges() + t.num_vertices();
        if (next > max_polyhedral_faces) {
            break;
        }
        Level level = refine(t, scheme);
        X = level.S0 * X;
        t = std::move(level.topology);
        out.push_back({l, t.num_faces(), polyhedral_volume(t, X)});
    }
    return out;
}

/// Types beyond the shipped tables the mesh will need (valences and face degrees above 12).
std::set<Index> types_beyond_tables(const Topology& t) {
    std::set<Index> out;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.valence(v) > 12) {
            out.insert(t.valence(v));
        }
    }
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (t.face_degree(f) > 12) {
            out.insert(t.face_degree(f));
        }
    }
    return out;
}

nlohmann::json vector_json(const Eigen::Vector3d& x) {
    return {x.x(), x.y(), x.z()};
}

nlohmann::json matrix_json(const Eigen::Matrix3d& m) {
    return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

int run_volume(const VolumeCommandOptions& options) {
    const BuildResult built = read_mesh(options.input);
    for (const Issue& issue : built.report.issues) {
        std::cerr << "warning: " << issue.to_string() << '\n';
    }
    const ControlMesh& mesh = built.mesh;
    const SchemeKind scheme = limit_schemes().at(options.scheme.scheme);
    const auto extra = types_beyond_tables(mesh.topology());
    if (!extra.empty() && !options.json) {
        std::cerr << "note: generating the volume forms of facet types";
        for (const Index type : extra) {
            std::cerr << ' ' << type;
        }
        std::cerr << " on demand (the shipped tables cover 3..12)\n";
    }
    std::unique_ptr<EnclosedVolume> forms;
    try {
        forms = std::make_unique<EnclosedVolume>(mesh.topology(), scheme, scheme_rules(mesh, options.scheme));
    } catch (const InputError& e) {
        throw InputError(options.input + ": " + e.what());
    } catch (const UnsupportedError& e) {
        throw UnsupportedError(options.input + ": " + e.what());
    }
    const double volume = forms->volume(mesh.positions());
    const auto levels = polyhedral_levels(mesh, scheme, options.levels);
    std::optional<MeasureReport> moments;
    if (options.moments) {
        const LimitBasis basis = make_limit_basis(mesh, options.scheme);
        moments = measure_with_error(basis, mesh.positions(), SamplerOptions{options.degree, options.tiles, 0});
    }
    const VolumeStatistics& stats = forms->statistics();
    if (options.json) {
        nlohmann::json out{{"scheme", options.scheme.scheme},
                           {"volume", volume},
                           {"method", "trilinear forms (exact)"},
                           {"facets",
                            {{"direct", stats.direct_facets},
                             {"subdivided", stats.subdivided_facets},
                             {"max_type", stats.max_type},
                             {"generated_types", stats.generated_types}}}};
        nlohmann::json polyhedral = nlohmann::json::array();
        for (const PolyhedralLevel& l : levels) {
            polyhedral.push_back({{"level", l.level},
                                  {"faces", l.faces},
                                  {"volume", l.volume},
                                  {"relative_difference", (l.volume - volume) / volume}});
        }
        out["polyhedral"] = polyhedral;
        if (moments) {
            out["centroid"] = vector_json(moments->value.centroid);
            out["inertia"] = matrix_json(moments->value.inertia);
            out["moments"] = {{"method", "quadrature of the limit surface"},
                              {"about", "centroid"},
                              {"degree", options.degree},
                              {"tiles", options.tiles},
                              {"quadrature_volume", moments->value.volume},
                              {"error_estimate",
                               {{"volume", moments->error.volume},
                                {"centroid", moments->error.centroid},
                                {"inertia", moments->error.inertia}}}};
        }
        std::cout << out.dump(2) << '\n';
        return exit_ok;
    }
    std::cout << std::setprecision(16) << "volume      " << volume << "  (exact: trilinear forms, "
              << options.scheme.scheme << "; " << stats.direct_facets << " facets direct, " << stats.subdivided_facets
              << " from locally subdivided faces)\n";
    for (const PolyhedralLevel& l : levels) {
        std::cout << std::setprecision(16) << "polyhedral  level " << l.level << "  " << std::setw(18) << std::left
                  << l.volume << std::right << std::setprecision(2) << "  relative difference "
                  << (l.volume - volume) / volume << "  (" << l.faces << " faces)\n";
    }
    if (moments) {
        const Eigen::Vector3d& c = moments->value.centroid;
        const Eigen::Matrix3d& I = moments->value.inertia;
        std::cout << std::setprecision(15) << "centroid    " << c.x() << ' ' << c.y() << ' ' << c.z()
                  << std::setprecision(2) << "  (quadrature, error estimate " << moments->error.centroid << ")\n";
        for (int r = 0; r < 3; ++r) {
            std::cout << (r == 0 ? "inertia     " : "            ") << std::setprecision(15) << I(r, 0) << ' '
                      << I(r, 1) << ' ' << I(r, 2);
            if (r == 0) {
                std::cout << std::setprecision(2) << "  (about the centroid; quadrature, error estimate "
                          << moments->error.inertia << ")";
            }
            std::cout << '\n';
        }
        std::cout << std::setprecision(16) << "quadrature volume " << moments->value.volume << std::setprecision(2)
                  << "  (differs from the exact volume by " << std::abs(moments->value.volume - volume) / volume
                  << " relative)\n";
    }
    return exit_ok;
}

}  // namespace

void add_volume_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<VolumeCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "volume",
        "Exact volume enclosed by the limit surface (trilinear forms), with --moments its centroid and inertia");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply), closed")->required();
    add_limit_scheme_options(cmd, options->scheme);
    cmd->add_option("--levels", options->levels, "Polyhedral volumes of subdivision levels 0..L for comparison (0..6)")
        ->check(CLI::Range(0, 6));
    cmd->add_flag("--moments", options->moments,
                  "Also the centroid and the inertia tensor (about the centroid) of the solid, by quadrature");
    cmd->add_option("--degree", options->degree, "Quadrature degree per tile for --moments (1..60)")
        ->check(CLI::Range(1, 60));
    cmd->add_option("--tiles", options->tiles, "Tile levels towards extraordinary vertices for --moments (0..20)")
        ->check(CLI::Range(0, 20));
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_volume(*options); }); });
}

}  // namespace limsurf::cli
