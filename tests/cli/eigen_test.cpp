// `limsurf eigen`: the Table 1 eigenvalues through --weights, the C2g0 spectrum in JSON, the
// characteristic map written as a mesh, and refusals (exit 1 naming the problem; usage errors 2).
#include <cmath>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/io/mesh_io.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_eigen");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

TEST(CliEigen, TunedWeightsGiveTableOnesEigenvalue) {
    const CliRun run = limsurf(
        {"eigen", "--scheme", "catmull-clark", "--valence", "5", "--weights", "13.9851,0.824885,0.824885", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_NEAR(out.at("subdominant").get<double>(), 0.585, 5e-6);  // Table 1, saddle
    EXPECT_EQ(out.at("size").get<int>(), 31);
    EXPECT_TRUE(out.at("tests").at("c1").at("passed").get<bool>());
    // The saddle set leaves the frequency-2 eigenvalue above λ²: curvature unbounded (the paper relaxes (30c)).
    EXPECT_FALSE(out.at("tests").at("bounded_curvature").at("passed").get<bool>());
}

TEST(CliEigen, ClassicalCatmullClarkInText) {
    const CliRun run = limsurf({"eigen", "--scheme", "catmull-clark", "--valence", "7"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("C1 (Reif)           yes"), std::string::npos) << run.out;
    EXPECT_FALSE(std::regex_search(run.out, std::regex(R"(\b(nan|inf)\b)"))) << run.out;
}

TEST(CliEigen, C2g0SpectrumAndCharacteristicMap) {
    const fs::path map = temp_dir() / "chi.obj";
    const CliRun run =
        limsurf({"eigen", "--scheme", "c2g0", "--valence", "3", "--characteristic-map", map.string(), "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_NEAR(out.at("subdominant").get<double>(), 0.25, 1e-12);
    EXPECT_EQ(out.at("subsubdominant_multiplicity").get<int>(), 3);
    EXPECT_TRUE(out.at("tests").at("c2_necessary").at("passed").get<bool>());
    const BuildResult written = read_mesh(map);
    EXPECT_GT(written.mesh.num_faces(), 0);
    EXPECT_TRUE(written.mesh.positions().col(2).isZero());
}

TEST(CliEigen, RefusalsNameTheProblem) {
    CliRun run = limsurf({"eigen", "--scheme", "c2g0", "--valence", "5"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("C2g0 has valences 3 and 6 only"), std::string::npos) << run.err;
    run = limsurf({"eigen", "--scheme", "loop", "--valence", "5", "--weights", "1,1,1"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("catmull-clark only"), std::string::npos) << run.err;
    run = limsurf({"eigen", "--scheme", "catmull-clark", "--valence", "5", "--weights", "1,nan,1"});
    EXPECT_EQ(run.exit_code, 1);
    run = limsurf({"eigen", "--scheme", "doo-sabin", "--valence", "5", "--characteristic-map",
                   (temp_dir() / "none.obj").string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_FALSE(fs::exists(temp_dir() / "none.obj"));
    run = limsurf({"eigen", "--scheme", "bilinear", "--valence", "4"});
    EXPECT_EQ(run.exit_code, 2);
    run = limsurf({"eigen", "--scheme", "loop", "--valence", "2"});
    EXPECT_EQ(run.exit_code, 1);
}

}  // namespace
}  // namespace limsurf
