// `limsurf vector-field`: a design on genus 2 whose JSON reports the constraints met to their weights, the
// VTK (glyph- and streamline-ready), the PNG and the saved 1-form written; the saved 1-form agrees with
// the library's design (the CLI only parses and prints); the reference on the subdivided mesh; and clear
// errors (exit 1, one line naming the element) for an out-of-range vertex or face, a stroke off the edges,
// a malformed constraint, a quad mesh under loop.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "limsurf/apps/vector_field.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_vector_field");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

TEST(CliVectorField, DesignsWritesAndAgreesWithTheLibrary) {
    const fs::path vtk = temp_dir() / "field.vtk";
    const fs::path png = temp_dir() / "field.png";
    const fs::path w = temp_dir() / "w.txt";
    const CliRun run = limsurf({"vector-field", mesh("genus2"), "--scheme",    "catmull-clark",   "--method",
                                "sec",          "--level",      "2",           "--source",        "0:1",
                                "--sink",       "30:1",         "--vorticity", "7:0.5:1e5",       "--vorticity",
                                "40:-0.5:1e5",  "--weight",     "1e5",         "--json",          "-o",
                                vtk.string(),   "--png",        png.string(),  "--save-one-form", w.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_EQ(out.at("edges").get<int>(), 100);
    EXPECT_EQ(out.at("genus").get<int>(), 2);
    EXPECT_EQ(out.at("constraints").size(), 4U);
    EXPECT_LT(out.at("max_residual").get<double>(), 1e-2);  // weight 1e5: met to O(1/weight) (measured 5.7e-3)
    EXPECT_EQ(out.at("vertex_mass").get<std::string>(), "exact");
    EXPECT_GT(out.at("solver_steps").get<int>(), 0);  // conjugate gradients: sec's M0 is not diagonal
    EXPECT_TRUE(out.at("warnings").empty());
    EXPECT_EQ(out.at("samples").at("count").get<int>(), 800);  // 50 quads, two levels
    EXPECT_TRUE(fs::exists(vtk));
    EXPECT_TRUE(fs::exists(png));
    // The library with the same constraints gives the same field.
    const BuildResult built = read_mesh(mesh("genus2"));
    VectorFieldConstraints c;
    c.sources = {{0, 1.0, 1e5}, {30, -1.0, 1e5}};
    c.vortices = {{7, 0.5, 1e5}, {40, -0.5, 1e5}};
    VectorFieldOptions o;
    o.inner_products.method = InnerProductMethod::Sec;
    o.inner_products.level = 2;
    const VectorFieldResult r =
        design_vector_field(built.mesh.topology(), built.mesh.positions(), SchemeKind::CatmullClark, c, o);
    const Eigen::VectorXd saved = read_vertex_values(w, 100);
    EXPECT_LT((saved - r.w).lpNorm<Eigen::Infinity>(), 1e-15 * r.w.lpNorm<Eigen::Infinity>() + 1e-300);
    EXPECT_EQ(out.at("energy").get<double>(), r.energy);
}

TEST(CliVectorField, ImbalancedSourcesWarn) {
    const CliRun run = limsurf({"vector-field", mesh("sphere_quads"), "--scheme", "catmull-clark", "--method", "dec",
                                "--source", "3:1", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_EQ(out.at("warnings").size(), 1U);
    EXPECT_EQ(out.at("source_imbalance").get<double>(), 1.0);
    EXPECT_NE(run.err.find("take up -1 spread out"), std::string::npos);
}

TEST(CliVectorField, ReferenceLevel) {
    const auto l2 = [](const std::string& method) {
        const CliRun run =
            limsurf({"vector-field", mesh("genus2"), "--scheme", "catmull-clark", "--method", method, "--vorticity",
                     "7:0.5", "--vorticity", "40:-0.5", "--reference-level", "2", "--json"});
        EXPECT_EQ(run.exit_code, 0) << run.err;
        return nlohmann::json::parse(run.out).at("reference").at("l2_relative").get<double>();
    };
    EXPECT_LT(l2("sec"), 0.2 * l2("dec"));
}

TEST(CliVectorField, ClearErrors) {
    const auto error = [](const std::vector<std::string>& extra) {
        std::vector<std::string> args{"vector-field", mesh("genus2"), "--scheme", "catmull-clark"};
        args.insert(args.end(), extra.begin(), extra.end());
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, 1);
        return run.err;
    };
    EXPECT_NE(error({"--source", "48:1"}).find("vertex 48 is out of range"), std::string::npos);
    EXPECT_NE(error({"--vorticity", "50:1"}).find("face 50 is out of range"), std::string::npos);
    EXPECT_NE(error({"--stroke", "0,40:1"}).find("not joined by an edge"), std::string::npos);
    EXPECT_NE(error({"--source", "a:1"}).find("is not a number"), std::string::npos);
    EXPECT_NE(error({"--source", "1"}).find("ELEMENT:VALUE"), std::string::npos);
    EXPECT_NE(error({}).find("at least one constraint"), std::string::npos);
    const CliRun loop = limsurf({"vector-field", mesh("genus2"), "--scheme", "loop", "--source", "0:1"});
    EXPECT_EQ(loop.exit_code, 1);
}

}  // namespace
}  // namespace limsurf
