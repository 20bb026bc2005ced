// `limsurf elasticity`: the seed's periodic cell with grains (a symmetric positive definite effective
// stiffness between the Voigt and Reuss bounds), the patch test of a homogeneous cell against the
// analytic C of plane strain and plane stress, the VTK and PNG files, and refusals of bad input.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_elasticity");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string bundled(const char* name) {
    return (test::mesh_dir() / name).string();
}

nlohmann::json run_json(const std::vector<std::string>& args) {
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return run.exit_code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
}

Eigen::Matrix3d matrix_of(const nlohmann::json& rows) {
    Eigen::Matrix3d C;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            C(i, j) = rows.at(i).at(j).get<double>();
        }
    }
    return C;
}

Eigen::Vector3d vector_of(const nlohmann::json& values) {
    return {values.at(0).get<double>(), values.at(1).get<double>(), values.at(2).get<double>()};
}

/// The analytic Voigt matrix (written out here, not taken from the library).
Eigen::Matrix3d analytic_C(double E, double nu, bool plane_stress) {
    Eigen::Matrix3d C;
    if (plane_stress) {
        C << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
        return E / (1 - nu * nu) * C;
    }
    C << 1 - nu, nu, 0, nu, 1 - nu, 0, 0, 0, (1 - 2 * nu) / 2;
    return E / ((1 + nu) * (1 - 2 * nu)) * C;
}

/// ε = sym(Fᵐ − I) in Voigt form (γ_xy = 2 ε_xy).
Eigen::Vector3d macro_strain(const Eigen::Matrix2d& F) {
    return {F(0, 0) - 1, F(1, 1) - 1, F(0, 1) + F(1, 0)};
}

std::string matrix_text(const Eigen::Matrix2d& F) {
    std::ostringstream out;
    out.precision(17);
    out << F(0, 0) << ',' << F(0, 1) << ';' << F(1, 0) << ',' << F(1, 1);
    return out.str();
}

/// A 3 × 3 grid of quads on [0, 3] × [0, 2] whose right side's middle vertices sit off the left side's heights.
std::string unmatched_grid() {
    const fs::path path = temp_dir() / "unmatched.obj";
    std::ofstream out(path);
    for (int j = 0; j <= 3; ++j) {
        for (int i = 0; i <= 3; ++i) {
            const double y = (i == 3 && j > 0 && j < 3) ? 2.0 * j / 3.0 + 0.1 : 2.0 * j / 3.0;
            out << "v " << i << ' ' << y << " 0\n";
        }
    }
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            const int a = j * 4 + i + 1;
            out << "f " << a << ' ' << a + 1 << ' ' << a + 5 << ' ' << a + 4 << '\n';
        }
    }
    return path.string();
}

// The seed's example (E = 1, ν = 0.3, Fᵐ = [[1, 0.05], [0.05, 1]], periodic) on the bundled block with
// stiffer grains: the effective stiffness is symmetric positive definite and lies between the Reuss and
// Voigt bounds as quadratic forms (bounds computed from the area fractions alone).
TEST(CliElasticity, SeedBlockHasSymmetricPositiveDefiniteStiffness) {
    const auto out = run_json({"elasticity", bundled("rve_block.obj"), "--E", "1", "--nu", "0.3", "--macro-strain",
                               "1,0.05;0.05,1", "--periodic", "--material", "grain:10,0.3", "--json"});
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.at("boundary"), "periodic");
    EXPECT_EQ(out.at("model"), "strain");
    ASSERT_EQ(out.at("materials").size(), 2u);
    EXPECT_GT(out.at("materials")[1].at("faces").get<int>(), 0);
    const auto& level = out.at("levels").at(0);
    const Eigen::Matrix3d C = matrix_of(level.at("effective_stiffness"));
    EXPECT_LT((C - C.transpose()).norm(), 1e-8 * C.norm()) << C;
    const Eigen::Matrix3d S = (C + C.transpose()) / 2;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(S);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0) << C;
    // The homogenised stress is C* times the macroscopic strain (linearity: one solve against three).
    const Eigen::Vector3d eps = macro_strain((Eigen::Matrix2d() << 1, 0.05, 0.05, 1).finished());
    EXPECT_LT((vector_of(level.at("homogenised_stress")) - C * eps).norm(), 1e-9 * (C * eps).norm());
    // Reuss ≤ C* ≤ Voigt.
    const auto& bounds = out.at("bounds");
    ASSERT_FALSE(bounds.is_null());
    const Eigen::Matrix3d voigt = matrix_of(bounds.at("voigt"));
    const Eigen::Matrix3d reuss = matrix_of(bounds.at("reuss"));
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(voigt - S).eigenvalues().minCoeff(), -1e-9);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S - reuss).eigenvalues().minCoeff(), -1e-9);
    // The grains make the cell stiffer than the matrix alone.
    EXPECT_GT(C(2, 2), analytic_C(1, 0.3, false)(2, 2));
}

// The centred circular inclusion: Reuss ≤ C* ≤ Voigt, and the in-plane bulk modulus
// κ* = (C*_11 + C*_12)/2 within the Hashin–Shtrikman bulk bounds, which hold for any two-phase
// geometry (not the shear bounds: a square array is not isotropic). κ* decreases with refinement
// (the discrete space grows, the energy under a prescribed mean strain falls).
TEST(CliElasticity, InclusionRespectsTheBounds) {
    const auto out = run_json(
        {"elasticity", bundled("square_inclusion.obj"), "--material", "inclusion:10,0.3", "--levels", "1", "--json"});
    ASSERT_FALSE(out.empty());
    const auto& bounds = out.at("bounds");
    ASSERT_FALSE(bounds.at("bulk_hashin_shtrikman").is_null());
    const double lower = bounds.at("bulk_hashin_shtrikman")[0].get<double>();
    const double upper = bounds.at("bulk_hashin_shtrikman")[1].get<double>();
    // Independent of the library's bounds: κ_HS- = κ1 + f2 / (1/(κ2 − κ1) + f1/(κ1 + μ1)), plane strain
    // κ = λ + μ, with the area fractions the command reports.
    const auto& area = out.at("levels")[1].at("material_area");
    const double f1 = area[0].get<double>() / (area[0].get<double>() + area[1].get<double>());
    const auto kappa_mu = [](double E, double nu) {
        const double mu = E / (2 * (1 + nu));
        const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
        return std::pair{lambda + mu, mu};
    };
    const auto [k1, m1] = kappa_mu(1.0, 0.3);
    const auto [k2, m2] = kappa_mu(10.0, 0.3);
    EXPECT_NEAR(lower, k1 + (1 - f1) / (1 / (k2 - k1) + f1 / (k1 + m1)), 1e-12);
    EXPECT_NEAR(upper, k2 + f1 / (1 / (k1 - k2) + (1 - f1) / (k2 + m2)), 1e-12);
    double previous = 1e300;
    for (const auto& level : out.at("levels")) {
        const Eigen::Matrix3d C = matrix_of(level.at("effective_stiffness"));
        const double kappa = (C(0, 0) + C(0, 1)) / 2;
        EXPECT_GT(kappa, lower);
        EXPECT_LT(kappa, upper);
        EXPECT_LT(kappa, previous);
        previous = kappa;
        const Eigen::Matrix3d S = (C + C.transpose()) / 2;
        EXPECT_GT(
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(matrix_of(bounds.at("voigt")) - S).eigenvalues().minCoeff(),
            -1e-9);
        EXPECT_GT(
            Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S - matrix_of(bounds.at("reuss"))).eigenvalues().minCoeff(),
            -1e-9);
    }
}

/// A homogeneous cell under Fᵐ: ũ = 0, so the homogenised stress is C ε to rounding, and the
/// effective stiffness is C itself.
void expect_patch_test(const std::string& mesh, const Eigen::Matrix2d& F, bool plane_stress,
                       const std::string& boundary = "periodic") {
    std::vector<std::string> args{"elasticity",     mesh,           "--E",        "2.5",
                                  "--nu",           "0.3",          "--boundary", boundary,
                                  "--macro-strain", matrix_text(F), "--json"};
    if (plane_stress) {
        args.push_back("--plane-stress");
    }
    const auto out = run_json(args);
    ASSERT_FALSE(out.empty());
    const Eigen::Matrix3d C = analytic_C(2.5, 0.3, plane_stress);
    const Eigen::Vector3d expected = C * macro_strain(F);
    const auto& level = out.at("levels").at(0);
    EXPECT_LT((vector_of(level.at("homogenised_stress")) - expected).norm(), 1e-10)
        << mesh << ' ' << boundary << (plane_stress ? " plane stress" : " plane strain");
    EXPECT_LT((vector_of(level.at("mean_strain")) - macro_strain(F)).norm(), 1e-10);
    EXPECT_LT((matrix_of(level.at("effective_stiffness")) - C).norm(), 1e-10 * C.norm());
}

TEST(CliElasticity, PatchTestOnARegularGrid) {
    const Eigen::Matrix2d seed = (Eigen::Matrix2d() << 1, 0.05, 0.05, 1).finished();
    for (const bool plane_stress : {false, true}) {
        expect_patch_test(bundled("quad_grid.obj"), seed, plane_stress);
        expect_patch_test(bundled("quad_grid.obj"), seed, plane_stress, "affine");
    }
}

// On the irregular block (extraordinary vertices, boundary and corner patches), all faces one material.
TEST(CliElasticity, PatchTestOnTheIrregularBlock) {
    const Eigen::Matrix2d seed = (Eigen::Matrix2d() << 1, 0.05, 0.05, 1).finished();
    // The issue's second Fᵐ: its H = Fᵐ − I has zero trace, so both models give σ = 2μ ε again.
    const Eigen::Matrix2d issue = (Eigen::Matrix2d() << 1.01, 0.02, 0, 0.99).finished();
    // A volumetric one, where plane strain and plane stress differ.
    const Eigen::Matrix2d volumetric = (Eigen::Matrix2d() << 1.01, 0.02, 0, 1.0).finished();
    for (const Eigen::Matrix2d& F : {seed, issue, volumetric}) {
        for (const bool plane_stress : {false, true}) {
            expect_patch_test(bundled("rve_block.obj"), F, plane_stress);
        }
    }
}

TEST(CliElasticity, PlaneStrainAndStressAgreeOnShearOnly) {
    const auto stress_of = [](const std::string& F, bool plane_stress) {
        std::vector<std::string> args{"elasticity", bundled("rve_block.obj"), "--macro-strain", F, "--no-stiffness",
                                      "--json"};
        if (plane_stress) {
            args.push_back("--plane-stress");
        }
        const auto out = run_json(args);
        return out.empty() ? Eigen::Vector3d::Zero().eval() : vector_of(out.at("levels")[0].at("homogenised_stress"));
    };
    const Eigen::Vector3d shear_strain = stress_of("1,0.05;0.05,1", false);
    const Eigen::Vector3d shear_stress = stress_of("1,0.05;0.05,1", true);
    EXPECT_LT((shear_strain - shear_stress).norm(), 1e-12);
    EXPECT_GT(shear_strain.norm(), 1e-3);
    const Eigen::Vector3d volume_strain = stress_of("1.01,0.02;0,1", false);
    const Eigen::Vector3d volume_stress = stress_of("1.01,0.02;0,1", true);
    EXPECT_GT((volume_strain - volume_stress).norm(), 1e-4);
}

/// The count after @p keyword on its line ("POINTS 123 double" -> 123), or -1.
long count_after(const std::string& text, const std::string& keyword) {
    const auto at = text.find("\n" + keyword + " ");
    if (at == std::string::npos) {
        return -1;
    }
    return std::stol(text.substr(at + keyword.size() + 2));
}

TEST(CliElasticity, WritesFieldsAndPicture) {
    const fs::path vtk = temp_dir() / "fields.vtk";
    const fs::path png = temp_dir() / "sxx.png";
    const auto out = run_json({"elasticity", bundled("rve_block.obj"), "--material", "grain:10,0.3", "-o", vtk.string(),
                               "--png", png.string(), "--resolution", "4", "--size", "320x240", "--json"});
    ASSERT_FALSE(out.empty());
    EXPECT_EQ(out.at("output"), vtk.string());
    EXPECT_EQ(out.at("png").at("field"), "sxx");
    const std::string text = test::slurp(vtk);
    ASSERT_EQ(text.rfind("# vtk DataFile Version", 0), 0u);
    const long points = count_after(text, "POINTS");
    EXPECT_EQ(points, out.at("field_points").get<long>());
    EXPECT_GT(count_after(text, "POLYGONS"), 0);
    EXPECT_EQ(count_after(text, "POINT_DATA"), points);
    for (const char* name : {"VECTORS displacement", "SCALARS stress_xx", "SCALARS stress_yy", "SCALARS stress_xy",
                             "SCALARS von_mises", "SCALARS strain_xx", "SCALARS material"}) {
        EXPECT_NE(text.find(name), std::string::npos) << name;
    }
    EXPECT_EQ(text.find("nan"), std::string::npos);
    // The PNG: signature and the IHDR's width and height (big-endian).
    std::ifstream in(png, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 33u);
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(bytes.substr(12, 4), "IHDR");
    const auto be32 = [&](std::size_t at) {
        std::uint32_t v = 0;
        for (std::size_t i = 0; i < 4; ++i) {
            v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
        }
        return v;
    };
    EXPECT_EQ(be32(16), 320u);
    EXPECT_EQ(be32(20), 240u);
}

TEST(CliElasticity, TextOutputListsLevels) {
    const CliRun run = limsurf({"elasticity", bundled("quad_grid.obj"), "--levels", "1"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("level 0"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("level 1"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("C*"), std::string::npos) << run.out;
}

// Clamped on the left side of [-1, 1]², pulled by t_x on the right: v = (x + 1, 0) is in the discrete
// space and vanishes on the clamped control vertices, so the Galerkin equations give
// ∫ σ_xx dA = a(u, v) = ∫_right t_x (x + 1) ds = 2 t_x · 2, a mean σ_xx of t_x exactly (the same
// quadrature on both sides), whatever the stress field looks like near the clamp.
TEST(CliElasticity, LoadedBlockBalancesItsTraction) {
    for (const bool plane_stress : {false, true}) {
        std::vector<std::string> args{"elasticity", bundled("quad_grid.obj"),
                                      "--boundary", "loaded",
                                      "--clamp",    "left",
                                      "--traction", "right:0.1,0",
                                      "--json"};
        if (plane_stress) {
            args.push_back("--plane-stress");
        }
        const auto out = run_json(args);
        ASSERT_FALSE(out.empty());
        EXPECT_TRUE(out.at("levels")[0].at("effective_stiffness").is_null());
        EXPECT_NEAR(out.at("levels")[0].at("homogenised_stress")[0].get<double>(), 0.1, 1e-9) << plane_stress;
    }
}

TEST(CliElasticity, BadInputIsRefused) {
    const std::string block = bundled("rve_block.obj");
    const auto refused = [](const std::vector<std::string>& args, const std::string& message, int code = 1) {
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, code) << run.err;
        EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    };
    refused({"elasticity", block, "--nu", "0.5"}, "nu");
    refused({"elasticity", block, "--E", "0"}, "E");
    refused({"elasticity", block, "--material", "grain:1,0.5"}, "--material");
    refused({"elasticity", block, "--material", "stone:2,0.3"}, "stone");
    refused({"elasticity", block, "--macro-strain", "1,0;0"}, "--macro-strain");
    refused({"elasticity", block, "--macro-strain", "1,0,0,1"}, "--macro-strain");
    refused({"elasticity", block, "--boundary", "loaded"}, "clamp");
    refused({"elasticity", block, "--clamp", "left"}, "--boundary loaded");
    refused({"elasticity", block, "--boundary", "loaded", "--clamp", "middle"}, "middle");
    refused({"elasticity", bundled("cube.obj")}, "cube.obj");
    refused({"elasticity", unmatched_grid()}, "unmatched.obj");
    refused({"elasticity", block, "-o", (temp_dir() / "f.obj").string()}, "f.obj");
    refused({"elasticity", block, "--boundary", "sliding"}, "sliding", 2);
    EXPECT_FALSE(fs::exists(temp_dir() / "f.obj"));
}

}  // namespace
}  // namespace limsurf
