// The limsurf binary: exit codes, the single "error:" line, JSON keys, and
// that a failed run leaves no output file. One malformed file per defect class.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;
using test::slurp;

/// Runs the limsurf binary with @p args; captures stdout, stderr and the exit code.
CliRun limsurf(const std::vector<std::string>& args) {
    static const fs::path dir = test::make_temp_dir("cli");
    return test::run_limsurf(args, dir);
}

std::string malformed(const std::string& name) {
    return (test::test_data_dir() / "malformed" / name).string();
}

TEST(Cli, InfoJsonHasTheKeysScriptsRelyOn) {
    const auto cube = test::find_bundled("cube");
    const CliRun run = limsurf({"info", "--json", cube.path.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(run.err, "");
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["num_vertices"], 8);
    EXPECT_EQ(json["num_edges"], 12);
    EXPECT_EQ(json["num_faces"], 6);
    EXPECT_EQ(json["euler_characteristic"], 2);
    EXPECT_EQ(json["genus"], 0);
    EXPECT_EQ(json["num_boundary_loops"], 0);
    EXPECT_EQ(json["is_closed"], true);
    EXPECT_EQ(json["face_degree_histogram"]["4"], 6);
    EXPECT_EQ(json["valence_histogram"]["3"], 8);
    EXPECT_EQ(json["validation"]["valid"], true);
}

TEST(Cli, InfoAgreesWithTheKnownValuesOfEveryBundledMesh) {
    for (const auto& mesh : test::bundled_meshes()) {
        SCOPED_TRACE(mesh.name);
        const CliRun run = limsurf({"info", "--json", mesh.path.string()});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const auto json = nlohmann::json::parse(run.out);
        EXPECT_EQ(json["num_vertices"], mesh.num_vertices);
        EXPECT_EQ(json["num_edges"], mesh.num_edges);
        EXPECT_EQ(json["num_faces"], mesh.num_faces);
        EXPECT_EQ(json["euler_characteristic"], mesh.euler_characteristic);
        EXPECT_EQ(json["genus"], mesh.genus);
        EXPECT_EQ(json["num_boundary_loops"], mesh.num_boundary_loops);
        EXPECT_EQ(json["num_components"], mesh.num_components);
        EXPECT_EQ(json["is_closed"], mesh.closed);
    }
}

TEST(Cli, InfoReportsTheSharpnessOfOpenSubdivTags) {
    const CliRun run = limsurf({"info", "--json", test::find_bundled("cube_creases").path.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto sharpness = nlohmann::json::parse(run.out)["sharpness"];
    EXPECT_EQ(sharpness["num_sharp_edges"], 5);
    EXPECT_EQ(sharpness["num_infinitely_sharp_edges"], 4);
    EXPECT_EQ(sharpness["max_semi_sharp_edge"], 2.5);
    EXPECT_EQ(sharpness["num_infinitely_sharp_vertices"], 1);
}

TEST(Cli, InfoTextNamesTheGenus) {
    const CliRun run = limsurf({"info", test::find_bundled("genus2").path.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.out.find("genus                 2"), std::string::npos) << run.out;
}

struct Defect {
    const char* file;
    const char* expected_error;  // after "error: <path>"
};

class CliDefect : public ::testing::TestWithParam<Defect> {};

TEST_P(CliDefect, InfoAndConvertRefuseWithOneErrorLineAndNoOutput) {
    const Defect& defect = GetParam();
    const std::string path = malformed(defect.file);
    const std::string expected = "error: " + path + defect.expected_error + "\n";

    const CliRun info = limsurf({"info", path});
    EXPECT_EQ(info.exit_code, 1);
    EXPECT_EQ(info.err, expected);

    const fs::path out = test::make_temp_dir("defect") / "out.ply";
    const CliRun convert = limsurf({"convert", path, out.string()});
    EXPECT_EQ(convert.exit_code, 1);
    EXPECT_EQ(convert.err, expected);
    EXPECT_FALSE(fs::exists(out));
    EXPECT_TRUE(fs::is_empty(out.parent_path())) << "a temporary file was left behind";
}

INSTANTIATE_TEST_SUITE_P(
    EveryDefectClass, CliDefect,
    ::testing::Values(
        Defect{"empty.obj", ": empty file"}, Defect{"no_faces.obj", ": no faces (3 vertices and no face)"},
        Defect{"face_two_vertices.obj", ":6: face 1 has 2 vertices (a face needs at least 3)"},
        Defect{"repeated_vertex.obj", ":7: face 1 repeats vertex 1"},
        Defect{"index_out_of_range.obj", ":5: vertex index 9 out of range [1, 3]"},
        Defect{"nan_coordinate.obj", ":4: vertex 2 has a non-finite coordinate (0, nan, 0)"},
        Defect{"non_manifold_edge.obj", ":9: edge (0, 1) is shared by 3 faces (non-manifold): faces 0, 1, 2"},
        Defect{"bow_tie.obj",
               ":2: vertex 0 is non-manifold: its faces form 2 fans that meet only at this vertex (bow-tie)"},
        Defect{"inconsistent_orientation.obj",
               ":13: faces 0 and 3 both traverse edge (2, 3) in the same direction (inconsistent orientation; "
               "reversing face 3 makes it consistent) (and 3 more errors)"},
        Defect{"moebius.obj", ":15: the surface is not orientable: no orientation of the faces around face 3 agrees "
                              "across edge (4, 9) (a Möbius band)"},
        Defect{"crease_not_an_edge.obj", ":7: crease (0, 3): no edge joins vertices 0 and 3"}),
    [](const ::testing::TestParamInfo<Defect>& param) {
        std::string name = param.param.file;
        return name.substr(0, name.find('.'));
    });

TEST(Cli, IsolatedVerticesAreDroppedWithAWarningOrRefusedWhenStrict) {
    const std::string path = malformed("isolated_vertex.obj");
    const CliRun info = limsurf({"info", "--json", path});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const auto json = nlohmann::json::parse(info.out);
    EXPECT_EQ(json["num_vertices"], 3);
    EXPECT_EQ(json["validation"]["num_warnings"], 1);
    EXPECT_EQ(json["validation"]["issues"][0]["message"], "vertex 3 is in no face (isolated); dropped");

    const CliRun strict = limsurf({"info", "--strict-isolated", path});
    EXPECT_EQ(strict.exit_code, 1);
    EXPECT_EQ(strict.err, "error: " + path + ":5: vertex 3 is in no face (isolated)\n");
}

TEST(Cli, DegenerateFacesAreReportedButAccepted) {
    const std::string path = malformed("degenerate_face.obj");
    const CliRun info = limsurf({"info", path});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("warning: " + path + ":7: face 1 has zero area (degenerate)"), std::string::npos)
        << info.out;
}

TEST(Cli, InfoJsonOnAnInvalidMeshStillPrintsTheWholeReport) {
    const std::string path = malformed("inconsistent_orientation.obj");
    const CliRun run = limsurf({"info", "--json", path});
    EXPECT_EQ(run.exit_code, 1);
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["validation"]["valid"], false);
    EXPECT_EQ(json["validation"]["num_errors"], 4);
    EXPECT_EQ(json["validation"]["issues"][0]["problem"], "inconsistent-orientation");
}

TEST(Cli, ConvertRoundTripsThroughEveryFormat) {
    const auto source = test::find_bundled("cube_ngons");
    const fs::path dir = test::make_temp_dir("convert");
    std::string previous = source.path.string();
    for (const std::string name : {"a.ply", "b.off", "c.obj", "d.ply"}) {
        const std::vector<std::string> extra =
            name == "d.ply" ? std::vector<std::string>{"--ply-encoding", "binary-be"} : std::vector<std::string>{};
        std::vector<std::string> args{"convert", previous, (dir / name).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        const CliRun run = limsurf(args);
        ASSERT_EQ(run.exit_code, 0) << run.err;
        previous = (dir / name).string();
    }
    const auto before = nlohmann::json::parse(limsurf({"info", "--json", source.path.string()}).out);
    const auto after = nlohmann::json::parse(limsurf({"info", "--json", previous}).out);
    for (const char* key :
         {"num_vertices", "num_edges", "num_faces", "genus", "face_degree_histogram", "bounding_box"}) {
        EXPECT_EQ(before[key], after[key]) << key;
    }
}

TEST(Cli, UsageErrorsExitWithTwoAndOneLine) {
    for (const auto& args :
         std::vector<std::vector<std::string>>{{},
                                               {"frobnicate"},
                                               {"info"},
                                               {"info", "a.obj", "--no-such-flag"},
                                               {"convert", "a.obj"},
                                               {"convert", "a.obj", "b.ply", "--ply-encoding", "1"}}) {
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, 2) << run.err;
        EXPECT_EQ(run.err.rfind("error: ", 0), 0U) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

TEST(Cli, BadFilesExitWithOne) {
    const CliRun missing = limsurf({"info", "/nonexistent/mesh.obj"});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_EQ(missing.err.rfind("error: /nonexistent/mesh.obj", 0), 0U) << missing.err;

    const CliRun unknown = limsurf({"info", "mesh.stl"});
    EXPECT_EQ(unknown.exit_code, 1);
    EXPECT_EQ(unknown.err, "error: mesh.stl: unknown mesh format '.stl' (expected .obj, .off or .ply)\n");

    const fs::path dir = test::make_temp_dir("badout");
    const CliRun bad_output = limsurf({"convert", test::find_bundled("cube").path.string(), (dir / "x.stl").string()});
    EXPECT_EQ(bad_output.exit_code, 1);
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CliSubdivide, CatmullClarkTwoLevelsOfTheCube) {
    const fs::path out = test::make_temp_dir("subdivide") / "cube2.obj";
    const CliRun run = limsurf({"subdivide", test::find_bundled("cube").path.string(), "--scheme", "catmull-clark",
                                "--levels", "2", "-o", out.string(), "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json["output"]["num_faces"], 96);     // 6 · 4²
    EXPECT_EQ(json["output"]["num_vertices"], 98);  // V − E + F = 2 with E = 2F
    EXPECT_EQ(json["per_level"][1]["num_faces"], 24);
    const auto info = nlohmann::json::parse(limsurf({"info", "--json", out.string()}).out);
    EXPECT_EQ(info["num_faces"], 96);
    EXPECT_EQ(info["genus"], 0);
}

TEST(CliSubdivide, CreasesAreCarriedToTheOutput) {
    // cube_creases: 4 edges at sharpness 10, one at 2.5, a corner. One uniform
    // Catmull-Clark step: each sharp edge splits in two, 2.5 decays to 1.5.
    const fs::path out = test::make_temp_dir("creases") / "creased.obj";
    const CliRun run = limsurf({"subdivide", test::find_bundled("cube_creases").path.string(), "--scheme",
                                "catmull-clark", "--levels", "1", "-o", out.string()});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto sharpness = nlohmann::json::parse(limsurf({"info", "--json", out.string()}).out)["sharpness"];
    EXPECT_EQ(sharpness["num_sharp_edges"], 10);
    EXPECT_EQ(sharpness["num_infinitely_sharp_edges"], 8);
    EXPECT_EQ(sharpness["max_semi_sharp_edge"], 1.5);
    EXPECT_EQ(sharpness["num_infinitely_sharp_vertices"], 1);
}

TEST(CliSubdivide, LoopRefusesQuadsNamingAFace) {
    const fs::path dir = test::make_temp_dir("loopquads");
    const CliRun run = limsurf({"subdivide", test::find_bundled("cube").path.string(), "--scheme", "loop", "--levels",
                                "1", "-o", (dir / "x.obj").string()});
    EXPECT_EQ(run.exit_code, 1);
    // The face's own line: cube.obj's first face is on line 10.
    const std::string cube = test::find_bundled("cube").path.string();
    EXPECT_EQ(run.err, "error: " + cube + ":10: face 0 has 4 vertices: Loop needs triangles\n");
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CliSubdivide, RefusesHugeOutputsBeforeWorking) {
    const fs::path dir = test::make_temp_dir("huge");
    const CliRun run = limsurf({"subdivide", test::find_bundled("quad_torus").path.string(), "--scheme",
                                "catmull-clark", "--levels", "14", "-o", (dir / "x.obj").string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("would make"), std::string::npos) << run.err;
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(CliSubdivide, TunedWeightsOnlyForCatmullClark) {
    const fs::path dir = test::make_temp_dir("weights");
    const CliRun run = limsurf({"subdivide", test::find_bundled("tri_valence_5").path.string(), "--scheme", "loop",
                                "--weights", "cup", "-o", (dir / "x.obj").string()});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_EQ(run.err, "error: --weights applies to --scheme catmull-clark only\n");
    const CliRun cup = limsurf({"subdivide", test::find_bundled("quad_valence_5").path.string(), "--scheme",
                                "catmull-clark", "--weights", "cup", "-o", (dir / "y.obj").string(), "--json"});
    EXPECT_EQ(cup.exit_code, 0) << cup.err;
    EXPECT_EQ(nlohmann::json::parse(cup.out)["tuned_weights"], true);
}

TEST(Cli, HelpIsEverywhere) {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"--help"}, {"info", "--help"}, {"convert", "--help"}, {"subdivide", "--help"}}) {
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, 0);
        EXPECT_NE(run.out.find("Usage"), std::string::npos) << run.out;
    }
    const CliRun version = limsurf({"--version"});
    EXPECT_EQ(version.exit_code, 0);
    EXPECT_EQ(version.out, "0.1.0\n");
}

}  // namespace
}  // namespace limsurf
