// `limsurf plate`: the simply supported square against Navier through the command (uniform load,
// Table 2's two-wave load with its zero centre), clamped support, loads from per-vertex values, and
// refusals.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <tuple>
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

/// One value per vertex of square_plate() (vertex j * 5 + i at (2.5 i, 2.5 j)), from value(x, y).
template <class Value>
std::string plate_values(const std::string& name, Value value) {
    const fs::path path = temp_dir() / name;
    std::ofstream out(path);
    out << "# one load value per control vertex\n";
    out.precision(17);
    for (int j = 0; j <= 4; ++j) {
        for (int i = 0; i <= 4; ++i) {
            out << value(2.5 * i, 2.5 * j) << '\n';
        }
    }
    return path.string();
}

/// The deflections of every level of two runs agree to @p tolerance (relative).
void expect_same_deflections(const nlohmann::json& a, const nlohmann::json& b, double tolerance) {
    ASSERT_EQ(a.at("levels").size(), b.at("levels").size());
    for (std::size_t l = 0; l < a.at("levels").size(); ++l) {
        for (const char* key : {"centre_deflection", "quarter_deflection", "max_deflection"}) {
            const double x = a.at("levels")[l].at(key).get<double>();
            const double y = b.at("levels")[l].at(key).get<double>();
            EXPECT_NEAR(x, y, tolerance * std::abs(y)) << "level " << l << ' ' << key;
        }
    }
}

// Per-vertex load values are control values of the load, p_h = Σ p_i φ_i (b = M p), carried to
// each level by S0: a constant field is the uniform load and the control points' own x (the limit
// map reproduces it) is the load x, both exactly, so the deflections agree with --load to rounding.
TEST(CliPlate, LoadFromPerVertexValues) {
    const std::string constant = plate_values("constant.txt", [](double, double) { return 1e4; });
    const fs::path vtk = temp_dir() / "w_p.vtk";
    const CliRun file =
        limsurf({"plate", square_plate(), "--load-file", constant, "--levels", "2", "--json", "-o", vtk.string()});
    ASSERT_EQ(file.exit_code, 0) << file.err;
    const CliRun uniform = limsurf({"plate", square_plate(), "--load", "uniform", "--levels", "2", "--json"});
    ASSERT_EQ(uniform.exit_code, 0) << uniform.err;
    const auto out = nlohmann::json::parse(file.out);
    EXPECT_EQ(out.at("load"), "file");
    EXPECT_FALSE(out.at("levels")[0].contains("navier"));  // not compared: any load may come from a file
    expect_same_deflections(out, nlohmann::json::parse(uniform.out), 1e-10);
    std::ifstream written(vtk);
    const std::string text((std::istreambuf_iterator<char>(written)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("SCALARS p"), std::string::npos);
    EXPECT_NE(text.find("SCALARS w"), std::string::npos);

    const std::string linear = plate_values("linear.txt", [](double x, double) { return 1000.0 * x; });
    const CliRun from_file = limsurf({"plate", square_plate(), "--load-file", linear, "--levels", "2", "--json"});
    ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
    const CliRun formula = limsurf({"plate", square_plate(), "--load", "1000*x", "--levels", "2", "--json"});
    ASSERT_EQ(formula.exit_code, 0) << formula.err;
    expect_same_deflections(nlohmann::json::parse(from_file.out), nlohmann::json::parse(formula.out), 1e-10);
}

TEST(CliPlate, BadLoadFilesAreRefused) {
    const fs::path short_file = temp_dir() / "short_load.txt";
    std::ofstream(short_file) << "1\n2\n";
    CliRun run = limsurf({"plate", square_plate(), "--load-file", short_file.string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("short_load.txt"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("25 vertices"), std::string::npos) << run.err;
    const fs::path nan_file = temp_dir() / "nan_load.txt";
    {
        std::ofstream out(nan_file);
        for (int v = 0; v < 25; ++v) {
            out << (v == 2 ? "nan" : "1") << '\n';
        }
    }
    run = limsurf({"plate", square_plate(), "--load-file", nan_file.string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("nan_load.txt:3"), std::string::npos) << run.err;
    run = limsurf({"plate", square_plate(), "--load-file", (temp_dir() / "missing.txt").string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("missing.txt"), std::string::npos) << run.err;
    run = limsurf({"plate", square_plate(), "--load", "uniform", "--load-file", short_file.string()});
    EXPECT_EQ(run.exit_code, 2);
    run = limsurf({"plate", square_plate(), "--pressure", "5", "--load-file", short_file.string()});
    EXPECT_EQ(run.exit_code, 2);
}

// --tuned (iga-tuned-catmull-clark-weights §4): cup and saddle put Table 1's weights at the four
// valence-5 vertices of plate_ev35 (valence 3 keeps Catmull–Clark's); auto reports the cup pass,
// R per vertex, and follows R; the plate stays its bounding square (the Navier comparison holds).
TEST(CliPlate, TunedWeightsAtTheValenceFiveVertices) {
    const std::string mesh = (test::mesh_dir() / "plate_ev35.obj").string();
    for (const auto& [shape, alpha, beta] :
         {std::tuple{"cup", 13.4575, 0.999938}, std::tuple{"saddle", 13.9851, 0.824885}}) {
        const CliRun run = limsurf({"plate", mesh, "--tuned", shape, "--json"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const auto out = nlohmann::json::parse(run.out);
        const auto& vertices = out.at("levels").at(0).at("tuned_vertices");
        ASSERT_EQ(vertices.size(), 4u);
        for (const auto& v : vertices) {
            EXPECT_EQ(v.at("valence"), 5);
            EXPECT_EQ(v.at("shape"), shape);
            EXPECT_NEAR(v.at("alpha").get<double>(), alpha, 5e-5);
            EXPECT_NEAR(v.at("beta").get<double>(), beta, 1e-6);
        }
        EXPECT_TRUE(out.at("levels").at(0).contains("navier"));
    }
    const CliRun run = limsurf({"plate", mesh, "--load", "sinusoidal", "--tuned", "auto", "--levels", "1", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    for (const auto& level : out.at("levels")) {
        EXPECT_TRUE(level.at("first_pass").contains("navier"));
        for (const auto& v : level.at("tuned_vertices")) {
            const double R = v.at("decomposition").at("ratio").get<double>();
            EXPECT_GT(R, 0.0);
            EXPECT_EQ(v.at("shape"), R >= 1.0 ? "cup" : "saddle");
        }
    }
}

TEST(CliPlate, TuningWithoutExtraordinaryVerticesWarns) {
    const CliRun run = limsurf({"plate", square_plate(), "--tuned", "auto", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("warning:"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("valence 5"), std::string::npos) << run.err;
    EXPECT_EQ(limsurf({"plate", square_plate(), "--tuned", "bowl"}).exit_code, 2);
}

}  // namespace
}  // namespace limsurf
