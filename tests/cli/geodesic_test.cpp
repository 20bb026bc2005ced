// `limsurf geodesic`: the JSON report (t = h_mean², sources, reference errors, SEC closer than DEC
// to the level-3 reference as in SEC §4.2), written fields and picture, and errors: a source out
// of range (named), a disconnected mesh, a quad mesh under loop, each exit 1 with one error line.
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
    static const fs::path dir = test::make_temp_dir("cli_geodesic");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

nlohmann::json run_json(const std::vector<std::string>& args) {
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
}

TEST(CliGeodesic, SecIsCloserThanDecToTheLevel3Reference) {
    std::vector<double> l2;
    for (const std::string method : {"dec", "sec"}) {
        const auto out = run_json({"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source", "0", "--method",
                                   method, "--reference-level", "3", "--json"});
        EXPECT_EQ(out.at("method"), method);
        EXPECT_EQ(out.at("reference").at("level"), 3);
        // genus2 has unit edges scaled by 0.5: t = h_mean² = 0.25.
        EXPECT_DOUBLE_EQ(out.at("mean_edge_length").get<double>(), 0.5);
        EXPECT_DOUBLE_EQ(out.at("t").get<double>(), 0.25);
        EXPECT_EQ(out.at("sources"), nlohmann::json::array({0}));
        l2.push_back(out.at("reference").at("l2_relative").get<double>());
    }
    EXPECT_GT(l2[0], 2.0 * l2[1]) << "dec " << l2[0] << " sec " << l2[1];
}

TEST(CliGeodesic, DecIsZeroAtTheSourcesAndTheTimeFactorScalesT) {
    const auto out = run_json({"geodesic", mesh("tri_torus"), "--scheme", "loop", "--source", "3", "--method", "dec",
                               "--time-factor", "4", "--json"});
    EXPECT_EQ(out.at("source_values").at(0).get<double>(), 0.0);
    EXPECT_NEAR(out.at("t").get<double>(), 4.0 * std::pow(out.at("mean_edge_length").get<double>(), 2), 1e-15);
    EXPECT_GT(out.at("distance_max").get<double>(), 0.0);
}

TEST(CliGeodesic, GradientIsLimitFromLevel3OnUnlessAGradientLevelIsGiven) {
    const std::vector<std::string> base{"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source",
                                        "0",        "--json"};
    const auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return run_json(args);
    };
    const auto limit = with({});
    EXPECT_EQ(limit.at("gradient"), "limit");
    EXPECT_TRUE(limit.at("gradient_level").is_null());
    const auto subdivided = with({"--gradient-level", "2"});
    EXPECT_EQ(subdivided.at("gradient"), "subdivided");
    EXPECT_EQ(subdivided.at("gradient_level"), 2);
    EXPECT_EQ(with({"--gradient", "subdivided"}).at("gradient_level"), 3);  // = --level
    EXPECT_EQ(with({"--level", "2"}).at("gradient"), "subdivided");
    EXPECT_EQ(with({"--level", "2", "--gradient", "limit"}).at("gradient"), "limit");
    EXPECT_EQ(with({"--method", "dec"}).at("gradient"), "control");
    // A finer rule moves the distance, but little (the rule's error, tested in geodesics_test).
    const double coarse = limit.at("distance_max").get<double>();
    const double fine = with({"--gradient-degree", "6"}).at("distance_max").get<double>();
    EXPECT_NE(coarse, fine);
    EXPECT_NEAR(coarse, fine, 0.03 * fine);
}

TEST(CliGeodesic, WritesFieldsAndAPicture) {
    const fs::path vtk = temp_dir() / "distance.vtk";
    const fs::path png = temp_dir() / "distance.png";
    const CliRun run = limsurf({"geodesic", mesh("quad_grid"), "--scheme", "catmull-clark", "--source", "12",
                                "--source", "0", "-o", vtk.string(), "--png", png.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("wrote"), std::string::npos);
    std::ifstream in(vtk);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("SCALARS distance"), std::string::npos);
    EXPECT_NE(text.find("SCALARS limit_distance"), std::string::npos);
    EXPECT_GT(fs::file_size(png), 1000u);
}

TEST(CliGeodesic, BadInputExitsWithOneClearLine) {
    const CliRun range = limsurf({"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source", "48"});
    EXPECT_EQ(range.exit_code, 1);
    EXPECT_NE(range.err.find("source vertex 48 is out of range"), std::string::npos) << range.err;
    const CliRun split = limsurf({"geodesic", mesh("tetra_and_cube"), "--scheme", "catmull-clark", "--source", "0"});
    EXPECT_EQ(split.exit_code, 1);
    EXPECT_NE(split.err.find("connected components"), std::string::npos) << split.err;
    const CliRun quads = limsurf({"geodesic", mesh("genus2"), "--scheme", "loop", "--source", "0"});
    EXPECT_EQ(quads.exit_code, 1);
    const CliRun missing = limsurf({"geodesic", mesh("genus2"), "--scheme", "catmull-clark"});
    EXPECT_NE(missing.exit_code, 0);
    const CliRun factor =
        limsurf({"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source", "0", "--time-factor", "-1"});
    EXPECT_EQ(factor.exit_code, 1);
    EXPECT_NE(factor.err.find("time factor"), std::string::npos) << factor.err;
    const CliRun level = limsurf({"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source", "0",
                                  "--gradient", "limit", "--gradient-level", "1"});
    EXPECT_EQ(level.exit_code, 1);
    EXPECT_NE(level.err.find("applies to the subdivided gradient only"), std::string::npos) << level.err;
    const CliRun name =
        limsurf({"geodesic", mesh("genus2"), "--scheme", "catmull-clark", "--source", "0", "--gradient", "faces"});
    EXPECT_NE(name.exit_code, 0);
}

}  // namespace
}  // namespace limsurf
