// `limsurf plate`: the simply supported square against Navier through the command (uniform load,
// Table 2's two-wave load with its zero centre), clamped support, and refusals.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_plate");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

/// The seed's square plate, L = 10, as a 4 × 4 quad grid.
std::string square_plate() {
    const fs::path path = temp_dir() / "square.obj";
    std::ofstream out(path);
    for (int j = 0; j <= 4; ++j) {
        for (int i = 0; i <= 4; ++i) {
            out << "v " << 2.5 * i << ' ' << 2.5 * j << " 0\n";
        }
    }
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            const int a = j * 5 + i + 1;
            out << "f " << a << ' ' << a + 1 << ' ' << a + 6 << ' ' << a + 5 << '\n';
        }
    }
    return path.string();
}

TEST(CliPlate, UniformLoadConvergesToNavier) {
    const fs::path vtk = temp_dir() / "w.vtk";
    const CliRun run = limsurf({"plate", square_plate(), "--levels", "2", "--json", "-o", vtk.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const auto& levels = out.at("levels");
    ASSERT_EQ(levels.size(), 3u);
    // Timoshenko: w = 0.00406 p a⁴ / D at the centre.
    const double D = out.at("bending_rigidity").get<double>();
    EXPECT_NEAR(levels[2].at("navier").at("centre_deflection").get<double>(), 0.00406235 * 1e4 * 1e4 / D, 1e-7);
    EXPECT_LT(std::abs(levels[2].at("navier").at("centre_relative_error").get<double>()), 1e-5);
    EXPECT_LT(levels[2].at("navier").at("energy_relative_error").get<double>(),
              levels[1].at("navier").at("energy_relative_error").get<double>() / 3.0);
    EXPECT_TRUE(fs::exists(vtk));
}

TEST(CliPlate, TableTwoLoadReportsTheQuarterPoint) {
    const CliRun run = limsurf({"plate", square_plate(), "--load", "sinusoidal", "--levels", "2", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto level = nlohmann::json::parse(run.out).at("levels")[2];
    EXPECT_TRUE(level.at("navier").at("centre_relative_error").is_null());  // the exact centre deflection is 0
    EXPECT_LT(std::abs(level.at("navier").at("quarter_relative_error").get<double>()), 1e-3);
}

TEST(CliPlate, BadInputIsRefused) {
    CliRun run = limsurf({"plate", square_plate(), "--nu", "0.5"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("nu must be in (-1, 0.5)"), std::string::npos) << run.err;
    run = limsurf({"plate", square_plate(), "--thickness", "0"});
    EXPECT_EQ(run.exit_code, 1);
    run = limsurf({"plate", test::find_bundled("cube").path.string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("plate"), std::string::npos) << run.err;
    run = limsurf({"plate", square_plate(), "--load", "1/0"});
    EXPECT_EQ(run.exit_code, 1);
    run = limsurf({"plate", square_plate(), "--load", "sin("});
    EXPECT_EQ(run.exit_code, 1);
    run = limsurf({"plate", square_plate(), "--support", "glued"});
    EXPECT_EQ(run.exit_code, 2);
}

}  // namespace
}  // namespace limsurf
