// limsurf measure MESH --scheme S [--degree D] [--tiles K] [--threads N] [--json]: area, enclosed
// volume, centroids and the solid's inertia tensor by quadrature, each with an error estimate.
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "commands/commands.h"
#include "commands/limit_options.h"
#include "commands/threads_option.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/quadrature/integrals.h"
#include "output.h"

namespace limsurf::cli {
namespace {

struct MeasureOptions {
    std::string input;
    LimitSchemeOptions scheme;
    int degree = 12;
    int tiles = 10;
    int threads = 0;
    bool json = false;
};

nlohmann::json vector_json(const Eigen::Vector3d& x) {
    return {x.x(), x.y(), x.z()};
}

int run_measure(const MeasureOptions& options) {
    const BuildResult built = read_mesh(options.input);
    print_warnings(built.report);
    const MeasureReport r = naming_file(built.source, {}, [&] {
        const LimitBasis basis = make_limit_basis(built.mesh, options.scheme);
        return measure_with_error(basis, built.mesh.positions(),
                                  SamplerOptions{options.degree, options.tiles, options.threads});
    });
    if (options.json) {
        nlohmann::json errors{{"area", r.error.area}, {"surface_centroid", r.error.surface_centroid}};
        errors["volume"] = r.closed ? nlohmann::json(r.error.volume) : nlohmann::json(nullptr);
        errors["centroid"] = r.closed ? nlohmann::json(r.error.centroid) : nlohmann::json(nullptr);
        errors["inertia"] = r.closed ? nlohmann::json(r.error.inertia) : nlohmann::json(nullptr);
        nlohmann::json out{
            {"closed", r.closed},
            {"area", r.value.area},
            {"surface_centroid", vector_json(r.value.surface_centroid)},
            {"error_estimate", errors},
            {"degree", options.degree},
            {"tiles", options.tiles},
            {"reference", {{"degree", r.finer.degree}, {"tiles", r.finer.subdivide_near_extraordinary}}}};
        out["volume"] = r.closed ? nlohmann::json(r.value.volume) : nlohmann::json(nullptr);
        out["centroid"] = r.closed ? vector_json(r.value.centroid) : nlohmann::json(nullptr);
        const Eigen::Matrix3d& I = r.value.inertia;
        out["inertia"] =
            r.closed
                ? nlohmann::json{{I(0, 0), I(0, 1), I(0, 2)}, {I(1, 0), I(1, 1), I(1, 2)}, {I(2, 0), I(2, 1), I(2, 2)}}
                : nlohmann::json(nullptr);
        print_json(out);
        return exit_ok;
    }
    require_finite({r.value.area, r.value.volume, r.error.area, r.error.volume, r.error.centroid,
                    r.error.surface_centroid, r.error.inertia, r.value.inertia.sum(), r.value.centroid.sum(),
                    r.value.surface_centroid.sum()});
    const auto vec = [](const Eigen::Vector3d& x) {
        std::ostringstream s;
        s << std::setprecision(15) << x.x() << ' ' << x.y() << ' ' << x.z();
        return s.str();
    };
    std::cout << std::setprecision(15) << "area              " << r.value.area << "  (error estimate "
              << std::setprecision(2) << r.error.area << ")\n";
    if (r.closed) {
        std::cout << std::setprecision(15) << "volume            " << r.value.volume << "  (error estimate "
                  << std::setprecision(2) << r.error.volume << ")\n"
                  << "centroid          " << vec(r.value.centroid) << "  (error estimate " << r.error.centroid << ")\n";
        for (int row = 0; row < 3; ++row) {
            std::cout << (row == 0 ? "inertia           " : "                  ") << std::setprecision(15)
                      << vec(r.value.inertia.row(row).transpose());
            if (row == 0) {
                std::cout << "  (about the centroid; error estimate " << std::setprecision(2) << r.error.inertia << ")";
            }
            std::cout << '\n';
        }
    } else {
        std::cout << "volume            not defined (the limit surface is not closed)\n";
    }
    std::cout << "surface centroid  " << vec(r.value.surface_centroid) << "  (error estimate " << std::setprecision(2)
              << r.error.surface_centroid << ")\n"
              << "quadrature        degree " << options.degree << ", " << options.tiles
              << " tile levels near extraordinary vertices; estimate: difference to degree " << r.finer.degree << ", "
              << r.finer.subdivide_near_extraordinary << " tile levels\n";
    return exit_ok;
}

}  // namespace

void add_measure_command(CLI::App& app, CommandStatus& status) {
    auto options = std::make_shared<MeasureOptions>();
    CLI::App* cmd = app.add_subcommand("measure", "Area, enclosed volume and centroids of the limit surface");
    cmd->add_option("input", options->input, "Input mesh (.obj, .off, .ply)")->required();
    add_limit_scheme_options(cmd, options->scheme);
    cmd->add_option("--degree", options->degree, "Quadrature degree per tile (1..60)")->check(CLI::Range(1, 60));
    cmd->add_option("--tiles", options->tiles, "Tile levels towards extraordinary vertices (0..20)")
        ->check(CLI::Range(0, 20));
    add_threads_option(cmd, options->threads);
    cmd->add_flag("--json", options->json, "Print JSON");
    cmd->callback([options, &status] { status.exit_code = run_guarded([&] { return run_measure(*options); }); });
}

}  // namespace limsurf::cli
