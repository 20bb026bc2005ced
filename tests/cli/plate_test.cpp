// `limsurf plate`: the simply supported square against Navier through the command (uniform load,
// Table 2's two-wave load with its zero centre), clamped support, loads from per-vertex values, and
// refusals.
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"
#include "support/timing.h"

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

/// The 5 × 5 vertices of the seed's square plate, L = 10, as OBJ lines.
void square_vertices(std::ostream& out) {
    for (int j = 0; j <= 4; ++j) {
        for (int i = 0; i <= 4; ++i) {
            out << "v " << 2.5 * i << ' ' << 2.5 * j << " 0\n";
        }
    }
}

/// The quads of a grid of nx × ny cells whose (nx + 1) × (ny + 1) vertices come row by row, as OBJ lines.
void grid_quads(std::ostream& out, int nx, int ny) {
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const int a = j * (nx + 1) + i + 1;
            out << "f " << a << ' ' << a + 1 << ' ' << a + nx + 2 << ' ' << a + nx + 1 << '\n';
        }
    }
}

/// The seed's square plate as a 4 × 4 quad grid.
std::string square_plate() {
    const fs::path path = temp_dir() / "square.obj";
    std::ofstream out(path);
    square_vertices(out);
    grid_quads(out, 4, 4);
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

/// The same square triangulated (every quad split along one diagonal), its four corners tagged
/// sharp: under Loop's rules only the valence-2 corners would stay corners, and a rounded corner
/// makes the plate no longer its bounding rectangle.
std::string triangulated_square_plate() {
    const fs::path path = temp_dir() / "square_tris.obj";
    std::ofstream out(path);
    square_vertices(out);
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            const int a = j * 5 + i + 1;
            out << "f " << a << ' ' << a + 1 << ' ' << a + 6 << "\nf " << a << ' ' << a + 6 << ' ' << a + 5 << '\n';
        }
    }
    out << "t corner 4/1/0 0 4 20 24 10.0\n";
    return path.string();
}

// Loop plates converge to Navier's deflection, but slowly: on the triangulated square the L2 error
// halves per level (2.0-2.4× measured over levels 0-4) and the energy error falls by about √2
// (1.42-1.53×), where Catmull–Clark on the quad square gains 18-20× and 4.4-4.6× — with w = 0 on
// the boundary control values Loop's space approximates smooth plates only to O(h²) near the edge
// (docs/fem.md). Without the corner tags the limit plate is not the square: no comparison.
TEST(CliPlate, LoopPlatesConvergeToNavier) {
    const CliRun run = limsurf({"plate", triangulated_square_plate(), "--scheme", "loop", "--levels", "3", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_EQ(out.at("scheme"), "loop");
    const auto& levels = out.at("levels");
    ASSERT_EQ(levels.size(), 4u);
    for (std::size_t l = 1; l < levels.size(); ++l) {
        const auto& coarse = levels[l - 1].at("navier");
        const auto& fine = levels[l].at("navier");
        EXPECT_GT(coarse.at("l2_relative_error").get<double>() / fine.at("l2_relative_error").get<double>(), 1.8);
        EXPECT_GT(coarse.at("energy_relative_error").get<double>() / fine.at("energy_relative_error").get<double>(),
                  1.3);
    }
    EXPECT_LT(levels[3].at("navier").at("l2_relative_error").get<double>(), 0.025);
    // Untagged corners are rounded by Loop's rules: no comparison, said in the text output too.
    const fs::path untagged = test::mesh_dir() / "tri_grid.obj";
    const CliRun text = limsurf({"plate", untagged.string(), "--scheme", "loop"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("not compared: the plate is not its bounding rectangle"), std::string::npos) << text.out;
    // Tuned weights are Catmull–Clark's; a quad mesh is not Loop's.
    EXPECT_EQ(limsurf({"plate", triangulated_square_plate(), "--scheme", "loop", "--tuned", "cup"}).exit_code, 1);
    EXPECT_EQ(limsurf({"plate", square_plate(), "--scheme", "loop"}).exit_code, 1);
}

// A plate far from its bounding rectangle (a corner of the square 80 000 away; fuzz/commands.py
// found plate_sym): the comparison is not made, and Navier's series — 10⁵ terms a point for a box
// that long — is not summed at every sample either (it was: a minute).
TEST(CliPlate, APlateFarFromItsBoxSkipsNavierAtOnce) {
    const fs::path path = temp_dir() / "stretched.obj";
    {
        std::ofstream out(path);
        out << "v 80000 0 0\n";
        for (int j = 0; j <= 4; ++j) {
            for (int i = j == 0 ? 1 : 0; i <= 4; ++i) {
                out << "v " << 2.5 * i << ' ' << 2.5 * j << " 0\n";
            }
        }
        grid_quads(out, 4, 4);
    }
    const auto start = std::chrono::steady_clock::now();
    const CliRun run = limsurf({"plate", path.string(), "--json"});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    EXPECT_EQ(out.at("navier"), "not compared: the plate is not its bounding rectangle") << run.out;
    EXPECT_FALSE(out.at("levels")[0].contains("navier")) << run.out;
    EXPECT_LT(seconds, 2.0 * test::time_scale);
}

TEST(CliPlate, ALongRectangleIsComparedWithTheStripQuickly) {
    // A 1 × 400 rectangle (4 × 8 quads stretched): the exact deflection is Lévy's series, ~300 terms a
    // point at any aspect ratio (Navier's double series needed ~10⁶ here); away from the short ends the
    // plate bends as a strip, w = 5 p a⁴ / (384 D) across its middle.
    const fs::path path = temp_dir() / "long.obj";
    {
        std::ofstream out(path);
        for (int j = 0; j <= 8; ++j) {
            for (int i = 0; i <= 4; ++i) {
                out << "v " << 0.25 * i << ' ' << 50.0 * j << " 0\n";
            }
        }
        grid_quads(out, 4, 8);
    }
    const auto start = std::chrono::steady_clock::now();
    const CliRun run = limsurf({"plate", path.string(), "--levels", "2", "--json"});
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const double D = out.at("bending_rigidity").get<double>();
    const auto& levels = out.at("levels");
    ASSERT_EQ(levels.size(), 3u);
    EXPECT_NEAR(levels[2].at("navier").at("centre_deflection").get<double>(), 5.0 * 1e4 / (384.0 * D), 1e-12 * 1e4 / D)
        << run.out;
    // The centre converges fast (measured 5.0e-2, 4.1e-3, 2.7e-5); L2 slowly, the quads 50 long against
    // the boundary layers at the short ends (0.25, 0.17, 0.11).
    EXPECT_LT(std::abs(levels[2].at("navier").at("centre_relative_error").get<double>()), 1e-4) << run.out;
    for (int l = 1; l <= 2; ++l) {
        EXPECT_LT(levels[l].at("navier").at("l2_relative_error").get<double>(),
                  levels[l - 1].at("navier").at("l2_relative_error").get<double>())
            << run.out;
    }
    EXPECT_LT(seconds, 2.0 * test::time_scale);
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

// A rotationally symmetric plate (the regular pentagonal disk under uniform load) has no saddle
// part at its valence-5 centre: R = inf, which JSON cannot hold — the command printed "not a
// finite number (an overflow)" and exited 1. Now R is null with the verdict beside it.
TEST(CliPlate, APureCupHasAnInfiniteRatioAndItsVerdict) {
    const std::string mesh = (test::mesh_dir() / "disk_ev5_quads.obj").string();
    const CliRun run = limsurf({"plate", mesh, "--tuned", "auto", "--levels", "1", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    for (const auto& level : nlohmann::json::parse(run.out).at("levels")) {
        const auto& v = level.at("tuned_vertices").at(0);
        const auto& d = v.at("decomposition");
        EXPECT_TRUE(d.at("ratio").is_null());
        EXPECT_TRUE(d.at("has_quadratic_part").get<bool>());
        EXPECT_TRUE(d.at("cup_dominates").get<bool>());
        EXPECT_EQ(d.at("k4").get<double>(), 0.0);
        EXPECT_EQ(d.at("k5").get<double>(), 0.0);
        EXPECT_NE(d.at("k3").get<double>(), 0.0);
        EXPECT_EQ(v.at("shape"), "cup");
    }
    const CliRun text = limsurf({"plate", mesh, "--tuned", "auto"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("R = inf (no saddle part)"), std::string::npos) << text.out;
}

/// The Hessian (w_xx, w_yy, w_xy) of Navier's deflection of the simply supported square [0, 10]² up
/// to a common factor (R does not see it): the uniform load's double series over odd m, n, or the
/// sinusoidal load sin(2πx/10) sin(2πy/10) (Table 2), whose deflection is that same product.
Eigen::Matrix2d navier_hessian(const std::string& load, double x, double y) {
    const double pi = std::numbers::pi, L = 10.0;
    Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
    if (load == "sinusoidal") {
        const double a = 2.0 * pi / L, s = std::sin(a * x) * std::sin(a * y), c = std::cos(a * x) * std::cos(a * y);
        H << -s, c, c, -s;
        return H;
    }
    for (int m = 1; m <= 401; m += 2) {
        for (int n = 1; n <= 401; n += 2) {
            const double a = m * pi / L, b = n * pi / L, w = 1.0 / (m * n * std::pow(m * m + n * n, 2));
            const double sxy = std::sin(a * x) * std::sin(b * y), cxy = std::cos(a * x) * std::cos(b * y);
            H(0, 0) -= w * a * a * sxy;
            H(1, 1) -= w * b * b * sxy;
            H(0, 1) += w * a * b * cxy;
        }
    }
    H(1, 0) = H(0, 1);
    return H;
}

/// R of (38) that Navier's solution has at a tuned vertex: its Hessian at the vertex's limit point,
/// taken to the vertex's characteristic coordinates through the decomposition's tangents (JᵀHJ =
/// 2[[k₃+k₄, k₅], [k₅, k₃−k₄]]).
double navier_ratio(const std::string& load, const nlohmann::json& decomposition) {
    const auto& position = decomposition.at("position");
    const auto& tangents = decomposition.at("tangents");
    Eigen::Matrix2d J;
    J << tangents.at(0).at(0).get<double>(), tangents.at(1).at(0).get<double>(),  //
        tangents.at(0).at(1).get<double>(), tangents.at(1).at(1).get<double>();
    const Eigen::Matrix2d G =
        J.transpose() * navier_hessian(load, position.at(0).get<double>(), position.at(1).get<double>()) * J;
    const double k3 = (G(0, 0) + G(1, 1)) / 4.0, k4 = (G(0, 0) - G(1, 1)) / 4.0, k5 = G(0, 1) / 2.0;
    return k3 * k3 / (k4 * k4 + k5 * k5) * 1.3 / 0.7;
}

// The seed's §4 verdicts (iga-tuned-catmull-clark-weights, Figs. 10, 12, 14) on its Fig. 8 stand-ins,
// decided at the paper's levels: plate_sym level 2, saddle at all four valence-5 vertices under the
// uniform load (paper R = 0.766) and cup under the sinusoidal one (R = 29.2); plate_flip level 3,
// one cup (P6, R = 85.8) and one saddle vertex (P12, R = 0.0463). The independent witness is Navier's
// own R at each vertex (navier_ratio): the same verdict, and R within a factor 2.5 — (37) reads the
// solution's control values as samples of the quadratics, the limit surface is what Navier matches,
// which moves R by a factor of 1.5-1.9 on these meshes. The second pass lowers both errors.
TEST(CliPlate, TheSeedsVerdictsOnItsFigureEightStandIns) {
    struct Example {
        const char* mesh;
        const char* load;
        int level;
        int cups, saddles;
    };
    for (const Example& ex : {Example{"plate_sym", "uniform", 2, 0, 4}, Example{"plate_sym", "sinusoidal", 2, 4, 0},
                              Example{"plate_flip", "sinusoidal", 3, 1, 1}}) {
        SCOPED_TRACE(testing::Message() << ex.mesh << ", " << ex.load << " load");
        const std::string mesh = (test::mesh_dir() / (std::string(ex.mesh) + ".obj")).string();
        const std::string level = std::to_string(ex.level);
        const CliRun tuned =
            limsurf({"plate", mesh, "--load", ex.load, "--levels", level, "--tuned", "auto", "--json"});
        const CliRun classical = limsurf({"plate", mesh, "--load", ex.load, "--levels", level, "--json"});
        ASSERT_EQ(tuned.exit_code, 0) << tuned.err;
        ASSERT_EQ(classical.exit_code, 0) << classical.err;
        const auto out = nlohmann::json::parse(tuned.out), reference = nlohmann::json::parse(classical.out);
        const auto& at_level = out.at("levels").at(static_cast<std::size_t>(ex.level));
        int cups = 0, saddles = 0;
        for (const auto& v : at_level.at("tuned_vertices")) {
            ASSERT_EQ(v.at("valence"), 5);
            const auto& d = v.at("decomposition");
            const double R = d.at("ratio").get<double>(), exact = navier_ratio(ex.load, d);
            SCOPED_TRACE(testing::Message() << "vertex " << v.at("vertex") << ": R " << R << ", Navier's " << exact);
            (R >= 1.0 ? cups : saddles) += 1;
            EXPECT_EQ(v.at("shape"), R >= 1.0 ? "cup" : "saddle");
            EXPECT_EQ(R >= 1.0, exact >= 1.0);
            EXPECT_LT(std::abs(std::log(R / exact)), std::log(2.5));
        }
        EXPECT_EQ(cups, ex.cups);
        EXPECT_EQ(saddles, ex.saddles);
        // Level 0 is decomposed one level finer and scaled back: the geometry's part of the limit
        // point and tangents is exactly level 1's (the tangents of the finer one-ring are λ = 0.55
        // times the coarser's, the cup pass's λ).
        std::size_t matched = 0;  // a vertex keeps its number when refined
        for (const auto& coarse : out.at("levels").at(0).at("tuned_vertices")) {
            for (const auto& fine : out.at("levels").at(1).at("tuned_vertices")) {
                if (fine.at("vertex") != coarse.at("vertex")) {
                    continue;
                }
                ++matched;
                const auto& a = coarse.at("decomposition");
                const auto& b = fine.at("decomposition");
                for (int c = 0; c < 2; ++c) {
                    EXPECT_NEAR(b.at("position").at(c).get<double>(), a.at("position").at(c).get<double>(), 1e-12);
                    for (int t = 0; t < 2; ++t) {
                        EXPECT_NEAR(b.at("tangents").at(t).at(c).get<double>(),
                                    0.55 * a.at("tangents").at(t).at(c).get<double>(), 1e-10);
                    }
                }
            }
        }
        EXPECT_EQ(matched, static_cast<std::size_t>(ex.cups + ex.saddles));
        const auto& errors = at_level.at("navier");
        const auto& before = reference.at("levels").at(static_cast<std::size_t>(ex.level));
        for (const char* key : {"l2_relative_error", "energy_relative_error"}) {
            EXPECT_LT(errors.at(key).get<double>(), before.at("navier").at(key).get<double>()) << key;
        }
    }
}

// --decide-level K (the paper's §4: decide on level 2 or 3, keep the choice): one cup pass, on level
// K, chooses for every level; on a level the per-level run decides alike it gives the same numbers.
TEST(CliPlate, DecidingOnceKeepsTheChoiceOnEveryLevel) {
    const std::string mesh = (test::mesh_dir() / "plate_flip.obj").string();
    const auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args{"plate", mesh, "--load", "sinusoidal", "--tuned", "auto", "--json"};
        args.insert(args.end(), extra.begin(), extra.end());
        const CliRun r = limsurf(args);
        EXPECT_EQ(r.exit_code, 0) << r.err;
        return nlohmann::json::parse(r.out);
    };
    const auto each = run({"--levels", "2"});
    const auto once = run({"--levels", "2", "--decide-level", "2"});
    const auto beyond = run({"--levels", "1", "--decide-level", "2"});  // decided on a level not reported
    EXPECT_TRUE(each.at("decide_level").is_null());
    EXPECT_EQ(once.at("decide_level"), 2);
    const auto& decided = once.at("levels").at(2).at("tuned_vertices");
    ASSERT_EQ(decided.size(), 2u);
    for (const auto* out : {&once, &beyond}) {
        for (const auto& level : out->at("levels")) {
            const int l = level.at("level").get<int>();
            SCOPED_TRACE(testing::Message() << "level " << l << (out == &beyond ? " of --levels 1" : ""));
            EXPECT_EQ(level.contains("first_pass"), out == &once && l == 2);
            EXPECT_EQ(level.at("tuned_vertices"), decided);
            // plate_flip's verdicts are the same on every level, so every level solves as the per-level run.
            const auto& alike = each.at("levels").at(static_cast<std::size_t>(l));
            for (std::size_t i = 0; i < decided.size(); ++i) {
                EXPECT_EQ(alike.at("tuned_vertices").at(i).at("shape"), decided.at(i).at("shape"));
            }
            EXPECT_EQ(level.at("navier"), alike.at("navier"));
        }
    }
    EXPECT_EQ(limsurf({"plate", mesh, "--decide-level", "2"}).exit_code, 2);
    EXPECT_EQ(limsurf({"plate", mesh, "--tuned", "cup", "--decide-level", "2"}).exit_code, 2);
    EXPECT_EQ(limsurf({"plate", mesh, "--tuned", "auto", "--decide-level", "7"}).exit_code, 2);
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
