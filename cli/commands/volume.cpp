// limsurf volume MESH --scheme S [--moments] [--levels L] [--threads N] [--json]: the exact volume enclosed
// by the limit surface (trilinear forms), the polyhedral volumes of the first subdivision
// levels for comparison, and with --moments the centroid and inertia tensor of the solid by
// quadrature of the limit surface, with error estimates.
#include <algorithm>
#include <cmath>
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
#include "commands/threads_option.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/quadrature/integrals.h"
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
    int threads = 0;
    bool json = false;
};

/// Polyhedral volumes are computed only up to this many faces.
constexpr Index max_polyhedral_faces = Index{1} << 22;

/// Types beyond the shipped tables the mesh will need (valences and face degrees above 12); none
/// when the mesh will be refused anyway (a type above the generated limit, a valence below 3).
std::set<Index> types_beyond_tables(const Topology& t) {
    std::set<Index> out;
    const LocalSize size = local_size(t);
    if (size.max_valence > VolumeOptions{}.max_generated_type ||
        size.max_face_degree > VolumeOptions{}.max_generated_type) {
        return out;
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.valence(v) < 3) {
            return {};
        }
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

void print_volume_text(const VolumeCommandOptions& options, const nlohmann::json& out,
                       const std::vector<PolyhedralVolume>& levels, const std::optional<MeasureReport>& moments,
                       double volume, bool zero) {
    std::cout << std::setprecision(16) << "volume      " << volume << "  (exact: trilinear forms, "
              << options.scheme.scheme << "; " << out["facets"]["direct"] << " facets direct, "
              << out["facets"]["subdivided"] << " from locally subdivided faces)\n";
    for (const PolyhedralVolume& l : levels) {
        std::cout << std::setprecision(16) << "polyhedral  level " << l.level << "  " << std::setw(18) << std::left
                  << l.volume << std::right << std::setprecision(2);
        if (zero) {
            std::cout << "  difference " << l.volume - volume << " (the exact volume is zero)";
        } else {
            std::cout << "  relative difference " << (l.volume - volume) / volume;
        }
        std::cout << "  (" << l.faces << " faces)\n";
    }
    if (static_cast<int>(levels.size()) <= options.levels) {
        std::cout << "polyhedral  levels " << levels.size() << ".." << options.levels << " skipped (more than "
                  << max_polyhedral_faces << " faces, or beyond the memory budget)\n";
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
}

/// True when @p volume is zero next to the cube of the mesh's extent (a flat closed surface):
/// relative differences to it are not defined.
bool is_zero_volume(double volume, const Points& X) {
    const double extent = (X.colwise().maxCoeff() - X.colwise().minCoeff()).maxCoeff();
    return extent == 0.0 || std::abs(volume) / extent / extent / extent <= 1e-12;
}

/// The polyhedral levels as JSON: volume, difference to the exact volume, and the relative
/// difference where the exact volume is not zero.
nlohmann::json polyhedral_json(const std::vector<PolyhedralVolume>& levels, double volume, bool zero) {
    nlohmann::json out = nlohmann::json::array();
    for (const PolyhedralVolume& l : levels) {
        out.push_back(
            {{"level", l.level},
             {"faces", l.faces},
             {"volume", l.volume},
             {"difference", l.volume - volume},
             {"relative_difference", zero ? nlohmann::json(nullptr) : nlohmann::json((l.volume - volume) / volume)}});
    }
    return out;
}

int run_volume(const VolumeCommandOptions& options) {
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
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
    return naming_file(built.source, {}, [&] {
        VolumeOptions volume_options;
        volume_options.num_threads = options.threads;
        const EnclosedVolume forms(mesh.topology(), scheme, scheme_rules(mesh, options.scheme), volume_options);
        const double volume = forms.volume(mesh.positions());
        const bool zero = is_zero_volume(volume, mesh.positions());
        const auto levels =
            polyhedral_volumes(mesh.topology(), mesh.positions(), scheme, options.levels, max_polyhedral_faces);
        std::optional<MeasureReport> moments;
        if (options.moments) {
            const LimitBasis basis = make_limit_basis(mesh, options.scheme);
            moments = measure_with_error(basis, mesh.positions(),
                                         SamplerOptions{options.degree, options.tiles, options.threads});
        }
        const VolumeStatistics& stats = forms.statistics();
        nlohmann::json out{{"scheme", options.scheme.scheme},
                           {"volume", volume},
                           {"method", "trilinear forms (exact)"},
                           {"facets",
                            {{"direct", stats.direct_facets},
                             {"subdivided", stats.subdivided_facets},
                             {"max_type", stats.max_type},
                             {"generated_types", stats.generated_types}}},
                           {"polyhedral", polyhedral_json(levels, volume, zero)}};
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
        if (options.json) {
            print_json(out);
            return exit_ok;
        }
        require_finite(out);
        print_volume_text(options, out, levels, moments, volume, zero);
        return exit_ok;
    });
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
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_volume(*options); }); });
}

}  // namespace limsurf::cli
