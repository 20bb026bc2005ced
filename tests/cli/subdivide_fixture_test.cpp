// `limsurf subdivide` writes byte for byte what the version before the refinement rewrite wrote
// (issue 20: "the CLI output must stay identical"). The fixtures in tests/data/subdivide_fixtures
// were produced by that version (see the folder's README.md for the commit and the command); every
// scheme, boundary rule, creasing, tuned weights and each output format appears at least once.
// A deliberate change of the documented vertex/face order (docs/conventions.md) regenerates them
// with tests/data/subdivide_fixtures/make_fixtures.sh and says so in the commit.
#include <cctype>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "support/paths.h"

namespace limsurf::test {
namespace {

struct FixtureCase {
    std::string name;  ///< fixture file name (its extension is the format)
    std::vector<std::string> args;
};

void PrintTo(const FixtureCase& c, std::ostream* os) {
    *os << c.name;
}

// Keep in sync with tests/data/subdivide_fixtures/make_fixtures.sh.
std::vector<FixtureCase> fixture_cases() {
    return {
        {"cube_cc3.obj", {"cube.obj", "--scheme", "catmull-clark", "--levels", "3"}},
        {"cube_creases_cc3_chaikin.obj",
         {"cube_creases.obj", "--scheme", "catmull-clark", "--levels", "3", "--creasing", "chaikin"}},
        {"cube_ngons_cc2.ply", {"cube_ngons.obj", "--scheme", "catmull-clark", "--levels", "2"}},
        {"tetrahedron_cc2_smooth.obj",
         {"tetrahedron.obj", "--scheme", "catmull-clark", "--levels", "2", "--triangles", "smooth"}},
        {"quad_grid_cc2_none.obj",
         {"quad_grid.obj", "--scheme", "catmull-clark", "--levels", "2", "--boundary", "none"}},
        {"annulus_cc2_edge_only.off",
         {"annulus.obj", "--scheme", "catmull-clark", "--levels", "2", "--boundary", "edge-only"}},
        {"genus2_cc2.ply", {"genus2.obj", "--scheme", "catmull-clark", "--levels", "2"}},
        {"genus2_cc2_binary.ply",
         {"genus2.obj", "--scheme", "catmull-clark", "--levels", "2", "--ply-encoding", "binary-le"}},
        {"quad_valence_5_cc2_cup.obj",
         {"quad_valence_5.obj", "--scheme", "catmull-clark", "--levels", "2", "--weights", "cup"}},
        {"icosahedron_loop3.obj", {"icosahedron.obj", "--scheme", "loop", "--levels", "3"}},
        {"disk_ev7_tris_loop2_edge_only.obj",
         {"disk_ev7_tris.obj", "--scheme", "loop", "--levels", "2", "--boundary", "edge-only"}},
        {"dodecahedron_ds2.obj", {"dodecahedron.obj", "--scheme", "doo-sabin", "--levels", "2"}},
        {"hexagon_fan_ds2.off", {"hexagon_fan.obj", "--scheme", "doo-sabin", "--levels", "2"}},
        {"tetra_1_c2g02.obj", {"tetra_1.obj", "--scheme", "c2g0", "--levels", "2"}},
        {"pentagon_bilinear2.obj", {"pentagon.obj", "--scheme", "bilinear", "--levels", "2"}},
        {"tri_grid_linear2.ply", {"tri_grid.obj", "--scheme", "linear", "--levels", "2"}},
    };
}

class SubdivideFixture : public ::testing::TestWithParam<FixtureCase> {};

TEST_P(SubdivideFixture, OutputIsUnchanged) {
    const FixtureCase& c = GetParam();
    const auto dir = make_temp_dir("subdivide-fixture");
    const auto out = dir / c.name;
    std::vector<std::string> args{"subdivide", (mesh_dir() / c.args[0]).string()};
    args.insert(args.end(), c.args.begin() + 1, c.args.end());
    args.insert(args.end(), {"-o", out.string()});
    const CliRun run = run_limsurf(args, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const std::string expected = slurp(test_data_dir() / "subdivide_fixtures" / c.name);
    ASSERT_FALSE(expected.empty()) << "missing fixture " << c.name;
    const std::string written = slurp(out);
    EXPECT_EQ(written.size(), expected.size());
    EXPECT_TRUE(written == expected) << c.name << " differs from the fixture";
    std::filesystem::remove_all(dir);
}

TEST(SubdivideFixtures, BinaryPlyHoldsTheSameMeshAsAscii) {
    // Exact doubles both ways: the binary fixture converted to ASCII is the ASCII fixture, byte for byte.
    const auto dir = make_temp_dir("subdivide-binary");
    const auto fixtures = test_data_dir() / "subdivide_fixtures";
    const CliRun run =
        run_limsurf({"convert", (fixtures / "genus2_cc2_binary.ply").string(), (dir / "ascii.ply").string()}, dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_TRUE(slurp(dir / "ascii.ply") == slurp(fixtures / "genus2_cc2.ply"));
    std::filesystem::remove_all(dir);
}

std::string case_name(const ::testing::TestParamInfo<FixtureCase>& param) {
    std::string name = param.param.name;
    for (char& ch : name) {
        ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
    }
    return name;
}

INSTANTIATE_TEST_SUITE_P(Cli, SubdivideFixture, ::testing::ValuesIn(fixture_cases()), case_name);

}  // namespace
}  // namespace limsurf::test
