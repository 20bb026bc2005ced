// `limsurf eval` and `limsurf measure`: JSON keys, known values (a planar grid, a sphere-like
// mesh, the cube's measures), errors for bad points files (exit 1, the file and line named),
// usage errors (exit 2), and atomic output files.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
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
using test::slurp;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_eval_measure");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string write_points(const std::string& name, const std::string& text) {
    const fs::path path = temp_dir() / name;
    std::ofstream(path) << text;
    return path.string();
}

int count_lines(const std::string& text) {
    int n = 0;
    for (const char c : text) {
        n += c == '\n' ? 1 : 0;
    }
    return n;
}

TEST(CliEval, PlanarGridHasVerticalNormalsAndZeroCurvature) {
    const CliRun run = limsurf(
        {"eval", test::find_bundled("quad_grid").path.string(), "--scheme", "catmull-clark", "--grid", "3", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    ASSERT_EQ(json.size(), 1U);
    const auto& points = json["points"];
    ASSERT_EQ(points.size(), 16U * 9U);
    for (const auto& p : points) {
        for (const char* key : {"face", "u", "v", "position", "du", "dv", "duu", "duv", "dvv", "normal",
                                "gaussian_curvature", "mean_curvature"}) {
            ASSERT_TRUE(p.contains(key)) << key;
        }
        EXPECT_EQ(p.size(), 12U);
        EXPECT_NEAR(std::abs(p["normal"][2].get<double>()), 1.0, 1e-12);
        EXPECT_NEAR(p["position"][2].get<double>(), 0.0, 1e-14);
        EXPECT_NEAR(p["gaussian_curvature"].get<double>(), 0.0, 1e-10);
        EXPECT_NEAR(p["mean_curvature"].get<double>(), 0.0, 1e-10);
    }
}

TEST(CliEval, SphereLikeMeshesCurvePositivelyWithOutwardNormals) {
    for (const auto& [name, scheme] : {std::pair{"sphere_quads", "catmull-clark"}, std::pair{"sphere_tris", "loop"}}) {
        SCOPED_TRACE(name);
        const CliRun run =
            limsurf({"eval", test::find_bundled(name).path.string(), "--scheme", scheme, "--grid", "2", "--json"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const auto json = nlohmann::json::parse(run.out);  // alive for the loop (a temporary would not be)
        for (const auto& p : json["points"]) {
            EXPECT_GT(p["gaussian_curvature"].get<double>(), 0.0);
            EXPECT_GT(p["mean_curvature"].get<double>(), 0.0);
            double outward = 0.0;
            for (int i = 0; i < 3; ++i) {
                outward += p["normal"][i].get<double>() * p["position"][i].get<double>();
            }
            EXPECT_GT(outward, 0.0);
        }
    }
}

TEST(CliEval, PointsFileGivesOneRowPerPointAndOutputIsAtomic) {
    const std::string points = write_points("good.txt", "# face u v\n0 0.5 0.5\n\n5 0.25 0.75  # comment\n");
    const std::string cube = test::find_bundled("cube").path.string();
    const CliRun table = limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", points});
    ASSERT_EQ(table.exit_code, 0) << table.err;
    EXPECT_EQ(count_lines(table.out), 2 + 2);  // two header lines
    EXPECT_EQ(table.out.find("nan"), std::string::npos);
    const fs::path out = temp_dir() / "points.json";
    const CliRun written = limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", points, "-o", out.string()});
    ASSERT_EQ(written.exit_code, 0) << written.err;
    const auto json = nlohmann::json::parse(slurp(out));
    ASSERT_EQ(json["points"].size(), 2U);
    EXPECT_EQ(json["points"][1]["face"], 5);
    EXPECT_EQ(json["points"][1]["u"], 0.25);
}

TEST(CliEval, BadPointsFilesNameTheFileAndLine) {
    const std::string cube = test::find_bundled("cube").path.string();
    const std::string tri = test::find_bundled("icosahedron").path.string();
    struct Case {
        std::string mesh;
        std::string scheme;
        std::string text;
        std::string expected;  // after "error: FILE"
    };
    const std::vector<Case> cases{
        {cube, "catmull-clark", "0 0.5 0.5\n0 0.5\n", ":2: expected 'face u v'"},
        {cube, "catmull-clark", "0 0.5 0.5 7\n", ":1: expected 'face u v'"},
        {cube, "catmull-clark", "# x\n6 0.5 0.5\n", ":2: ptex face 6 out of range"},
        {cube, "catmull-clark", "-1 0.5 0.5\n", ":1: ptex face -1 out of range"},
        {cube, "catmull-clark", "0 1.5 0.5\n", ":1: (u, v) = (1.5, 0.5) is outside the unit square"},
        {tri, "loop", "0 0.75 0.75\n", ":1: (u, v) = (0.75, 0.75) is outside the triangle"},
    };
    int number = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string path = write_points("bad" + std::to_string(number++) + ".txt", c.text);
        const fs::path out = temp_dir() / "never.json";
        const CliRun run = limsurf({"eval", c.mesh, "--scheme", c.scheme, "--points", path, "-o", out.string()});
        EXPECT_EQ(run.exit_code, 1);
        EXPECT_EQ(run.err.rfind("error: " + path + c.expected, 0), 0U) << run.err;
        EXPECT_EQ(count_lines(run.err), 1) << run.err;
        EXPECT_FALSE(fs::exists(out));
    }
    const CliRun missing = limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", "/nonexistent/points.txt"});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_EQ(missing.err, "error: /nonexistent/points.txt: cannot open: No such file or directory\n");
    const CliRun directory = limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", temp_dir().string()});
    EXPECT_EQ(directory.exit_code, 1);
    EXPECT_EQ(directory.err, "error: " + temp_dir().string() + ": cannot open: is a directory\n");
    const fs::path empty = temp_dir() / "no_points.txt";
    std::ofstream(empty) << "# nothing but a comment\n";
    const CliRun none = limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", empty.string()});
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_EQ(none.err, "error: " + empty.string() + ": no points (expected lines 'face u v')\n");
}

TEST(CliEval, UsageErrorsExitTwo) {
    const std::string cube = test::find_bundled("cube").path.string();
    EXPECT_EQ(limsurf({"eval", cube, "--scheme", "catmull-clark"}).exit_code, 2);  // neither --points nor --grid
    EXPECT_EQ(limsurf({"eval", cube, "--scheme", "bilinear", "--grid", "2"}).exit_code, 2);  // no limit evaluation
    EXPECT_EQ(limsurf({"eval", cube, "--grid", "2"}).exit_code, 2);                          // --scheme is required
    EXPECT_EQ(limsurf({"eval", cube, "--scheme", "catmull-clark", "--grid", "2", "--points", "x"}).exit_code, 2);
    EXPECT_EQ(limsurf({"measure", cube, "--scheme", "catmull-clark", "--degree", "0"}).exit_code, 2);
}

TEST(CliEval, LoopOnQuadsIsAnInputError) {
    const CliRun run = limsurf({"eval", test::find_bundled("cube").path.string(), "--scheme", "loop", "--grid", "1"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_EQ(run.err.rfind("error: ", 0), 0U) << run.err;
}

// The Doo–Sabin cube encloses exactly 6241/9920 (volume-trilinear-forms); measure with a
// fine rule reproduces it.
TEST(CliMeasure, DooSabinCubeEnclosesThePublishedVolume) {
    const CliRun run = limsurf({"measure", test::find_bundled("cube").path.string(), "--scheme", "doo-sabin",
                                "--degree", "14", "--tiles", "12", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_NEAR(json["volume"].get<double>(), 6241.0 / 9920.0, 1e-10);
}

TEST(CliMeasure, CubeJsonHasTheKeysAndTheKnownValues) {
    const CliRun run = limsurf({"measure", test::find_bundled("cube").path.string(), "--scheme", "catmull-clark",
                                "--degree", "10", "--tiles", "8", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["closed"], true);
    // Richardson-extrapolated polyhedral values of deep subdivision (tests/quadrature/integrals_test.cpp).
    EXPECT_NEAR(json["area"].get<double>(), 2.29939658944542, 1e-8);
    EXPECT_NEAR(json["volume"].get<double>(), 0.327552379564745, 1e-8);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(json["centroid"][i].get<double>(), 0.0, 1e-12);
        EXPECT_NEAR(json["surface_centroid"][i].get<double>(), 0.0, 1e-12);
    }
    EXPECT_LT(json["error_estimate"]["area"].get<double>(), 1e-7);
    EXPECT_LT(json["error_estimate"]["volume"].get<double>(), 1e-7);
    EXPECT_TRUE(json["error_estimate"].contains("centroid"));
}

TEST(CliMeasure, OpenSurfacesHaveNoVolume) {
    const auto grid = test::find_bundled("quad_grid").path.string();
    const CliRun json_run = limsurf({"measure", grid, "--scheme", "catmull-clark", "--json"});
    ASSERT_EQ(json_run.exit_code, 0) << json_run.err;
    const auto json = nlohmann::json::parse(json_run.out);
    EXPECT_EQ(json["closed"], false);
    EXPECT_NEAR(json["area"].get<double>(), 4.0, 1e-12);  // the limit of a planar grid with straight sides
    EXPECT_TRUE(json["volume"].is_null());
    EXPECT_TRUE(json["error_estimate"]["volume"].is_null());
    const CliRun text = limsurf({"measure", grid, "--scheme", "catmull-clark"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("volume            not defined"), std::string::npos) << text.out;
}

}  // namespace
}  // namespace limsurf
