// `limsurf poisson`: a closed solve (residual, mean removed, SEC far closer than DEC to the DEC
// reference on the subdivided mesh for a smooth right-hand side), an open solve with Dirichlet
// values and a written field, a right-hand side from a file, and errors: a bad formula, a short
// rhs file (naming the file), a quad mesh under loop exit 1; a missing --rhs exits 1.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "limsurf/io/mesh_io.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_poisson");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

double reference_l2(const std::string& method) {
    const CliRun run = limsurf({"poisson", mesh("sphere_tris"), "--scheme", "loop", "--method", method, "--rhs", "z",
                                "--reference-level", "4", "--json"});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_LE(out.at("residual").get<double>(), 1e-12);
    EXPECT_TRUE(out.at("closed").get<bool>());
    return out.at("reference").at("l2_relative").get<double>();
}

TEST(CliPoisson, SecIsCloserThanDecToTheFineReference) {
    const double dec = reference_l2("dec");
    const double sec = reference_l2("sec");
    EXPECT_LT(sec, dec / 10.0) << "dec " << dec << " sec " << sec;
    EXPECT_LT(reference_l2("decsnap"), dec);
}

// --method iga (Galerkin with the limit basis) on the same problem: as close to the reference as
// SEC (both are far below DEC; the level-4 DEC reference limits what can be seen).
TEST(CliPoisson, IgaIsAsCloseAsSecToTheFineReference) {
    const double dec = reference_l2("dec");
    const double iga = reference_l2("iga");
    EXPECT_LT(iga, dec / 10.0) << "dec " << dec << " iga " << iga;
}

// The patch test through the command: f = 0 and a linear boundary function give that linear
// function's control values everywhere (the limit basis reproduces it).
TEST(CliPoisson, IgaReproducesALinearFunctionOnAnOpenMesh) {
    const CliRun run =
        limsurf({"poisson", mesh("disk_ev5_quads"), "--scheme", "catmull-clark", "--method", "iga", "--rhs", "0",
                 "--boundary-value", "1+2*x", "--degree", "12", "--tiles", "10", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const BuildResult built = read_mesh(mesh("disk_ev5_quads"));
    const Eigen::VectorXd u = 1.0 + 2.0 * built.mesh.positions().col(0).array();
    EXPECT_NEAR(out.at("u_min").get<double>(), u.minCoeff(), 1e-9);
    EXPECT_NEAR(out.at("u_max").get<double>(), u.maxCoeff(), 1e-9);
    EXPECT_EQ(out.at("quadrature").at("degree").get<int>(), 12);
    const CliRun lumped = limsurf(
        {"poisson", mesh("disk_ev5_quads"), "--scheme", "catmull-clark", "--method", "iga", "--rhs", "0", "--lumped"});
    EXPECT_EQ(lumped.exit_code, 1);
    EXPECT_NE(lumped.err.find("--lumped"), std::string::npos) << lumped.err;
}

TEST(CliPoisson, OpenMeshWritesTheSolution) {
    const fs::path out = temp_dir() / "solution.vtk";
    const CliRun run = limsurf({"poisson", mesh("disk_ev5_quads"), "--scheme", "catmull-clark", "--rhs", "1",
                                "--boundary-value", "x", "-o", out.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("residual"), std::string::npos);
    std::ifstream in(out);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("SCALARS u"), std::string::npos);
}

TEST(CliPoisson, RightHandSideFromAFile) {
    const fs::path values = temp_dir() / "f.txt";
    {
        std::ofstream out(values);
        out << "# one value per vertex\n";
        for (int v = 0; v < 48; ++v) {
            out << (v % 2 == 0 ? 1.0 : -1.0) << '\n';
        }
    }
    const CliRun run =
        limsurf({"poisson", mesh("genus2"), "--scheme", "catmull-clark", "--rhs-file", values.string(), "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_LE(nlohmann::json::parse(run.out).at("residual").get<double>(), 1e-12);
    const fs::path short_file = temp_dir() / "short.txt";
    std::ofstream(short_file) << "1\n2\n";
    const CliRun bad =
        limsurf({"poisson", mesh("genus2"), "--scheme", "catmull-clark", "--rhs-file", short_file.string()});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_NE(bad.err.find("short.txt"), std::string::npos) << bad.err;
}

TEST(CliPoisson, ErrorsAreClear) {
    const CliRun formula = limsurf({"poisson", mesh("genus2"), "--scheme", "catmull-clark", "--rhs", "sin(x"});
    EXPECT_EQ(formula.exit_code, 1);
    EXPECT_NE(formula.err.find("--rhs"), std::string::npos) << formula.err;
    const CliRun quads = limsurf({"poisson", mesh("cube"), "--scheme", "loop", "--rhs", "x"});
    EXPECT_EQ(quads.exit_code, 1);
    EXPECT_NE(quads.err.find("cube.obj"), std::string::npos) << quads.err;
    const CliRun missing = limsurf({"poisson", mesh("genus2"), "--scheme", "catmull-clark"});
    EXPECT_EQ(missing.exit_code, 1);
    const CliRun creased = limsurf({"poisson", mesh("cube_creases"), "--scheme", "catmull-clark", "--rhs", "x"});
    EXPECT_EQ(creased.exit_code, 1);
    EXPECT_NE(creased.err.find("crease"), std::string::npos) << creased.err;
}

}  // namespace
}  // namespace limsurf
