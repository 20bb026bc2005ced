// evaluate_points (limit/batch_evaluation.h): bit for bit LimitBasis::evaluate at every point, for any
// thread count, every scheme with a limit basis; bad points refused before any work, naming the point.
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/batch_evaluation.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

std::vector<SurfacePoint> random_points(const LimitBasis& basis, int count) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<Index> face(0, basis.num_ptex_faces() - 1);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<SurfacePoint> points;
    while (static_cast<int>(points.size()) < count) {
        SurfacePoint p{face(rng), uniform(rng), uniform(rng)};
        if (basis.domain() == ParameterDomain::Triangle && p.u + p.v > 1.0) {
            p = {p.face, 1.0 - p.u, 1.0 - p.v};
        }
        if (basis.has_limit_surface(p.face)) {
            points.push_back(p);
        }
    }
    points.push_back({points.front().face, 0.0, 0.0});  // a corner: a vertex of the control mesh
    return points;
}

// Every scheme with a limit basis: Catmull–Clark (with creases, with n-gons), Loop (boundary),
// Doo–Sabin and C2g0.
const std::pair<const char*, SchemeKind> meshes_and_schemes[] = {
    {"genus2", SchemeKind::CatmullClark},     {"cube_creases", SchemeKind::CatmullClark},
    {"cube_ngons", SchemeKind::CatmullClark}, {"disk_ev7_tris", SchemeKind::Loop},
    {"dodecahedron", SchemeKind::DooSabin},   {"tetra_1", SchemeKind::C2g0}};

TEST(BatchEvaluation, EqualsPointByPointEvaluationForAnyThreadCount) {
    for (const auto& [name, scheme] : meshes_and_schemes) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(find_bundled(name).path);
        const Points& X = built.mesh.positions();
        const LimitBasis basis(built.mesh.topology(), scheme);
        const std::vector<SurfacePoint> points = random_points(basis, 500);
        for (const auto order : {DerivativeOrder::Value, DerivativeOrder::First, DerivativeOrder::Second}) {
            const int rows = order == DerivativeOrder::Value ? 1 : order == DerivativeOrder::First ? 3 : 6;
            for (const int threads : {1, 2, 3}) {
                const PointValues values = evaluate_points(basis, X, points, order, threads);
                ASSERT_EQ(values.rows(), static_cast<Eigen::Index>(points.size()));
                ASSERT_EQ(values.cols(), 3 * rows);
                for (std::size_t i = 0; i < points.size(); ++i) {
                    const Eigen::Matrix<double, 6, 3> one = basis.evaluate(X, points[i], order);
                    for (int r = 0; r < rows; ++r) {
                        for (int c = 0; c < 3; ++c) {
                            ASSERT_EQ(values(static_cast<Eigen::Index>(i), 3 * r + c), one(r, c))
                                << "point " << i << " row " << r << " threads " << threads;
                        }
                    }
                }
            }
        }
    }
}

TEST(BatchEvaluation, RefusesBadPointsNamingThem) {
    const BuildResult built = read_mesh(find_bundled("quad_grid").path);
    const Points& X = built.mesh.positions();
    SchemeOptions none;
    none.boundary = BoundaryInterpolation::None;
    const LimitBasis basis(built.mesh.topology(), SchemeKind::CatmullClark, none);
    Index hole = 0;
    while (basis.has_limit_surface(hole)) {
        ++hole;
    }
    const auto message = [&](std::vector<SurfacePoint> points, const Points& positions) {
        try {
            (void)evaluate_points(basis, positions, points, DerivativeOrder::First, 2);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    Index inside = 0;
    while (!basis.has_limit_surface(inside)) {
        ++inside;
    }
    const SurfacePoint good{inside, 0.5, 0.5};
    EXPECT_NE(message({good, good, {basis.num_ptex_faces(), 0.5, 0.5}}, X).find("point 2: ptex face"),
              std::string::npos);
    EXPECT_NE(message({good, {inside, 1.5, 0.5}}, X).find("point 1: parameter (1.5, 0.5) is outside"),
              std::string::npos);
    EXPECT_NE(message({good, {inside, std::nan(""), 0.5}}, X).find("point 1"), std::string::npos);
    EXPECT_NE(message({{hole, 0.5, 0.5}}, X).find("point 0: ptex face " + std::to_string(hole) + " has no limit"),
              std::string::npos);
    EXPECT_NE(message({good}, X.topRows(3)).find("positions are 3 × 3"), std::string::npos);
    // Checked on the batch's threads: the lowest bad point is named for any number of threads,
    // also when a later range meets its own bad point first.
    std::vector<SurfacePoint> many(1000, good);
    many[300] = {inside, -1.0, 0.5};
    many[900] = {inside, 2.0, 0.5};
    for (const int threads : {1, 2, 3}) {
        std::string what = "no error";
        try {
            (void)evaluate_points(basis, X, many, DerivativeOrder::First, threads);
        } catch (const InputError& e) {
            what = e.what();
        }
        EXPECT_NE(what.find("point 300: parameter (-1, 0.5) is outside"), std::string::npos) << threads << ": " << what;
    }
}

// LimitBasis::prefetch is a hint: for any point, any stage, any X (wrong size included), on a fresh
// basis (no local patch built yet) and a warm one, it reads nothing out of range and changes no
// result. Run it under the asan preset to see an out-of-range read; here a crash fails it.
TEST(BatchEvaluation, PrefetchAsksForNothingItCannotUse) {
    using Stage = LimitBasis::PrefetchStage;
    for (const auto& [name, scheme] : meshes_and_schemes) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(find_bundled(name).path);
        const Points& X = built.mesh.positions();
        const InterleavedPoints interleaved(X);
        const InterleavedPoints too_small = interleaved.topRows(1);
        const LimitBasis basis(built.mesh.topology(), scheme);
        const LimitBasis untouched(built.mesh.topology(), scheme);
        const std::vector<SurfacePoint> points = random_points(basis, 200);
        std::vector<SurfacePoint> odd = points;
        const double nan = std::nan("");
        for (const Index face : {Index{-1}, basis.num_ptex_faces(), std::numeric_limits<Index>::max(),
                                 std::numeric_limits<Index>::min()}) {
            odd.push_back({face, 0.5, 0.5});
        }
        odd.push_back({0, nan, -7.0});
        for (int pass = 0; pass < 2; ++pass) {  // fresh, then with every root built
            for (const SurfacePoint& p : odd) {
                for (const Stage stage : {Stage::Lookup, Stage::Patch, Stage::ControlPoints}) {
                    basis.prefetch(interleaved, p, stage);
                    basis.prefetch(too_small, p, stage);
                }
            }
            for (const SurfacePoint& p : points) {
                const Eigen::Matrix<double, 6, 3> ours = basis.evaluate(X, p, DerivativeOrder::Second);
                const Eigen::Matrix<double, 6, 3> theirs = untouched.evaluate(X, p, DerivativeOrder::Second);
                ASSERT_EQ(ours, theirs) << "face " << p.face;
            }
        }
    }
}

}  // namespace
}  // namespace limsurf::test
