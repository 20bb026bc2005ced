// `limsurf parameterize`: the spectral map of a planar mesh is conformal (distortion 1), SEC is
// closer to conformal than DEC on the pinched hemisphere, the circle boundary with a reference
// reports L2/L∞ (SEC below DEC), the outputs (OBJ with one `vt` per vertex read back, VTK with u
// and v, a PNG), and errors with one line and exit 1: a closed mesh, two boundary loops for the
// circle, a reference with the free boundary, a quad mesh under loop.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "limsurf/io/vtk.h"
#include "support/mesh_zoo.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

using test::CliRun;

const fs::path& temp_dir() {
    static const fs::path dir = test::make_temp_dir("cli_parameterize");
    return dir;
}

CliRun limsurf(const std::vector<std::string>& args) {
    return test::run_limsurf(args, temp_dir());
}

std::string mesh(const std::string& name) {
    return test::find_bundled(name).path.string();
}

nlohmann::json run_json(const std::vector<std::string>& args) {
    std::vector<std::string> full{"parameterize"};
    full.insert(full.end(), args.begin(), args.end());
    full.emplace_back("--json");
    const CliRun run = limsurf(full);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return run.exit_code == 0 ? nlohmann::json::parse(run.out) : nlohmann::json::object();
}

TEST(CliParameterize, PlanarMeshIsMappedConformally) {
    for (const std::string method : {"sec", "iga"}) {
        SCOPED_TRACE(method);
        std::vector<std::string> args{mesh("quad_grid"), "--scheme", "catmull-clark", "--method", method};
        if (method == "sec") {
            args.insert(args.end(), {"--level", "2"});  // refused with iga, which has no level
        }
        const auto out = run_json(args);
        EXPECT_EQ(out.at("method"), method);
        EXPECT_EQ(out.at("level"), method == "sec" ? 2 : 0);
        EXPECT_EQ(out.at("boundary"), "free");
        EXPECT_LT(std::abs(out.at("eigenvalue").get<double>()), 1e-10);
        // Exact up to rounding near the corners, where the quadrature's tiles shrink (measured 2e-8).
        EXPECT_NEAR(out.at("distortion").at("mean").get<double>(), 1.0, 1e-8);
        EXPECT_NEAR(out.at("distortion").at("max").get<double>(), 1.0, 1e-7);
        EXPECT_EQ(out.at("distortion").at("flipped").get<int>(), 0);
        // The grid is [-1, 1]²: mapped isometrically (area-normalised) and rotated so that its first
        // boundary vertex, the corner (-1, -1), lies on the +u axis: u spans the diagonal, 2√2.
        EXPECT_NEAR(out.at("u_max").get<double>() - out.at("u_min").get<double>(), 2.0 * std::sqrt(2.0), 1e-8);
        EXPECT_NEAR(out.at("u_max").get<double>(), std::sqrt(2.0), 1e-8);
    }
}

TEST(CliParameterize, SecIsCloserToConformalThanDec) {
    auto mean = [](const std::string& method) {
        return run_json({mesh("shell_hemisphere"), "--scheme", "catmull-clark", "--method", method})  // sec: L = 3
            .at("distortion")
            .at("mean")
            .get<double>();
    };
    const double dec = mean("dec");
    const double sec = mean("sec");
    EXPECT_GT(dec - 1.0, 4.0 * (sec - 1.0)) << "dec " << dec << " sec " << sec;
}

TEST(CliParameterize, CircleWithReference) {
    auto reference = [](const std::string& method) {
        const auto out = run_json({mesh("disk_ev7_tris"), "--scheme", "loop", "--method", method, "--boundary",
                                   "circle", "--reference-level", "3"});
        EXPECT_TRUE(out.at("eigenvalue").is_null());
        EXPECT_EQ(out.at("reference").at("level").get<int>(), 3);
        EXPECT_GT(out.at("boundary_length").get<double>(), 0.0);
        return out.at("reference");
    };
    const auto dec = reference("dec");
    const auto sec = reference("sec");
    EXPECT_LT(sec.at("l2_relative").get<double>(), 0.5 * dec.at("l2_relative").get<double>());
    EXPECT_LT(sec.at("linf_relative").get<double>(), dec.at("linf_relative").get<double>());
}

TEST(CliParameterize, WritesObjWithTextureCoordinatesVtkAndPng) {
    const fs::path obj = temp_dir() / "map.obj";
    const fs::path vtk = temp_dir() / "map.vtk";
    const fs::path png = temp_dir() / "map.png";
    const auto out = run_json({mesh("disk_ev5_quads"), "--scheme", "catmull-clark", "--method", "dec", "-o",
                               obj.string(), "--texture-png", png.string(), "--size", "200x150", "--squares", "4"});
    ASSERT_TRUE(fs::exists(obj));
    ASSERT_TRUE(fs::exists(png));
    EXPECT_GT(fs::file_size(png), 1000U);
    std::ifstream in(obj);
    std::string line;
    int vertices = 0;
    int texcoords = 0;
    double u_min = 1e300;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) {
            ++vertices;
        } else if (line.rfind("vt ", 0) == 0) {
            ++texcoords;
            std::istringstream fields(line.substr(3));
            double u = 0.0;
            fields >> u;
            u_min = std::min(u_min, u);
        } else if (line.rfind("f ", 0) == 0) {
            EXPECT_NE(line.find('/'), std::string::npos) << line;
        }
    }
    EXPECT_EQ(vertices, test::find_bundled("disk_ev5_quads").num_vertices);
    EXPECT_EQ(texcoords, vertices);
    EXPECT_DOUBLE_EQ(u_min, out.at("u_min").get<double>());
    const CliRun run = limsurf(
        {"parameterize", mesh("disk_ev5_quads"), "--scheme", "catmull-clark", "--method", "dec", "-o", vtk.string()});
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const Eigen::VectorXd v = read_vtk_point_scalar(vtk, "v");
    EXPECT_EQ(v.size(), vertices);
    EXPECT_DOUBLE_EQ(v.minCoeff(), out.at("v_min").get<double>());
    EXPECT_NE(run.out.find("distortion"), std::string::npos);
}

TEST(CliParameterize, RefusesWithOneLine) {
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases{
        {{mesh("sphere_quads"), "--scheme", "catmull-clark"}, "closed"},
        {{mesh("annulus"), "--scheme", "catmull-clark", "--boundary", "circle"}, "2 boundary loops"},
        {{mesh("quad_grid"), "--scheme", "catmull-clark", "--reference-level", "2"}, "circle"},
        {{mesh("quad_grid"), "--scheme", "loop"}, "loop"},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args{"parameterize"};
        args.insert(args.end(), c.args.begin(), c.args.end());
        const CliRun run = limsurf(args);
        EXPECT_EQ(run.exit_code, 1) << c.message;
        EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

}  // namespace
}  // namespace limsurf
