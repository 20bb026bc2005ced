// `limsurf reverse`: a bundled mesh subdivided by `limsurf subdivide` comes back (the original file
// is the oracle: same counts, same positions read from both OBJ files); the JSON reports the levels
// and residuals; a mesh that is not a subdivided topology is refused naming file and line.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_reverse");
    return dir;
}

test::CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

/// The "v x y z" lines of an OBJ file.
std::vector<std::array<double, 3>> obj_vertices(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::array<double, 3>> out;
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("v ", 0) == 0) {
            std::istringstream words(line.substr(2));
            std::array<double, 3> p{};
            words >> p[0] >> p[1] >> p[2];
            out.push_back(p);
        }
    }
    return out;
}

TEST(CliReverse, SubdividedTwiceComesBack) {
    for (const char* name : {"cube_ngons", "annulus", "cube_creases"}) {
        SCOPED_TRACE(name);
        const fs::path original = test::mesh_dir() / (std::string(name) + ".obj");
        const fs::path fine = temp_dir() / (std::string(name) + "_fine.obj");
        const fs::path coarse = temp_dir() / (std::string(name) + "_coarse.obj");
        const auto sub = limsurf(
            {"subdivide", original.string(), "--scheme", "catmull-clark", "--levels", "2", "-o", fine.string()});
        ASSERT_EQ(sub.exit_code, 0) << sub.err;
        const auto run = limsurf({"reverse", fine.string(), "-o", coarse.string(), "--json"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const auto json = nlohmann::json::parse(run.out);
        EXPECT_EQ(json.at("levels_reversed").get<int>(), 2);
        EXPECT_EQ(json.at("method").get<std::string>(), "least-squares");
        ASSERT_EQ(json.at("per_level").size(), 2U);
        for (const auto& level : json.at("per_level")) {
            EXPECT_LE(level.at("residual_max").get<double>(), 1e-12);
        }
        const auto want = obj_vertices(original);
        const auto got = obj_vertices(coarse);
        ASSERT_EQ(got.size(), want.size());
        EXPECT_EQ(json.at("output").at("num_vertices").get<std::size_t>(), want.size());
        for (std::size_t i = 0; i < want.size(); ++i) {
            for (int j = 0; j < 3; ++j) {
                EXPECT_NEAR(got[i][static_cast<std::size_t>(j)], want[i][static_cast<std::size_t>(j)], 1e-12);
            }
        }
    }
}

TEST(CliReverse, ExplicitLevelsBeyondThePossibleAreRefused) {
    const fs::path fine = temp_dir() / "torus_fine.obj";
    const auto sub = limsurf({"subdivide", (test::mesh_dir() / "torus_4x5.obj").string(), "--scheme", "catmull-clark",
                              "--levels", "1", "-o", fine.string()});
    ASSERT_EQ(sub.exit_code, 0) << sub.err;
    const auto one = limsurf({"reverse", fine.string(), "-o", (temp_dir() / "t1.obj").string(), "--json"});
    ASSERT_EQ(one.exit_code, 0) << one.err;
    EXPECT_EQ(nlohmann::json::parse(one.out).at("levels_reversed").get<int>(), 1);
    const auto two = limsurf({"reverse", fine.string(), "-o", (temp_dir() / "t2.obj").string(), "--levels", "2"});
    EXPECT_EQ(two.exit_code, 1);
    EXPECT_NE(two.err.find("level 2"), std::string::npos) << two.err;
    EXPECT_FALSE(fs::exists(temp_dir() / "t2.obj"));
}

TEST(CliReverse, RefusesANonSubdividedTopologyNamingTheLine) {
    const auto run = limsurf(
        {"reverse", (test::mesh_dir() / "single_triangle.obj").string(), "-o", (temp_dir() / "x.obj").string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("single_triangle.obj:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("quads only"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(temp_dir() / "x.obj"));
    const auto usage = limsurf(
        {"reverse", (test::mesh_dir() / "cube.obj").string(), "-o", (temp_dir() / "y.obj").string(), "--levels", "0"});
    EXPECT_EQ(usage.exit_code, 2);
}

}  // namespace
}  // namespace limsurf
