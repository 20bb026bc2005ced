// The CLI on the bad inputs of issue "Hardening" (docs/io.md "Limits"): faces and valences of
// 10⁵, results that would overflow or underflow a double, meshes far from unit size, special
// output files, inputs that are directories, memory beyond the budget, and the smaller promises
// (the file named in every error, capped warnings). Each case checks the exit code, the one
// error line, and that nothing is left behind; the sizes are checked against identities
// (V(sX) = s³ V(X), the rule's invariance under scaling its weights).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <sys/stat.h>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_runner.h"
#include "limsurf/io/mesh_io.h"
#include "support/paths.h"
#include "support/timing.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_hardening");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

/// @p args timed: the run and its wall-clock seconds.
std::pair<CliRun, double> timed(const std::vector<std::string>& args) {
    const auto start = std::chrono::steady_clock::now();
    CliRun run = limsurf(args);
    return {run, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

std::string bundled(const std::string& name) {
    return (test::mesh_dir() / (name + ".obj")).string();
}

int count_lines(const std::string& text, const std::string& prefix) {
    int n = 0;
    std::size_t start = 0;
    while (start < text.size()) {
        const std::size_t end = text.find('\n', start);
        if (text.compare(start, prefix.size(), prefix) == 0) {
            ++n;
        }
        start = end == std::string::npos ? text.size() : end + 1;
    }
    return n;
}

/// Exit 1 with exactly one error line, the last one, "error: " + @p start + … (warnings may precede it).
void expect_one_error(const CliRun& run, const std::string& start) {
    EXPECT_EQ(run.exit_code, 1) << run.err;
    EXPECT_EQ(count_lines(run.err, "error: "), 1) << run.err;
    const std::size_t last = run.err.rfind("error: ");
    ASSERT_NE(last, std::string::npos) << run.err;
    EXPECT_EQ(run.err.compare(last, 7 + start.size(), "error: " + start), 0) << run.err;
    EXPECT_EQ(run.err.find('\n', last), run.err.size() - 1) << "the error line is not the last: " << run.err;
}

/// A regular n-gon in the plane z = 0: one face (a disk) or two opposite faces (a pillow).
std::string ngon(int n, bool pillow) {
    const fs::path path = temp_dir() / ((pillow ? "pillow" : "disk") + std::to_string(n) + ".obj");
    std::ofstream out(path);
    out.precision(17);
    for (int i = 0; i < n; ++i) {
        out << "v " << std::cos(2 * M_PI * i / n) << ' ' << std::sin(2 * M_PI * i / n) << " 0\n";
    }
    out << 'f';
    for (int i = 1; i <= n; ++i) {
        out << ' ' << i;
    }
    out << '\n';
    if (pillow) {
        out << 'f';
        for (int i = n; i >= 1; --i) {
            out << ' ' << i;
        }
        out << '\n';
    }
    return path.string();
}

/// A cone of n triangles around an apex of valence n (open).
std::string fan(int n) {
    const fs::path path = temp_dir() / ("fan" + std::to_string(n) + ".obj");
    std::ofstream out(path);
    out.precision(17);
    out << "v 0 0 1\n";
    for (int i = 0; i < n; ++i) {
        out << "v " << std::cos(2 * M_PI * i / n) << ' ' << std::sin(2 * M_PI * i / n) << " 0\n";
    }
    for (int i = 0; i < n; ++i) {
        out << "f 1 " << i + 2 << ' ' << (i + 1) % n + 2 << '\n';
    }
    return path.string();
}

/// The bundled unit cube with every coordinate times @p scale (and z = 0 when @p flat).
std::string scaled_cube(double scale, bool flat = false) {
    char name[64];
    std::snprintf(name, sizeof name, "cube_%g%s.obj", scale, flat ? "_flat" : "");
    const fs::path path = temp_dir() / name;
    std::ofstream out(path);
    out.precision(17);
    for (const double x : {-0.5, 0.5}) {
        for (const double y : {-0.5, 0.5}) {
            for (const double z : {-0.5, 0.5}) {
                out << "v " << scale * x << ' ' << scale * y << ' ' << (flat ? 0.0 : scale * z) << '\n';
            }
        }
    }
    out << "f 5 7 8 6\nf 1 2 4 3\nf 3 4 8 7\nf 1 5 6 2\nf 2 6 8 4\nf 1 3 7 5\n";
    return path.string();
}

double json_number(const std::string& out, const char* key) {
    return nlohmann::json::parse(out).at(key).get<double>();
}

// --- 1. faces and valences of 10⁵ --------------------------------------------------------

TEST(CliHardening, HugeFacesAreReadConvertedAndSubdividedInLinearTime) {
    const std::string disk = ngon(100000, false);
    const std::string pillow = ngon(50000, true);
    for (const std::string& mesh : {disk, pillow}) {
        const auto [info, info_seconds] = timed({"info", "--json", mesh});
        ASSERT_EQ(info.exit_code, 0) << info.err;
        EXPECT_LT(info_seconds, 1.0 * test::time_scale);
        const auto [convert, convert_seconds] = timed({"convert", mesh, (temp_dir() / "huge.ply").string()});
        EXPECT_EQ(convert.exit_code, 0) << convert.err;
        EXPECT_LT(convert_seconds, 1.0 * test::time_scale);
        // Bilinear refinement of an n-gon is linear in n (its face point has n weights).
        const auto [split, split_seconds] =
            timed({"subdivide", mesh, "--scheme", "bilinear", "-o", (temp_dir() / "huge_split.obj").string()});
        EXPECT_EQ(split.exit_code, 0) << split.err;
        EXPECT_LT(split_seconds, 1.0 * test::time_scale);
    }
    // Catmull–Clark's one step on a disk is linear too (its vertex and edge points see one face).
    const auto [cc, cc_seconds] =
        timed({"subdivide", disk, "--scheme", "catmull-clark", "-o", (temp_dir() / "huge_cc.obj").string()});
    EXPECT_EQ(cc.exit_code, 0) << cc.err;
    EXPECT_LT(cc_seconds, 1.0 * test::time_scale);
}

TEST(CliHardening, HugeFacesAreRefusedBeforeAnyWorkWhereTheCostIsNotLinear) {
    const std::string disk = ngon(100000, false);
    const std::string pillow = ngon(50000, true);
    // The limit basis: face 0 (line 100001) is beyond the documented limit of 128 corners.
    for (const char* scheme : {"catmull-clark", "doo-sabin"}) {
        const auto [eval, seconds] = timed({"eval", disk, "--scheme", scheme, "--grid", "1"});
        expect_one_error(eval, disk + ":100001: face 0 has 100000 corners; the limit basis handles faces and "
                                      "vertices of at most 128");
        EXPECT_LT(seconds, 1.0 * test::time_scale);
    }
    const auto [measure, measure_seconds] = timed({"measure", pillow, "--scheme", "catmull-clark"});
    expect_one_error(measure, pillow + ":50001: face 0 has 50000 corners");
    EXPECT_LT(measure_seconds, 1.0 * test::time_scale);
    const auto [volume, volume_seconds] = timed({"volume", pillow, "--scheme", "doo-sabin"});
    expect_one_error(volume, pillow + ":");
    EXPECT_LT(volume_seconds, 1.0 * test::time_scale);
    // Catmull–Clark on the pillow: every vertex and edge point holds a whole face point, 2·n²
    // weights in all: the memory estimate names the face (was "out of memory" after minutes).
    const fs::path out = temp_dir() / "never.obj";
    const auto [cc, cc_seconds] = timed({"subdivide", pillow, "--scheme", "catmull-clark", "-o", out.string()});
    expect_one_error(cc, pillow + ":50001: catmull-clark refinement needs about ");
    EXPECT_NE(cc.err.find("face 0's 50000 corners"), std::string::npos) << cc.err;
    EXPECT_LT(cc_seconds, 1.0 * test::time_scale);
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliHardening, HighValencesAreRefusedByTheLimitLayersNamingTheVertex) {
    const std::string cone = fan(30000);
    const auto [info, info_seconds] = timed({"info", cone});
    EXPECT_EQ(info.exit_code, 0) << info.err;
    EXPECT_LT(info_seconds, 1.0 * test::time_scale);
    const auto [eval, eval_seconds] = timed({"eval", cone, "--scheme", "loop", "--grid", "1"});
    expect_one_error(eval, cone + ":1: vertex 0 has 30000 edges; the limit basis handles faces and vertices of at "
                                  "most 128");
    EXPECT_LT(eval_seconds, 1.0 * test::time_scale);
    const CliRun poisson = limsurf({"poisson", cone, "--scheme", "loop", "--rhs", "x"});
    expect_one_error(poisson, cone + ":1: vertex 0 has 30000 edges; SEC's ring stencils handle");
}

TEST(CliHardening, ValenceTwoIsRefusedByNameWhereTheRulesNeedThree) {
    const std::string pillow = ngon(6, true);
    expect_one_error(limsurf({"volume", pillow, "--scheme", "catmull-clark"}),
                     pillow + ":1: exact volume: vertex 0 has valence 2");
    const fs::path out = temp_dir() / "never_ds.obj";
    expect_one_error(limsurf({"subdivide", pillow, "--scheme", "doo-sabin", "-o", out.string()}),
                     pillow + ":1: Doo-Sabin refinement needs interior vertices in at least 3 faces: vertex 0");
    EXPECT_FALSE(fs::exists(out));
    expect_one_error(limsurf({"eval", pillow, "--scheme", "doo-sabin", "--grid", "1"}),
                     pillow + ":1: Doo-Sabin limit evaluation needs interior vertices in at least 3 faces");
    // Two triangles with the same corners: Loop's local subdivision never reaches a regular patch
    // there (it recursed until the stack overflowed: found by fuzz/commands.py).
    const std::string triangles = ngon(3, true);
    const std::string refusal =
        ":1: Loop limit evaluation needs interior vertices of valence 3 or more: vertex 0 has valence 2";
    expect_one_error(limsurf({"eval", triangles, "--scheme", "loop", "--grid", "1"}), triangles + refusal);
    expect_one_error(limsurf({"measure", triangles, "--scheme", "loop"}), triangles + refusal);
    expect_one_error(limsurf({"membrane", triangles, "--scheme", "loop", "--evaluate-only"}), triangles + refusal);
    const fs::path refined = temp_dir() / "pillow3_loop.obj";  // refinement has no such limit
    EXPECT_EQ(limsurf({"subdivide", triangles, "--scheme", "loop", "-o", refined.string()}).exit_code, 0);
}

// --- 2. and 3. results that do not fit a double; verdicts at any scale ---------------------

TEST(CliHardening, OverflowAndUnderflowAreNamedNeverPrinted) {
    const std::string huge = scaled_cube(1.7e308);
    const std::string tiny = scaled_cube(1e-160);
    for (const char* scheme : {"catmull-clark", "doo-sabin"}) {
        expect_one_error(limsurf({"volume", huge, "--scheme", scheme}),
                         huge + ": the enclosed volume (about 1e924) overflows a double");
        expect_one_error(limsurf({"volume", tiny, "--scheme", scheme}),
                         tiny + ": the enclosed volume (about 1e-480) underflows a double");
    }
    expect_one_error(limsurf({"measure", scaled_cube(1e155), "--scheme", "catmull-clark"}),
                     scaled_cube(1e155) + ": the area of the limit surface (about 1e310) overflows");
    // Curvature grows as 1/size²: on a cube 1e-160 across the Gaussian curvature overflows.
    const CliRun eval = limsurf({"eval", tiny, "--scheme", "catmull-clark", "--grid", "1"});
    expect_one_error(eval, tiny + ": the curvatures overflow a double");
}

TEST(CliHardening, AValidMeshGivesTheSameAnswersAtAnyScale) {
    const CliRun unit = limsurf({"volume", scaled_cube(1.0), "--scheme", "doo-sabin", "--json"});
    ASSERT_EQ(unit.exit_code, 0) << unit.err;
    const double v = json_number(unit.out, "volume");
    EXPECT_NEAR(v, 6241.0 / 9920.0, 1e-15);  // the paper's rational for the unit cube
    // V(sX) = s³ V(X): computed at unit scale and scaled back, to rounding.
    for (const double s : {1e80, 1e-100, 1e100}) {
        const CliRun run = limsurf({"volume", scaled_cube(s), "--scheme", "doo-sabin", "--json"});
        ASSERT_EQ(run.exit_code, 0) << s << ": " << run.err;
        EXPECT_EQ(count_lines(run.err, "warning: "), 0) << run.err;  // no face of a scaled cube is degenerate
        EXPECT_NEAR(json_number(run.out, "volume") / (s * s * s), v, 1e-14 * v) << s;
    }
    // measure at 1e50: area s², volume s³, inertia s⁵ (the unit cube's limit surface is not a cube,
    // so only the scaling is asserted).
    const CliRun m1 = limsurf({"measure", scaled_cube(1.0), "--scheme", "catmull-clark", "--json"});
    const CliRun m2 = limsurf({"measure", scaled_cube(1e50), "--scheme", "catmull-clark", "--json"});
    ASSERT_EQ(m1.exit_code, 0) << m1.err;
    ASSERT_EQ(m2.exit_code, 0) << m2.err;
    const auto a = nlohmann::json::parse(m1.out);
    const auto b = nlohmann::json::parse(m2.out);
    EXPECT_NEAR(b["area"].get<double>() / 1e100, a["area"].get<double>(), 1e-13 * a["area"].get<double>());
    EXPECT_NEAR(b["volume"].get<double>() / 1e150, a["volume"].get<double>(), 1e-13 * a["volume"].get<double>());
    EXPECT_NEAR(b["inertia"][0][0].get<double>() / 1e250, a["inertia"][0][0].get<double>(),
                1e-13 * a["inertia"][0][0].get<double>());
}

TEST(CliHardening, AFlatClosedMeshHasZeroVolumeAndNoRelativeDifference) {
    const std::string flat = scaled_cube(1.0, true);
    const CliRun text = limsurf({"volume", flat, "--scheme", "catmull-clark"});
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_NE(text.out.find("(the exact volume is zero)"), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("nan"), std::string::npos) << text.out;
    const CliRun json = limsurf({"volume", flat, "--scheme", "catmull-clark", "--json"});
    ASSERT_EQ(json.exit_code, 0) << json.err;
    const auto level0 = nlohmann::json::parse(json.out)["polyhedral"][0];
    EXPECT_TRUE(level0["relative_difference"].is_null());
    EXPECT_TRUE(level0["difference"].is_number());
    // The four side faces are flat (the top and bottom overlap, each of full area).
    EXPECT_EQ(count_lines(text.err, "warning: "), 4) << text.err;
}

TEST(CliHardening, PoissonRefusesOverflowingDataAndWritesNothing) {
    const fs::path out = temp_dir() / "never.vtk";
    for (const char* method : {"dec", "sec"}) {
        const CliRun run = limsurf({"poisson", bundled("genus2"), "--scheme", "catmull-clark", "--method", method,
                                    "--rhs", "1e308*(x+0.6)", "-o", out.string()});
        expect_one_error(run, bundled("genus2") + ": --rhs '1e308*(x+0.6)' is not finite at (x, y, z)");
        EXPECT_FALSE(fs::exists(out));
    }
    // Data near the range of a double solve exactly (the problem is linear: solved at unit scale).
    const CliRun big = limsurf({"poisson", bundled("quad_grid"), "--scheme", "catmull-clark", "--rhs", "0",
                                "--boundary-value", "1e308", "--json"});
    ASSERT_EQ(big.exit_code, 0) << big.err;
    EXPECT_NEAR(json_number(big.out, "u_min") / 1e308, 1.0, 1e-12);
    EXPECT_NEAR(json_number(big.out, "u_max") / 1e308, 1.0, 1e-12);
}

// --- 4. special output files and overwriting inputs -------------------------------------------

TEST(CliHardening, DevicesArePassedThroughNotReplaced) {
    const std::string cube = bundled("cube");
    const CliRun null = limsurf({"convert", cube, "/dev/null", "--format", "obj"});
    EXPECT_EQ(null.exit_code, 0) << null.err;
    struct stat status {};
    ASSERT_EQ(::stat("/dev/null", &status), 0);
    EXPECT_TRUE(S_ISCHR(status.st_mode)) << "/dev/null is no longer a character device";
    const CliRun stdout_run = limsurf({"convert", cube, "/dev/stdout", "--format", "off"});
    EXPECT_EQ(stdout_run.exit_code, 0) << stdout_run.err;
    EXPECT_EQ(stdout_run.out.rfind("OFF\n", 0), 0U) << stdout_run.out;
    if (fs::exists("/dev/full")) {
        expect_one_error(limsurf({"eval", cube, "--scheme", "catmull-clark", "--grid", "2", "-o", "/dev/full"}),
                         "/dev/full: write failed: No space left on device");
        ASSERT_EQ(::stat("/dev/full", &status), 0);
        EXPECT_TRUE(S_ISCHR(status.st_mode));
    }
    // A path without a mesh extension needs --format, refused before any work.
    expect_one_error(limsurf({"convert", cube, "/dev/null"}), "/dev/null: unknown mesh format");
}

TEST(CliHardening, AFifoIsWrittenThroughToItsReader) {
    const fs::path fifo = temp_dir() / "pipe.obj";
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::string received;
    std::thread reader([&] { received = test::slurp(fifo); });
    const CliRun run = limsurf({"convert", bundled("cube"), fifo.string()});
    // Should limsurf never have opened the FIFO (it failed to start), the reader would wait for a
    // writer forever: open and close one without blocking (ENXIO, harmless, when the reader is done).
    const int unblock = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (unblock >= 0) {
        ::close(unblock);
    }
    reader.join();
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(received.find("f 5 7 8 6"), std::string::npos) << received;
    EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST(CliHardening, SymbolicLinksKeepPointingAtTheReplacedTarget) {
    const fs::path dir = temp_dir() / "links";
    fs::create_directories(dir);
    const fs::path target = dir / "target.obj";
    std::ofstream(target) << "old\n";
    const fs::path link = dir / "link.obj";
    fs::remove(link);
    fs::create_symlink("target.obj", link);
    ASSERT_EQ(limsurf({"convert", bundled("cube"), link.string()}).exit_code, 0);
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_NE(test::slurp(target).find("f 5 7 8 6"), std::string::npos);
    // A dangling link: its target is created, as the shell's '>' does.
    const fs::path dangling = dir / "dangling.obj";
    fs::remove(dangling);
    fs::create_symlink("created.obj", dangling);
    ASSERT_EQ(limsurf({"convert", bundled("cube"), dangling.string()}).exit_code, 0);
    EXPECT_TRUE(fs::is_symlink(dangling));
    EXPECT_TRUE(fs::is_regular_file(dir / "created.obj"));
    // Nothing else was left in the folder (no temporary files).
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        names.push_back(entry.path().filename().string());
    }
    EXPECT_EQ(names.size(), 4U);
}

TEST(CliHardening, AnOutputThatIsTheInputIsRefused) {
    const fs::path dir = temp_dir() / "same";
    fs::create_directories(dir);
    const fs::path input = dir / "mesh.obj";
    fs::copy_file(bundled("cube"), input, fs::copy_options::overwrite_existing);
    const std::string before = test::slurp(input);
    const fs::path alias = dir / "alias.obj";
    fs::remove(alias);
    fs::create_symlink("mesh.obj", alias);
    const fs::path hard = dir / "hard.obj";
    fs::remove(hard);
    fs::create_hard_link(input, hard);
    for (const fs::path& output : {input, alias, hard}) {
        expect_one_error(limsurf({"convert", input.string(), output.string()}),
                         output.string() + ": is also the input '" + input.string() + "'");
        expect_one_error(limsurf({"subdivide", input.string(), "--scheme", "catmull-clark", "-o", output.string()}),
                         output.string() + ": is also the input");
        expect_one_error(
            limsurf({"poisson", input.string(), "--scheme", "catmull-clark", "--rhs", "x", "-o", output.string()}),
            output.string() + ": is also the input");
    }
    EXPECT_EQ(test::slurp(input), before);
}

// --- 5. inputs that are not what they claim ----------------------------------------------------

TEST(CliHardening, DirectoriesGivenAsInputsAreNamed) {
    const std::string dir = temp_dir().string();
    const std::string cube = bundled("cube");
    expect_one_error(limsurf({"eval", cube, "--scheme", "catmull-clark", "--points", dir}),
                     dir + ": cannot open: is a directory");
    expect_one_error(limsurf({"poisson", cube, "--scheme", "catmull-clark", "--rhs-file", dir}),
                     dir + ": cannot open: is a directory");
    expect_one_error(limsurf({"subdivide", bundled("quad_valence_5"), "--scheme", "catmull-clark", "--weights", dir,
                              "-o", (temp_dir() / "never.obj").string()}),
                     dir + ": cannot open: is a directory");
    expect_one_error(limsurf({"info", dir}), dir + ": unknown mesh format");
}

TEST(CliHardening, TunedWeightsOfAnySizeGiveFiniteRules) {
    // α, β, γ weigh the extraordinary vertex against neighbours of weight 1 (the paper's Fig. 1), so
    // 2¹⁰⁰⁰ times the cup weights is another scheme: the vertex, its edge points and its face points
    // all collapse onto it. The normalising sums must not overflow (they gave nan): the vertex stays
    // exactly where it is. 2⁻¹⁰⁰⁰ times them must give finite points too.
    const fs::path file = temp_dir() / "huge_weights.txt";
    const fs::path tiny_file = temp_dir() / "tiny_weights.txt";
    {
        std::ofstream huge(file);
        std::ofstream tiny(tiny_file);
        huge.precision(17);
        tiny.precision(17);
        huge << "5 " << std::ldexp(13.4575, 1000) << ' ' << std::ldexp(0.999938, 1000) << ' '
             << std::ldexp(0.999938, 1000) << '\n';
        tiny << "5 " << std::ldexp(13.4575, -1000) << ' ' << std::ldexp(0.999938, -1000) << ' '
             << std::ldexp(0.999938, -1000) << '\n';
    }
    const fs::path out = temp_dir() / "weights_out.obj";
    const std::string mesh = bundled("quad_valence_5");
    const BuildResult coarse = read_mesh(mesh);
    const Topology& t = coarse.mesh.topology();
    for (const fs::path& weights : {file, tiny_file}) {
        const CliRun run = limsurf({"subdivide", mesh, "--scheme", "catmull-clark", "--levels", "1", "--weights",
                                    weights.string(), "-o", out.string()});
        ASSERT_EQ(run.exit_code, 0) << run.err;
        const BuildResult fine = read_mesh(out);
        EXPECT_TRUE(fine.mesh.positions().allFinite()) << weights;
        if (weights != file) {
            continue;
        }
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (t.is_boundary_vertex(v) || t.valence(v) != 5) {
                continue;
            }
            EXPECT_LT((fine.mesh.positions().row(v) - coarse.mesh.positions().row(v)).norm(), 1e-12) << "vertex " << v;
            for (const Index f : t.vertex_faces(v)) {
                EXPECT_LT((fine.mesh.positions().row(t.num_vertices() + f) - coarse.mesh.positions().row(v)).norm(),
                          1e-12)
                    << "face " << f;
            }
        }
    }
}

// --- 6. memory ------------------------------------------------------------------------------

TEST(CliHardening, WorkBeyondTheMemoryBudgetIsRefusedBeforeAllocating) {
    const fs::path out = temp_dir() / "never_big.obj";
    // 14 levels: 1.6 G faces, past the face limit (raised here) and ~200 GB at the peak, past the budget of
    // any machine this runs on. (`subdivide` keeps two levels and the finest only as a face list, so 12
    // levels, 100 M faces, need ~11 GB: on a large machine they would be refined, not refused.)
    const auto [run, seconds] = timed({"subdivide", bundled("cube"), "--scheme", "catmull-clark", "--levels", "14",
                                       "--max-faces", "4000000000", "-o", out.string()});
    expect_one_error(run, bundled("cube") + ": catmull-clark with 14 levels needs about ");
    EXPECT_NE(run.err.find("more than the memory budget of"), std::string::npos) << run.err;
    EXPECT_LT(seconds, 1.0 * test::time_scale);
    EXPECT_FALSE(fs::exists(out));
    // --max-memory sets the budget.
    expect_one_error(limsurf({"subdivide", bundled("cube"), "--scheme", "loop", "--levels", "1", "-o", out.string()}),
                     bundled("cube") + ":10: face 0 has 4 vertices: Loop needs triangles");
    const CliRun small = limsurf({"subdivide", bundled("cube"), "--scheme", "catmull-clark", "--levels", "6",
                                  "--max-memory", "1M", "-o", out.string()});
    expect_one_error(small, bundled("cube") + ": catmull-clark with 6 levels needs about ");
    EXPECT_NE(small.err.find("memory budget of 1 MiB (max_memory)"), std::string::npos) << small.err;
    expect_one_error(limsurf({"subdivide", bundled("cube"), "--scheme", "catmull-clark", "--max-memory", "lots", "-o",
                              out.string()}),
                     "--max-memory: memory size 'lots' is not a positive size");
    // A reference that cannot be had is refused before the main solve, not after it.
    const auto [reference, reference_seconds] =
        timed({"poisson", bundled("sphere_quads"), "--scheme", "catmull-clark", "--rhs", "z", "--level", "4",
               "--reference-level", "7", "--max-memory", "100M"});
    expect_one_error(reference, bundled("sphere_quads") + ": the DEC reference on level 7 (");
    EXPECT_LT(reference_seconds, 1.0 * test::time_scale);
}

// --- 7. the smaller promises --------------------------------------------------------------------

TEST(CliHardening, LibraryErrorsNameTheInputFile) {
    // A zero-area limit surface: every vertex at the origin.
    const fs::path point = temp_dir() / "point.obj";
    std::ofstream(point) << "v 0 0 0\nv 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3 4\nf 4 3 2 1\n";
    const CliRun run = limsurf({"measure", point.string(), "--scheme", "catmull-clark"});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("error: " + point.string() + ": the limit surface has zero area"), std::string::npos)
        << run.err;
}

TEST(CliHardening, WarningsAreCapped) {
    // Thirty separate degenerate triangles: 30 warnings, of which ten are printed and one line counts the rest.
    const fs::path path = temp_dir() / "many_warnings.obj";
    std::ofstream out(path);
    for (int i = 0; i < 30; ++i) {
        out << "v " << i << " 0 0\nv " << i + 0.5 << " 0 0\nv " << i + 1 << " 0 1e-20\n";
    }
    for (int i = 0; i < 30; ++i) {
        out << "f " << 3 * i + 1 << ' ' << 3 * i + 2 << ' ' << 3 * i + 3 << '\n';
    }
    out.close();
    const CliRun run = limsurf({"convert", path.string(), (temp_dir() / "copy.off").string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    EXPECT_EQ(count_lines(run.err, "warning: "), 11) << run.err;
    EXPECT_NE(run.err.find("warning: … and 20 more warnings not shown ('limsurf info' lists them all)"),
              std::string::npos)
        << run.err;
    const CliRun info = limsurf({"info", path.string()});
    EXPECT_EQ(count_lines(info.out, "  warning: "), 30) << info.out;
}

TEST(CliHardening, ByteOrderMarksAndClassicMacLineEndingsAreRead) {
    const fs::path bom = temp_dir() / "bom.off";
    std::ofstream(bom) << "\xEF\xBB\xBFOFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    const CliRun a = limsurf({"info", "--json", bom.string()});
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(nlohmann::json::parse(a.out)["num_faces"], 4);
    const fs::path cr = temp_dir() / "cr.obj";
    std::ofstream(cr) << "v 0 0 0\rv 1 0 0\rv 0 1 0\rv 0 0 1\rf 1 3 2\rf 1 2 4\rf 1 4 3\rf 2 3 4\r";
    const CliRun b = limsurf({"info", "--json", cr.string()});
    ASSERT_EQ(b.exit_code, 0) << b.err;
    EXPECT_EQ(nlohmann::json::parse(b.out)["num_faces"], 4);
    const fs::path ply = temp_dir() / "cr.ply";
    std::ofstream(ply) << "ply\rformat ascii 1.0\relement vertex 0\rend_header\r";
    expect_one_error(limsurf({"info", ply.string()}), ply.string() + ":1: a carriage return");
}

// --- 8. every option with hostile values (a sweep of 19 commands × their options, 2026-12-06) ---

/// Exit 2 (a usage mistake, refused before any work) with "error: " + @p start + … on stderr.
void expect_usage_error(const CliRun& run, const std::string& start) {
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_EQ(run.err.rfind("error: " + start, 0), 0U) << run.err;
}

/// The names of the files in @p dir.
std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        names.push_back(entry.path().filename().string());
    }
    return names;
}

TEST(CliHardening, TinyMembraneTargetsAreRefusedNotCrashed) {
    // A subnormal V0 or M0 made the scale of its constraint, 1/target, infinite: SIGSEGV inside
    // the solver's linear algebra, no message.
    const std::string out = (temp_dir() / "membrane_tiny.obj").string();
    const auto membrane = [&](const std::vector<std::string>& targets) {
        std::vector<std::string> args{"membrane",           bundled("octahedron"), "--scheme", "loop", "--area",
                                      "12.566370614359172", "--max-iterations",    "3",        "-o",   out};
        args.insert(args.end(), targets.begin(), targets.end());
        return limsurf(args);
    };
    expect_one_error(membrane({"--volume", "1e-320"}), "volume V0 = ");
    const CliRun tiny_v = membrane({"--reduced-volume", "1e-310"});
    expect_one_error(tiny_v, "reduced volume v0 = ");
    EXPECT_NE(tiny_v.err.find(": must be at least 9.9999999999999995e-07"), std::string::npos) << tiny_v.err;
    expect_one_error(membrane({"--reduced-volume", "1e-7"}),
                     "reduced volume v0 = 9.9999999999999995e-08: must be at least");
    expect_one_error(limsurf({"membrane", bundled("octahedron"), "--scheme", "loop", "--area", "1e308",
                              "--reduced-volume", "0.9", "-o", out}),
                     "area A0 = 1e+308: must lie in [1e-100, 1e+100]");
    EXPECT_FALSE(fs::exists(out));
    // A tiny M0 is scaled as M0 = 0 is (by the sphere's M): the solve runs (and stops after 3 iterations).
    const CliRun tiny_m = membrane({"--reduced-volume", "0.9", "--mean-curvature", "1e-320"});
    EXPECT_EQ(tiny_m.exit_code, 0) << tiny_m.err;
    EXPECT_TRUE(fs::exists(out));
}

TEST(CliHardening, EveryWriterPassesDevicesThrough) {
    // vector-field and hodge wrote a temporary file and renamed it over the output: run as root
    // with -o /dev/full, they replaced the device with a regular file and reported success.
    if (!fs::exists("/dev/full")) {
        GTEST_SKIP() << "no /dev/full on this system";
    }
    const std::string cube = bundled("cube");
    expect_one_error(
        limsurf({"hodge", cube, "--scheme", "catmull-clark", "--method", "dec", "--random", "1", "-o", "/dev/full"}),
        "/dev/full: write failed: No space left on device");
    expect_one_error(limsurf({"vector-field", cube, "--scheme", "catmull-clark", "--method", "dec", "--source", "0:1",
                              "--sink", "6:1", "-o", "/dev/full"}),
                     "/dev/full: write failed: No space left on device");
    struct stat status {};
    ASSERT_EQ(::stat("/dev/full", &status), 0);
    EXPECT_TRUE(S_ISCHR(status.st_mode)) << "/dev/full is no longer a character device";
}

TEST(CliHardening, NoOutputIsWrittenWhenAnotherOneCannotBe) {
    // Each command wrote its outputs one after the other and failed on the first it could not
    // write, keeping those before it; now every path is checked before any work.
    const fs::path dir = temp_dir() / "several_outputs";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string missing = (temp_dir() / "no_such_folder" / "x.png").string();
    const std::string folder_error =
        missing + ": the folder '" + (temp_dir() / "no_such_folder").string() + "' does not exist";
    const std::string cube = bundled("cube");
    const std::string disk = bundled("disk_ev5_quads");
    const auto in_dir = [&](const char* name) { return (dir / name).string(); };
    expect_one_error(limsurf({"geodesic", cube, "--scheme", "catmull-clark", "--source", "0", "--level", "1", "-o",
                              in_dir("a.ply"), "--png", missing}),
                     folder_error);
    expect_one_error(limsurf({"parameterize", disk, "--scheme", "catmull-clark", "--method", "dec", "-o",
                              in_dir("a.ply"), "--texture-png", missing}),
                     folder_error);
    expect_one_error(
        limsurf({"vector-field", cube, "--scheme", "catmull-clark", "--method", "dec", "--source", "0:1", "--sink",
                 "6:1", "--save-one-form", in_dir("w.txt"), "-o", in_dir("v.vtk"), "--png", missing}),
        folder_error);
    expect_one_error(limsurf({"hodge", cube, "--scheme", "catmull-clark", "--method", "dec", "--random", "1",
                              "--save-parts", in_dir("p_"), "-o", missing}),
                     folder_error);
    // Two outputs naming one file, and an output that is a folder.
    expect_one_error(limsurf({"geodesic", cube, "--scheme", "catmull-clark", "--source", "0", "--level", "1", "-o",
                              in_dir("a.png"), "--png", (dir / "." / "a.png").string()}),
                     (dir / "." / "a.png").string() + ": names the same file as the output '" + in_dir("a.png") + "'");
    const fs::path folder = dir / "folder.obj";
    fs::create_directories(folder);
    expect_one_error(limsurf({"subdivide", cube, "--scheme", "catmull-clark", "-o", folder.string()}),
                     folder.string() + ": is a directory");
    EXPECT_EQ(files_in(dir), std::vector<std::string>{"folder.obj"});
}

TEST(CliHardening, UsageMistakesAreNamed) {
    const CliRun unknown = limsurf({"nosuch"});
    expect_usage_error(unknown, "unknown command 'nosuch'; the commands are info, convert, subdivide");
    expect_usage_error(limsurf({"--bogus"}), "unknown option '--bogus' before the command");
    // An empty value was read as 0 (--nu '') or as "not given" (-o '').
    const std::string plate = bundled("plate_sym");
    expect_usage_error(limsurf({"plate", plate, "--nu", ""}), "argument 4 (after '--nu') is empty");
    expect_usage_error(limsurf({"plate", plate, "--nu="}), "'--nu=' has an empty value");
    // CLI11's own range checks printed the largest double in full (309 digits) and let nan through.
    const std::string out = (temp_dir() / "never.obj").string();
    const CliRun faces =
        limsurf({"subdivide", bundled("cube"), "--scheme", "catmull-clark", "-o", out, "--max-faces", "0"});
    expect_usage_error(faces, "--max-faces: '0' is not a positive finite number");
    EXPECT_LT(faces.err.size(), 200U) << faces.err;
    expect_usage_error(limsurf({"reverse", bundled("cube"), "-o", out, "--tolerance", "nan"}),
                       "--tolerance: 'nan' is not a finite number >= 0");
    // The texture's size and view are checked whether or not a texture is asked for.
    expect_usage_error(
        limsurf({"parameterize", bundled("disk_ev5_quads"), "--scheme", "catmull-clark", "--size", "abc"}),
        "--size: expected WIDTHxHEIGHT");
    expect_usage_error(
        limsurf({"parameterize", bundled("disk_ev5_quads"), "--scheme", "catmull-clark", "--view", "abc"}), "--view: ");
    // --format and --ply-encoding that contradict the output.
    expect_one_error(limsurf({"convert", bundled("cube"), (temp_dir() / "o.ply").string(), "--format", "off"}),
                     (temp_dir() / "o.ply").string() + ": --format off contradicts the extension '.ply'");
    expect_one_error(limsurf({"convert", bundled("cube"), out, "--ply-encoding", "binary-le"}),
                     "--ply-encoding binary-le applies to PLY output only, and the output is OBJ");
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(temp_dir() / "o.ply"));
}

TEST(CliHardening, FormulasAreOneExpressionAndCheckedBeforeUse) {
    // muParser reads "1,2" as two expressions and returns the last: f = 2, silently.
    const std::string cube = bundled("cube");
    expect_one_error(limsurf({"poisson", cube, "--scheme", "catmull-clark", "--rhs", "1,2"}),
                     "--rhs '1,2' has 2 comma-separated values: give one expression");
    expect_one_error(limsurf({"plate", bundled("plate_sym"), "--load", "x,y"}),
                     "--load 'x,y' has 2 comma-separated values");
    expect_one_error(limsurf({"hodge", cube, "--scheme", "catmull-clark", "--method", "dec", "--field", "x,y;0;0"}),
                     cube + ": --field 'x,y' has 2 comma-separated values");
    // A boundary value on a closed mesh is not used, but a malformed one is still a mistake.
    expect_one_error(limsurf({"poisson", cube, "--scheme", "catmull-clark", "--rhs", "x", "--boundary-value", "abc"}),
                     "--boundary-value 'abc': ");
}

TEST(CliHardening, DegenerateNumbersAreNamedForWhatTheyAre) {
    const std::string cube = bundled("cube");
    const std::string plate = bundled("plate_sym");
    // A 1-form has one value per edge: the cube's 8 vertices were named instead of its 12 edges.
    const fs::path form = temp_dir() / "eleven_values.txt";
    {
        std::ofstream file(form);
        for (int i = 0; i < 11; ++i) {
            file << i << '\n';
        }
    }
    expect_one_error(
        limsurf({"hodge", cube, "--scheme", "catmull-clark", "--method", "dec", "--one-form", form.string()}),
        form.string() + ": 11 values, but the mesh has 12 edges");
    // p = 0 made the comparison with Navier 0/0, reported as an overflow.
    expect_one_error(limsurf({"plate", plate, "--pressure", "0"}),
                     plate + ": plate: the pressure p = 0 must be a non-zero");
    // Subnormal moduli were reported as degenerate geometry or as an overflow of the results.
    expect_one_error(limsurf({"plate", plate, "--E", "1e-320"}), plate + ": plate: E = ");
    expect_one_error(limsurf({"shell", bundled("shell_scordelis_lo"), "--E", "1e-320", "--gravity", "90"}),
                     bundled("shell_scordelis_lo") + ": shell: E = ");
    expect_one_error(limsurf({"elasticity", bundled("rve_block"), "--E", "1e-320"}), "--E/--nu: elasticity: E = ");
    // The evaluation path checks H0 as the solve path does (it reported the Helfrich energy's overflow).
    expect_one_error(limsurf({"membrane", bundled("tetra_3"), "--scheme", "c2g0", "--evaluate-only",
                              "--spontaneous-curvature", "nan"}),
                     "--spontaneous-curvature: H0 must be a finite number, not nan");
    // A sink was called a source, and its nan reached the library.
    expect_one_error(limsurf({"vector-field", cube, "--scheme", "catmull-clark", "--method", "dec", "--sink", "6:nan"}),
                     cube + ": --sink '6:nan': 'nan' is not a finite number");
    // A heat flow so long that M + tL lost M to rounding gave 0.5 everywhere, the source too, and exit 0.
    expect_one_error(limsurf({"geodesic", cube, "--scheme", "catmull-clark", "--source", "0", "--level", "1",
                              "--time-factor", "1e200"}),
                     cube + ": the time step t = 9.9999999999999997e+199 makes t L_ii up to ");
    const CliRun long_but_fine = limsurf({"geodesic", cube, "--scheme", "catmull-clark", "--source", "0", "--level",
                                          "1", "--time-factor", "1e6", "--json"});
    ASSERT_EQ(long_but_fine.exit_code, 0) << long_but_fine.err;
    EXPECT_GT(json_number(long_but_fine.out, "distance_max"), 0.5) << long_but_fine.out;
}

// Before: --level with dec or iga, and --degree or --tiles with dec or sec, were ignored without a word
// (a user comparing "sec --level 1" with "dec --level 1" compared nothing); --lumped with iga already
// was refused.
TEST(CliHardening, OptionsTheMethodDoesNotUseAreRefused) {
    const std::string cube = bundled("cube");
    const std::vector<std::string> poisson{"poisson", cube, "--scheme", "catmull-clark", "--rhs", "x"};
    const auto with = [](std::vector<std::string> args, const std::vector<std::string>& more) {
        args.insert(args.end(), more.begin(), more.end());
        return args;
    };
    expect_one_error(limsurf(with(poisson, {"--method", "dec", "--level", "2"})),
                     "--level applies to --method sec and secsnap, not to dec");
    expect_one_error(limsurf(with(poisson, {"--method", "iga", "--level", "2"})),
                     "--level applies to --method sec and secsnap, not to iga");
    expect_one_error(limsurf(with(poisson, {"--degree", "4"})), "--degree applies to --method iga, not to sec");
    expect_one_error(limsurf(with(poisson, {"--method", "secsnap", "--tiles", "2"})),
                     "--tiles applies to --method iga, not to secsnap");
    expect_one_error(limsurf({"geodesic", cube, "--scheme", "catmull-clark", "--source", "0", "--method", "decsnap",
                              "--level", "1"}),
                     "--level applies to --method sec and secsnap, not to decsnap");
    expect_one_error(
        limsurf({"hodge", cube, "--scheme", "catmull-clark", "--method", "dec", "--level", "1", "--random", "1"}),
        "--level applies to --method sec and secsnap, not to dec");
    expect_one_error(limsurf({"vector-field", cube, "--scheme", "catmull-clark", "--method", "dec", "--level", "1",
                              "--source", "0:1"}),
                     "--level applies to --method sec and secsnap, not to dec");
    expect_one_error(
        limsurf({"parameterize", bundled("quad_grid"), "--scheme", "catmull-clark", "--method", "iga", "--level", "1"}),
        "--level applies to --method sec and secsnap, not to iga");
    // What each method uses still runs: iga's quadrature, sec's level, and parameterize's distortion
    // quadrature (--degree there is not iga's) with any method.
    EXPECT_EQ(limsurf(with(poisson, {"--method", "iga", "--degree", "2", "--tiles", "1"})).exit_code, 0);
    EXPECT_EQ(limsurf(with(poisson, {"--method", "sec", "--level", "1"})).exit_code, 0);
    const CliRun dec_distortion = limsurf({"parameterize", bundled("quad_grid"), "--scheme", "catmull-clark",
                                           "--method", "dec", "--degree", "2", "--tiles", "1"});
    EXPECT_EQ(dec_distortion.exit_code, 0) << dec_distortion.err;
}

}  // namespace
}  // namespace limsurf
