// `limsurf hodge`: the decomposition of a random 1-form and of a vector field given by formulas on genus 2
// (parts orthogonal, summing to the input, harmonic dimension 4 = 2g = b1), parts saved to files that add
// up to the input file, the VTK written, the reference on the subdivided mesh (SEC closer than DEC), the
// harmonic dimension on a torus and a sphere, and clear errors (no 1-form, a short file, a bad formula).
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "limsurf/io/vertex_field.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_hodge");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

nlohmann::json hodge(const std::vector<std::string>& extra) {
    std::vector<std::string> args{"hodge"};
    args.insert(args.end(), extra.begin(), extra.end());
    args.push_back("--json");
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return nlohmann::json::parse(run.out);
}

void expect_identities(const nlohmann::json& out) {
    for (const char* key : {"exact_coexact", "exact_harmonic", "coexact_harmonic"}) {
        EXPECT_LT(out.at("orthogonality").at(key).get<double>(), 1e-12) << key;
    }
    EXPECT_LT(out.at("sum_residual").get<double>(), 1e-14);
    EXPECT_LT(out.at("curl_of_exact").get<double>(), 1e-13);
    EXPECT_LT(out.at("harmonic_curl").get<double>(), 1e-11);
    EXPECT_LT(out.at("harmonic_divergence").get<double>(), 1e-11);
    EXPECT_EQ(out.at("harmonic_dimension").get<int>(), out.at("betti_1").get<int>());
}

TEST(CliHodge, RandomFormOnGenusTwoAndSavedParts) {
    const std::string prefix = (temp_dir() / "part_").string();
    const fs::path vtk = temp_dir() / "parts.vtk";
    const auto out = hodge({mesh("genus2"), "--scheme", "catmull-clark", "--method", "sec", "--level", "2", "--random",
                            "3", "--save-parts", prefix, "-o", vtk.string()});
    expect_identities(out);
    EXPECT_EQ(out.at("harmonic_dimension").get<int>(), 4);
    EXPECT_EQ(out.at("genus").get<int>(), 2);
    EXPECT_GT(out.at("harmonic_gap").get<double>(), 1e6);
    EXPECT_TRUE(fs::exists(vtk));
    // Pythagoras for the printed norms.
    const double n = out.at("norm").get<double>();
    const double e = out.at("exact_norm").get<double>();
    const double c = out.at("coexact_norm").get<double>();
    const double h = out.at("harmonic_norm").get<double>();
    EXPECT_NEAR(e * e + c * c + h * h, n * n, 1e-12 * n * n);
    // The saved parts decompose again into themselves: feed the exact part back in.
    const auto again = hodge({mesh("genus2"), "--scheme", "catmull-clark", "--method", "sec", "--level", "2",
                              "--one-form", prefix + "exact.txt", "--no-basis"});
    EXPECT_NEAR(again.at("exact_norm").get<double>(), e, 1e-12 * e);
    EXPECT_LT(again.at("coexact_norm").get<double>() + again.at("harmonic_norm").get<double>(), 1e-10 * e);
}

TEST(CliHodge, FieldFormulaAndReference) {
    const auto l2 = [](const std::string& method) {
        const auto out = hodge({mesh("genus2"), "--scheme", "catmull-clark", "--method", method, "--field",
                                "-y;x;sin(x)", "--reference-level", "2", "--no-basis"});
        EXPECT_LT(out.at("sum_residual").get<double>(), 1e-14);
        return out.at("reference").at("l2_relative").get<double>();
    };
    EXPECT_LT(l2("sec"), 0.5 * l2("dec"));
}

TEST(CliHodge, HarmonicDimensionIsTwiceTheGenus) {
    EXPECT_EQ(hodge({mesh("torus_8x10"), "--scheme", "loop", "--method", "dec", "--random", "1"})
                  .at("harmonic_dimension")
                  .get<int>(),
              2);
    EXPECT_EQ(hodge({mesh("icosahedron"), "--scheme", "loop", "--method", "sec", "--random", "1"})
                  .at("harmonic_dimension")
                  .get<int>(),
              0);
    EXPECT_EQ(hodge({mesh("annulus"), "--scheme", "catmull-clark", "--method", "dec", "--random", "1"})
                  .at("harmonic_dimension")
                  .get<int>(),
              1);  // b1 = 2g + b − 1 with natural boundary conditions
}

TEST(CliHodge, ClearErrors) {
    const CliRun none = limsurf({"hodge", mesh("genus2"), "--scheme", "catmull-clark"});
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_NE(none.err.find("hodge needs a 1-form"), std::string::npos);
    const fs::path short_file = temp_dir() / "short.txt";
    std::ofstream(short_file) << "1\n2\n";
    const CliRun bad =
        limsurf({"hodge", mesh("genus2"), "--scheme", "catmull-clark", "--one-form", short_file.string()});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("short.txt"), std::string::npos);
    const CliRun formula = limsurf({"hodge", mesh("genus2"), "--scheme", "catmull-clark", "--field", "x;y"});
    EXPECT_EQ(formula.exit_code, 1);
    EXPECT_NE(formula.err.find("three formulas"), std::string::npos);
}

}  // namespace
}  // namespace limsurf
