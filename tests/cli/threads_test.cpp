// `--threads N` of the commands whose work is parallel: every such command takes it, the reports
// are the same numbers for one thread and for several (timings left out), and a negative or
// non-numeric count is a usage error (exit 2) naming --threads.
//
// The meshes are refined first (limsurf subdivide) so that the parallel loops, which give each
// thread at least 64 items, really run on several threads.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
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
    static const fs::path dir = test::make_temp_dir("cli_threads");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

/// The bundled mesh @p name refined @p levels times by Catmull–Clark (written once per run).
std::string refined(const std::string& name, int levels) {
    const fs::path out = temp_dir() / (name + "_l" + std::to_string(levels) + ".obj");
    if (!fs::exists(out)) {
        const CliRun run = limsurf({"subdivide", mesh(name), "--scheme", "catmull-clark", "--levels",
                                    std::to_string(levels), "-o", out.string()});
        EXPECT_EQ(run.exit_code, 0) << run.err;
    }
    return out.string();
}

/// @p json without its timings ("seconds", "times"), which differ from run to run.
nlohmann::json without_timings(const nlohmann::json& json) {
    if (json.is_object()) {
        nlohmann::json out = nlohmann::json::object();
        for (const auto& [key, value] : json.items()) {
            if (key != "seconds" && key != "times") {
                out[key] = without_timings(value);
            }
        }
        return out;
    }
    if (json.is_array()) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& value : json) {
            out.push_back(without_timings(value));
        }
        return out;
    }
    return json;
}

/// The JSON report of `limsurf ARGS --threads N --json`, timings left out.
nlohmann::json report(std::vector<std::string> args, int threads) {
    args.insert(args.end(), {"--threads", std::to_string(threads), "--json"});
    const CliRun run = limsurf(args);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return run.exit_code == 0 ? without_timings(nlohmann::json::parse(run.out)) : nlohmann::json();
}

/// The reports for one thread and for four are equal, every number to the last bit.
void expect_same_for_any_thread_count(const std::vector<std::string>& args) {
    SCOPED_TRACE(args.front());
    const nlohmann::json one = report(args, 1);
    const nlohmann::json four = report(args, 4);
    ASSERT_FALSE(one.is_null());
    EXPECT_EQ(one, four) << "--threads 1:\n" << one.dump(2) << "\n--threads 4:\n" << four.dump(2);
}

// The commands with --threads, each with arguments that make a valid run.
const std::vector<std::vector<std::string>>& threaded_commands() {
    static const std::vector<std::vector<std::string>> commands{
        {"measure", mesh("cube"), "--scheme", "catmull-clark"},
        {"volume", mesh("cube"), "--scheme", "catmull-clark", "--moments"},
        {"render", mesh("cube"), "--scheme", "catmull-clark", "-o", (temp_dir() / "refused.png").string()},
        {"geodesic", mesh("cube"), "--scheme", "catmull-clark", "--source", "0"},
        {"parameterize", mesh("disk_ev5_quads"), "--scheme", "catmull-clark"},
        {"vector-field", mesh("cube"), "--scheme", "catmull-clark", "--source", "0:1", "--sink", "6:1"},
        {"hodge", mesh("cube"), "--scheme", "catmull-clark", "--random", "1"},
        {"poisson", mesh("cube"), "--scheme", "catmull-clark", "--rhs", "x"},
        {"plate", mesh("quad_grid")},
        {"shell", mesh("shell_hemisphere")},
        {"elasticity", mesh("rve_block")},
        {"membrane", mesh("cube"), "--scheme", "catmull-clark", "--evaluate-only"},
        {"eval", mesh("cube"), "--scheme", "catmull-clark", "--grid", "2"},
        {"subdivide", mesh("cube"), "--scheme", "catmull-clark", "-o", (temp_dir() / "refused.obj").string()},
        {"tune", "--valence", "5", "--lambda", "0.55"},
    };
    return commands;
}

TEST(CliThreads, EveryParallelCommandTakesTheOption) {
    for (const auto& args : threaded_commands()) {
        SCOPED_TRACE(args.front());
        const CliRun run = limsurf({args.front(), "--help"});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        EXPECT_NE(run.out.find("--threads"), std::string::npos) << run.out;
        EXPECT_NE(run.out.find("0: all cores"), std::string::npos) << run.out;
    }
}

TEST(CliThreads, NegativeOrNonNumericCountIsAUsageError) {
    for (const auto& args : threaded_commands()) {
        for (const char* bad : {"-1", "abc", "1.5"}) {
            SCOPED_TRACE(args.front() + " --threads " + bad);
            std::vector<std::string> with = args;
            with.insert(with.end(), {"--threads", bad});
            const CliRun run = limsurf(with);
            EXPECT_EQ(run.exit_code, 2) << run.err;
            EXPECT_NE(run.err.find("--threads"), std::string::npos) << run.err;
            EXPECT_TRUE(run.out.empty()) << run.out;
        }
    }
    EXPECT_FALSE(fs::exists(temp_dir() / "refused.png"));
    EXPECT_FALSE(fs::exists(temp_dir() / "refused.obj"));
}

/// Each step from 1024 faces on builds the child topology on a second thread: the file written is
/// the same, byte for byte, for one thread and for four.
TEST(CliThreads, SubdivideWritesTheSameFileForAnyThreadCount) {
    for (const auto& [name, scheme] : {std::pair{"cube_creases", "catmull-clark"}, std::pair{"icosahedron", "loop"}}) {
        std::vector<std::string> written;
        for (const char* threads : {"1", "4"}) {
            const fs::path out = temp_dir() / (std::string(name) + "_threads" + threads + ".ply");
            const CliRun run = limsurf({"subdivide", mesh(name), "--scheme", scheme, "--levels", "6", "--ply-encoding",
                                        "binary-le", "--threads", threads, "-o", out.string()});
            ASSERT_EQ(run.exit_code, 0) << run.err;
            std::ifstream file(out, std::ios::binary);
            written.emplace_back(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
        }
        EXPECT_GT(written[0].size(), 100000U) << name;
        EXPECT_TRUE(written[0] == written[1]) << name << ": --threads 1 and --threads 4 wrote different files";
    }
}

TEST(CliThreads, GeodesicIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count({"geodesic", refined("genus2", 2), "--scheme", "catmull-clark", "--source", "0"});
}

TEST(CliThreads, ParameterizeIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count({"parameterize", refined("disk_ev5_quads", 1), "--scheme", "catmull-clark"});
}

TEST(CliThreads, PoissonIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count({"poisson", refined("genus2", 2), "--scheme", "catmull-clark", "--rhs", "x"});
    expect_same_for_any_thread_count(
        {"poisson", refined("disk_ev5_quads", 1), "--scheme", "catmull-clark", "--rhs", "x", "--method", "iga"});
}

TEST(CliThreads, RenderedPicturesAreTheSameForAnyThreadCount) {
    // Tessellation and pixel shading: each row and point alone, so the PNG files are byte-identical.
    std::string pictures[2];
    for (const int threads : {1, 4}) {
        const fs::path png = temp_dir() / ("threads" + std::to_string(threads) + ".png");
        const CliRun run =
            limsurf({"render", refined("genus2", 1), "--scheme", "catmull-clark", "--field", "mean-curvature", "--size",
                     "320x240", "--threads", std::to_string(threads), "-o", png.string()});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        pictures[threads == 1 ? 0 : 1] = test::slurp(png);
    }
    ASSERT_FALSE(pictures[0].empty());
    EXPECT_TRUE(pictures[0] == pictures[1]);
}

TEST(CliThreads, ElasticityFieldsAreTheSameForAnyThreadCount) {
    // The stresses written by -o are evaluated point by point: the VTK files are byte-identical.
    std::string fields[2];
    for (const int threads : {1, 4}) {
        const fs::path vtk = temp_dir() / ("elasticity_threads" + std::to_string(threads) + ".vtk");
        const CliRun run = limsurf({"elasticity", refined("rve_block", 1), "--no-stiffness", "--threads",
                                    std::to_string(threads), "-o", vtk.string()});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        fields[threads == 1 ? 0 : 1] = test::slurp(vtk);
    }
    ASSERT_FALSE(fields[0].empty());
    EXPECT_TRUE(fields[0] == fields[1]);
}

TEST(CliThreads, EvalIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count({"eval", refined("genus2", 1), "--scheme", "catmull-clark", "--grid", "12"});
}

TEST(CliThreads, EvalNamesTheFirstFailingPointWhicheverThreadMetIt) {
    // A cube 2e308 across: the derivatives overflow at every point; the error names the first one
    // in input order (ptex face 0) for any thread count, not the first one a thread happened to meet.
    const fs::path huge = temp_dir() / "huge_cube.obj";
    {
        std::ofstream out(huge);
        for (int i = 0; i < 8; ++i) {
            out << "v " << ((i & 1) != 0 ? "1e308" : "-1e308") << ' ' << ((i & 2) != 0 ? "1e308" : "-1e308") << ' '
                << ((i & 4) != 0 ? "1e308" : "-1e308") << '\n';
        }
        out << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 2 4 8 6\nf 4 3 7 8\nf 3 1 5 7\n";
    }
    for (const char* threads : {"1", "4"}) {
        const CliRun run =
            limsurf({"eval", huge.string(), "--scheme", "catmull-clark", "--grid", "40", "--threads", threads});
        EXPECT_EQ(run.exit_code, 1) << run.err;
        EXPECT_NE(run.err.find("derivatives at ptex face 0 (0.0125"), std::string::npos) << threads << ": " << run.err;
    }
}

TEST(CliThreads, HodgeIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count({"hodge", refined("genus2", 2), "--scheme", "catmull-clark", "--random", "1"});
}

TEST(CliThreads, ExactVolumeIsTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count(
        {"volume", refined("cube", 6), "--scheme", "catmull-clark"});  // 24 576 facets: 4 workers
}

// The quadrature sums (measure, volume --moments) and the exact volume add fixed blocks of samples
// or facets in order, whatever the split: the same bits for any thread count.
TEST(CliThreads, QuadratureMomentsAreTheSameForAnyThreadCount) {
    expect_same_for_any_thread_count(
        {"measure", refined("cube", 2), "--scheme", "catmull-clark", "--degree", "8", "--tiles", "4"});
    expect_same_for_any_thread_count(
        {"volume", refined("cube", 2), "--scheme", "catmull-clark", "--moments", "--degree", "8", "--tiles", "4"});
}

}  // namespace
}  // namespace limsurf
