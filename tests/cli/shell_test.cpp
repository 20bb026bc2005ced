// `limsurf shell`: the Scordelis–Lo roof and the pinched hemisphere of the shell obstacle course
// through the command (the literature's reference values), the output file, and refusals.
#include <cmath>
#include <filesystem>
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
    static const fs::path dir = test::make_temp_dir("cli_shell");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string bundled(const char* name) {
    return test::find_bundled(name).path.string();
}

/// The roof's arguments: R = 25, L = 50, 40°, t = 0.25, E = 4.32e8, ν = 0, self-weight 90, diaphragms.
std::vector<std::string> roof(const std::vector<std::string>& more) {
    std::vector<std::string> args{"shell", bundled("shell_scordelis_lo"), "--E", "4.32e8", "--nu", "0",
                                  "--thickness", "0.25", "--gravity", "90", "--fix", "abs(y) > 24.999:xz",
                                  "--probe", "16.06969024216348,0,19.15111107797445", "--surface", "x^2+z^2-625",
                                  "--json"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

TEST(CliShell, ScordelisLoRoofReachesTheReference) {
    const fs::path vtk = temp_dir() / "roof.vtk";
    const CliRun run = limsurf(roof({"--levels", "2", "-o", vtk.string()}));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const auto& levels = out.at("levels");
    ASSERT_EQ(levels.size(), 3u);
    std::vector<double> w;
    for (const auto& level : levels) {
        w.push_back(-level.at("probes").at(0).at("displacement").at(2).get<double>());
        EXPECT_EQ(level.at("rigid_motions_removed").get<int>(), 1);
    }
    // 0.3006: the converged Kirchhoff–Love (deep-shell) value; 0.3024 with shear (MacNeal–Harder).
    EXPECT_NEAR(w[2], 0.3006, 0.005 * 0.3006);
    EXPECT_LT(std::abs(w[2] - 0.3006), std::abs(w[0] - 0.3006));
    // The area of the roof, 25 · (80° in radians) · 50.
    EXPECT_NEAR(levels[2].at("area").get<double>(), 25 * 80 * std::acos(-1.0) / 180 * 50, 1e-2);
    EXPECT_TRUE(fs::exists(vtk));
}

TEST(CliShell, PinchedHemisphereReachesTheReference) {
    const CliRun run =
        limsurf({"shell", bundled("shell_hemisphere"), "--E", "6.825e7", "--nu", "0.3", "--thickness", "0.04",
                 "--point-load", "10,0,0:2,0,0", "--point-load", "-10,0,0:-2,0,0", "--point-load", "0,10,0:0,-2,0",
                 "--point-load", "0,-10,0:0,2,0", "--probe", "10,0,0", "--surface", "x^2+y^2+z^2-100", "--levels",
                 "2", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const auto& finest = out.at("levels").at(2);
    EXPECT_EQ(finest.at("rigid_motions_removed").get<int>(), 6);  // free edges: all six
    const double u = finest.at("probes").at(0).at("displacement").at(0).get<double>();
    EXPECT_NEAR(u, 0.0940, 0.02 * 0.0940);  // the thin-shell value; MacNeal–Harder's 0.0924
    EXPECT_NEAR(u, 0.0924, 0.02 * 0.0924);
}

TEST(CliShell, BadInputIsRefused) {
    const auto refused = [](const std::vector<std::string>& args, const std::string& message) {
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, 1) << run.err;
        EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
        EXPECT_EQ(run.err.find("nan"), std::string::npos) << run.err;
    };
    const std::string hemisphere = bundled("shell_hemisphere");
    refused({"shell", hemisphere, "--nu", "0.5", "--pressure", "1"}, "nu must be in (-1, 0.5)");
    refused({"shell", hemisphere, "--thickness", "-1", "--pressure", "1"}, "thickness must be > 0");
    refused({"shell", hemisphere}, "no load");
    // A point load that is not at a vertex's limit point.
    refused({"shell", hemisphere, "--point-load", "10,1,0:1,0,0", "--point-load", "-10,1,0:-1,0,0"},
            "no control vertex has its limit point at the point load");
    // One unbalanced force on a free shell has no static solution.
    refused({"shell", hemisphere, "--interpolate", "--point-load", "10,0,0:1,0,0"}, "not in equilibrium");
    refused({"shell", hemisphere, "--pressure", "1", "--fix", "z > 100:xyz"}, "selects no boundary control vertex");
    refused({"shell", hemisphere, "--pressure", "1", "--fix", "z > 9:xw"}, "components are letters");
    refused({"shell", hemisphere, "--pressure", "1", "--fix", "sin(:x"}, "--fix");
    refused({"shell", hemisphere, "--pressure", "1", "--point-load", "1,2:3,4,5"}, "three finite numbers");
    refused({"shell", hemisphere, "--pressure", "1", "--surface", "1"}, "no gradient");
    refused({"shell", hemisphere, "--pressure", "1", "--scheme", "loop"}, "");
    refused({"shell", bundled("shell_scordelis_lo"), "--gravity", "1", "--probe", "0,0,0"}, "no control vertex has its limit point at the probe");
}

}  // namespace
}  // namespace limsurf
