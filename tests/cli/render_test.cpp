// `limsurf render`: a PNG of the right size whose pixels decode (stb_image) and whose JSON reports the
// coverage and the field; a field from `limsurf poisson -o u.vtk` read back (values within the vertex
// values: the limit basis is a convex combination); the same input twice gives the same bytes; a .glb;
// and the errors: unknown field name (listing the file's), a point count that is not the mesh's, NaN in
// the file (file:line and the point), an unknown output format, bad --size and --view (usage), and never a
// file left behind.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include "cli_runner.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_render");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

std::string out(const std::string& name) {
    return (temp_dir() / name).string();
}

std::string bytes_of(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path) << text;
}

TEST(CliRender, WritesAPngOfTheAskedSizeAndReportsIt) {
    const std::string png = out("sphere.png");
    const CliRun run = limsurf({"render", mesh("sphere_quads"), "--scheme", "catmull-clark", "--field",
                                "mean-curvature", "--isolines", "4", "--control-mesh", "--view", "front", "--size",
                                "200x150", "--resolution", "4", "-o", png, "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json.at("width").get<int>(), 200);
    EXPECT_EQ(json.at("height").get<int>(), 150);
    EXPECT_EQ(json.at("format").get<std::string>(), "png");
    EXPECT_EQ(json.at("field").get<std::string>(), "mean_curvature");
    EXPECT_EQ(json.at("resolution").get<int>(), 4);
    EXPECT_EQ(json.at("triangles").get<int>(), 96 * 32);
    EXPECT_GT(json.at("coverage").get<double>(), 0.2);  // the fit includes the control points, outside the surface
    EXPECT_LT(json.at("coverage").get<double>(), 0.6);
    EXPECT_GT(json.at("field_min").get<double>(), 0.5);  // H of a near-unit sphere
    EXPECT_LT(json.at("field_max").get<double>(), 2.0);
    EXPECT_EQ(json.at("range")[0].get<double>(), json.at("field_min").get<double>());
    int w = 0;
    int h = 0;
    int channels = 0;
    unsigned char* pixels = stbi_load(png.c_str(), &w, &h, &channels, 3);
    ASSERT_NE(pixels, nullptr);
    EXPECT_EQ(w, 200);
    EXPECT_EQ(h, 150);
    EXPECT_EQ(pixels[0], 255);  // white background in the corner
    stbi_image_free(pixels);

    const CliRun again = limsurf({"render", mesh("sphere_quads"), "--scheme", "catmull-clark", "--field",
                                  "mean-curvature", "--isolines", "4", "--control-mesh", "--view", "front", "--size",
                                  "200x150", "--resolution", "4", "-o", out("sphere2.png")});
    ASSERT_EQ(again.exit_code, 0) << again.err;
    EXPECT_NE(again.out.find("wrote"), std::string::npos) << again.out;
    EXPECT_EQ(bytes_of(png), bytes_of(out("sphere2.png")));  // deterministic
}

TEST(CliRender, ColoursBySolutionFromPoisson) {
    const std::string vtk = out("u.vtk");
    const CliRun solve = limsurf({"poisson", mesh("sphere_tris"), "--scheme", "loop", "--rhs", "z", "-o", vtk});
    ASSERT_EQ(solve.exit_code, 0) << solve.err;
    const CliRun run = limsurf({"render", mesh("sphere_tris"), "--scheme", "loop", "--field", vtk + ":u", "--size",
                                "120x90", "--resolution", "3", "--colormap", "coolwarm", "-o", out("u.png"), "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json.at("field").get<std::string>(), "u");
    const double lo = json.at("field_min").get<double>();
    const double hi = json.at("field_max").get<double>();
    EXPECT_LT(lo, 0.0);  // u follows z: both signs
    EXPECT_GT(hi, 0.0);
    EXPECT_EQ(json.at("range")[1].get<double>(), -json.at("range")[0].get<double>());  // diverging: symmetric

    // Another mesh's field: the count differs.
    const CliRun wrong = limsurf({"render", mesh("icosahedron"), "--scheme", "loop", "--field", vtk + ":u", "--size",
                                  "120x90", "-o", out("wrong.png")});
    EXPECT_EQ(wrong.exit_code, 1);
    EXPECT_NE(wrong.err.find("42 values, but the mesh"), std::string::npos) << wrong.err;
    EXPECT_FALSE(fs::exists(out("wrong.png")));
    const CliRun missing = limsurf({"render", mesh("sphere_tris"), "--scheme", "loop", "--field", vtk + ":v", "--size",
                                    "120x90", "-o", out("missing.png")});
    EXPECT_EQ(missing.exit_code, 1);
    EXPECT_NE(missing.err.find("no point scalar 'v' (the file's point scalars: u, f)"), std::string::npos)
        << missing.err;
    EXPECT_FALSE(fs::exists(out("missing.png")));
}

TEST(CliRender, RefusesANonFiniteFieldNamingTheLineAndPoint) {
    const std::string vtk = out("nan.vtk");
    write_text(vtk, "# vtk DataFile Version 3.0\nlimsurf\nASCII\nDATASET POLYDATA\nPOINTS 8 double\n"
                    "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                    "POINT_DATA 8\nSCALARS u double 1\nLOOKUP_TABLE default\n0\n1\n2\nnan\n4\n5\n6\n7\n");
    const CliRun run =
        limsurf({"render", mesh("cube"), "--scheme", "catmull-clark", "--field", vtk + ":u", "-o", out("nan.png")});
    EXPECT_EQ(run.exit_code, 1);
    EXPECT_NE(run.err.find("nan.vtk:20: 'u' at point 3: value 'nan' is not finite"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(out("nan.png")));
}

TEST(CliRender, WritesGltf) {
    const std::string glb = out("cube.glb");
    const CliRun run = limsurf({"render", mesh("cube"), "--scheme", "catmull-clark", "--field", "gaussian-curvature",
                                "--resolution", "3", "-o", glb, "--json"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const auto json = nlohmann::json::parse(run.out);
    EXPECT_EQ(json.at("format").get<std::string>(), "glb");
    EXPECT_EQ(json.at("points").get<int>(), 6 * 16);
    EXPECT_FALSE(json.contains("coverage"));
    const std::string bytes = bytes_of(glb);
    ASSERT_GE(bytes.size(), 12u);
    EXPECT_EQ(bytes.substr(0, 4), "glTF");
    EXPECT_NE(bytes.find("_GAUSSIAN_CURVATURE"), std::string::npos);
    EXPECT_NE(bytes.find("COLOR_0"), std::string::npos);
}

TEST(CliRender, BadOptionsAndOutputs) {
    const std::string cube = mesh("cube");
    const auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args{"render", cube, "--scheme", "catmull-clark"};
        args.insert(args.end(), extra.begin(), extra.end());
        return limsurf(args);
    };
    const CliRun jpg = run({"-o", out("a.jpg")});
    EXPECT_EQ(jpg.exit_code, 1);
    EXPECT_NE(jpg.err.find("unknown output format '.jpg' (expected .png or .glb)"), std::string::npos) << jpg.err;
    EXPECT_FALSE(fs::exists(out("a.jpg")));
    EXPECT_EQ(run({"--size", "10x10", "-o", out("b.png")}).exit_code, 2);
    EXPECT_EQ(run({"--size", "200", "-o", out("b.png")}).exit_code, 2);
    EXPECT_EQ(run({"--view", "sideways", "-o", out("b.png")}).exit_code, 2);
    EXPECT_EQ(run({"--range", "2,1", "-o", out("b.png")}).exit_code, 2);
    EXPECT_EQ(run({"--field", "curvature", "-o", out("b.png")}).exit_code, 2);
    EXPECT_EQ(run({"--isolines", "-1", "-o", out("b.png")}).exit_code, 2);
    EXPECT_FALSE(fs::exists(out("b.png")));
    const CliRun loop = limsurf({"render", cube, "--scheme", "loop", "-o", out("c.png")});  // quads under Loop
    EXPECT_NE(loop.exit_code, 0);
    EXPECT_FALSE(fs::exists(out("c.png")));
    const CliRun overwrite = limsurf({"render", cube, "--scheme", "catmull-clark", "-o", cube});
    EXPECT_EQ(overwrite.exit_code, 1);
    EXPECT_NE(overwrite.err.find("is also the input"), std::string::npos) << overwrite.err;
}

}  // namespace
}  // namespace limsurf
