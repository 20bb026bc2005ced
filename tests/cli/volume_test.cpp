// `limsurf volume`: the exact volume (the Doo–Sabin cube's 6241/9920, the Loop tetrahedron's
// published value), polyhedral levels approaching it, --moments (centroid and inertia by
// quadrature, checked on a symmetric mesh and against the exact volume), and errors: an open,
// creased or non-orientable mesh exits 1 naming the file; usage errors exit 2.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
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
    static const fs::path dir = test::make_temp_dir("cli_volume");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

/// A regular tetrahedron with unit edges as an OBJ file.
std::string regular_tetrahedron() {
    const fs::path path = temp_dir() / "regular_tetrahedron.obj";
    const double h = std::sqrt(2.0 / 3.0);
    const double r = 1.0 / std::sqrt(3.0);
    std::ofstream out(path);
    out.precision(17);
    out << "v " << r << " 0 0\n"
        << "v " << -r / 2 << " 0.5 0\n"
        << "v " << -r / 2 << " -0.5 0\n"
        << "v 0 0 " << h << "\n"
        << "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    return path.string();
}

TEST(CliVolume, DooSabinCubeIsTheRationalOfThePaper) {
    const CliRun run = limsurf({"volume", mesh("cube"), "--scheme", "doo-sabin", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    // The bundled cube has unit edges.
    EXPECT_NEAR(out.at("volume").get<double>(), 6241.0 / 9920.0, 1e-15);
    const auto& levels = out.at("polyhedral");
    ASSERT_EQ(levels.size(), 4U);  // levels 0..3
    // Polyhedral volumes approach the limit volume monotonically here (Doo–Sabin cuts corners).
    double previous = 1.0;
    for (const auto& level : levels) {
        const double difference = std::abs(level.at("relative_difference").get<double>());
        EXPECT_LT(difference, previous);
        previous = difference;
    }
}

TEST(CliVolume, LoopRegularTetrahedronIsThePublishedValue) {
    const CliRun run = limsurf({"volume", regular_tetrahedron(), "--scheme", "loop", "--json", "--levels", "1"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    // 44192429513855101 / (6865302375425894400 √2), the numerator split to stay exact in double.
    const long double numerator = 44192429513855101.0L;
    const long double expected = numerator / (6865302375425894400.0L * std::sqrt(2.0L));
    EXPECT_NEAR(out.at("volume").get<double>(), static_cast<double>(expected), 1e-14 * static_cast<double>(expected));
}

TEST(CliVolume, TextOutputNamesTheMethodAndTheLevels) {
    const CliRun run = limsurf({"volume", mesh("octahedron"), "--scheme", "catmull-clark"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("volume "), std::string::npos);
    EXPECT_NE(run.out.find("trilinear forms"), std::string::npos);
    EXPECT_NE(run.out.find("polyhedral  level 3"), std::string::npos);
}

TEST(CliVolume, MomentsOfASymmetricMeshAndAgreementWithTheExactVolume) {
    // The octahedron is symmetric under x -> -x, y -> -y, z -> -z and the coordinate permutations:
    // centroid at its centre and an isotropic inertia tensor, whatever the scheme.
    const CliRun run = limsurf({"volume", mesh("octahedron"), "--scheme", "loop", "--moments", "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto out = nlohmann::json::parse(run.out);
    const double volume = out.at("volume").get<double>();
    const auto& moments = out.at("moments");
    EXPECT_NEAR(moments.at("quadrature_volume").get<double>(), volume, 1e-9 * volume);
    const auto centroid = out.at("centroid").get<std::vector<double>>();
    const auto inertia = out.at("inertia").get<std::vector<std::vector<double>>>();
    ASSERT_EQ(centroid.size(), 3U);
    ASSERT_EQ(inertia.size(), 3U);
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(centroid[static_cast<std::size_t>(i)], 0.0, 1e-12);
        for (int j = 0; j < 3; ++j) {
            const double value = inertia[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
            EXPECT_NEAR(value, i == j ? inertia[0][0] : 0.0, 1e-10 * inertia[0][0]) << i << ' ' << j;
        }
    }
    EXPECT_GT(inertia[0][0], 0.0);
    EXPECT_LT(moments.at("error_estimate").at("inertia").get<double>(), 1e-8 * inertia[0][0]);
}

TEST(CliVolume, ValencesBeyondTheTablesAreGeneratedWithANote) {
    // A 14-gonal bipyramid: apexes of valence 14, beyond the shipped types 3..12.
    const fs::path path = temp_dir() / "bipyramid14.obj";
    std::ofstream out(path);
    out.precision(17);
    const int n = 14;
    for (int i = 0; i < n; ++i) {
        out << "v " << std::cos(2 * std::numbers::pi * i / n) << ' ' << std::sin(2 * std::numbers::pi * i / n)
            << " 0\n";
    }
    out << "v 0 0 1\nv 0 0 -1\n";
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        out << "f " << i + 1 << ' ' << j + 1 << ' ' << n + 1 << "\nf " << j + 1 << ' ' << i + 1 << ' ' << n + 2 << '\n';
    }
    out.close();
    const CliRun text = limsurf({"volume", path.string(), "--scheme", "loop", "--levels", "0"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.err.find("generating the volume forms of facet types 14"), std::string::npos) << text.err;
    const CliRun json = limsurf({"volume", path.string(), "--scheme", "loop", "--json", "--levels", "0"});
    ASSERT_EQ(json.exit_code, 0) << json.err;
    const auto parsed = nlohmann::json::parse(json.out);
    EXPECT_EQ(parsed.at("facets").at("generated_types"), nlohmann::json::array({14}));
    EXPECT_GT(parsed.at("volume").get<double>(), 0.0);
}

TEST(CliVolume, OpenMeshAndCreasesAreRefusedNamingTheFile) {
    const std::string open = mesh("quad_grid");
    const CliRun run = limsurf({"volume", open, "--scheme", "catmull-clark"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find(open), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("open"), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty());
    const std::string creases = mesh("cube_creases");
    const CliRun creased = limsurf({"volume", creases, "--scheme", "catmull-clark"});
    EXPECT_EQ(creased.exit_code, 1);
    EXPECT_NE(creased.err.find(creases), std::string::npos) << creased.err;
    EXPECT_NE(creased.err.find("crease"), std::string::npos) << creased.err;
}

TEST(CliVolume, NonOrientableMeshIsRefusedNamingTheFile) {
    // The six-vertex projective plane (hemi-icosahedron): closed, every edge in two faces, no orientation.
    const fs::path path = temp_dir() / "projective_plane.obj";
    std::ofstream out(path);
    out << "v 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n"
        << "f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\nf 1 6 2\nf 2 3 5\nf 3 4 6\nf 4 5 2\nf 5 6 3\nf 6 2 4\n";
    out.close();
    const CliRun run = limsurf({"volume", path.string(), "--scheme", "loop"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find(path.string()), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("orient"), std::string::npos) << run.err;
    EXPECT_TRUE(run.out.empty());
}

TEST(CliVolume, LoopOnQuadsNamesTheFace) {
    const CliRun run = limsurf({"volume", mesh("cube"), "--scheme", "loop"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("face 0"), std::string::npos) << run.err;
}

TEST(CliVolume, UsageErrorsExitTwo) {
    EXPECT_EQ(limsurf({"volume", mesh("cube")}).exit_code, 2);                          // no --scheme
    EXPECT_EQ(limsurf({"volume", mesh("cube"), "--scheme", "bilinear"}).exit_code, 2);  // not a limit scheme
    EXPECT_EQ(limsurf({"volume", mesh("cube"), "--scheme", "loop", "--levels", "9"}).exit_code, 2);  // out of range
}

}  // namespace
}  // namespace limsurf
