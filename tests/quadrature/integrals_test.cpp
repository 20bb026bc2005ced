// The limit sampler and the integrals on it: identities (gradients against finite
// differences, rigid motions and scaling, orientation), an analytic value (the area of a
// planar grid's limit surface from its B-spline boundary curve; the inertia of the degenerate cubes,
// whose limit surface is the unit cube), and a witness: the
// polyhedral area and volume of deeply subdivided control meshes, Richardson-extrapolated.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/quadrature/rules.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

/// A bundled mesh with its basis; the BuildResult stays alive alongside.
struct Loaded {
    explicit Loaded(const std::string& name, SchemeKind scheme = SchemeKind::CatmullClark)
        : built(read_mesh(find_bundled(name).path)), basis(built.mesh.topology(), scheme) {}
    [[nodiscard]] const Points& X() const { return built.mesh.positions(); }
    BuildResult built;
    LimitBasis basis;
};

TEST(LimitSampler, StoresOneSampleperRulePointAndWeightsSumToTheDomain) {
    const Loaded cube("cube");
    const LimitSampler sampler(cube.basis, 5);
    const int per_face = square_rule(5).num_points();
    ASSERT_EQ(sampler.num_samples(), cube.basis.num_ptex_faces() * per_face);
    double total = 0.0;
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        total += sampler.weight(s);
        const auto w = sampler.limit_weights(s);
        EXPECT_NEAR(w.row(0).sum(), 1.0, 1e-12);
        const LimitWeights direct = cube.basis.evaluate(sampler.point(s));
        EXPECT_LT((sampler.evaluate(cube.X(), s) - direct.apply(cube.X())).cwiseAbs().maxCoeff(), 1e-13);
    }
    EXPECT_NEAR(total, cube.basis.num_ptex_faces(), 1e-12);
}

// Before: a degree out of range was named after an internal function ("square_rule: degree 200 ...").
TEST(LimitSampler, ADegreeOutOfRangeIsNamedAsTheQuadratureDegree) {
    const Loaded cube("cube");
    const Loaded icosahedron("icosahedron", SchemeKind::Loop);
    const auto message = [](const LimitBasis& basis, int degree) {
        try {
            const LimitSampler sampler(basis, degree);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message(cube.basis, 200), "the quadrature degree per tile must be in 1..127 on quad ptex faces, not 200");
    EXPECT_EQ(message(cube.basis, 0), "the quadrature degree per tile must be in 1..127 on quad ptex faces, not 0");
    EXPECT_EQ(message(icosahedron.basis, 61),
              "the quadrature degree per tile must be in 1..60 on triangle ptex faces, not 61");
    EXPECT_EQ(message(icosahedron.basis, 1), "no error");
}

TEST(LimitSampler, TilesCoverTheDomainAndCrowdTowardsExtraordinaryCorners) {
    for (const auto& [name, scheme, domain] :
         {std::tuple{"cube", SchemeKind::CatmullClark, 1.0}, std::tuple{"icosahedron", SchemeKind::Loop, 0.5},
          std::tuple{"dodecahedron", SchemeKind::CatmullClark, 1.0}}) {
        SCOPED_TRACE(name);
        const Loaded m(name, scheme);
        const LimitSampler plain(m.basis, 4);
        const LimitSampler tiled(m.basis, 4, 3);
        EXPECT_GT(tiled.num_samples(), plain.num_samples());
        double total = 0.0;
        for (Index s = 0; s < tiled.num_samples(); ++s) {
            total += tiled.weight(s);
        }
        EXPECT_NEAR(total, domain * m.basis.num_ptex_faces(), 1e-12);
    }
}

// A sampler over a range of ptex faces (a large mesh in pieces) holds exactly the samples of those
// faces: the pieces, one after the other, are the whole sampler, sample for sample.
TEST(LimitSampler, PiecesOfPtexFacesAreTheWholeSampler) {
    const Loaded m("dodecahedron");
    const SamplerOptions options{4, 2, 2};
    const LimitSampler whole(m.basis, options);
    const Index faces = m.basis.num_ptex_faces();
    Index s = 0;
    for (const auto& [first, last] : {std::pair<Index, Index>{0, 7}, {7, 7}, {7, 31}, {31, faces}}) {
        const LimitSampler piece(m.basis, options, first, last);
        for (Index i = 0; i < piece.num_samples(); ++i, ++s) {
            ASSERT_LT(s, whole.num_samples());
            EXPECT_EQ(piece.point(i).face, whole.point(s).face);
            EXPECT_GE(piece.point(i).face, first);
            EXPECT_LT(piece.point(i).face, last);
            EXPECT_EQ(piece.point(i).u, whole.point(s).u);
            EXPECT_EQ(piece.point(i).v, whole.point(s).v);
            EXPECT_EQ(piece.weight(i), whole.weight(s));
            EXPECT_TRUE(std::ranges::equal(piece.vertices(i), whole.vertices(s)));
            EXPECT_TRUE(piece.limit_weights(i) == whole.limit_weights(s));
        }
    }
    EXPECT_EQ(s, whole.num_samples());
    EXPECT_THROW(LimitSampler(m.basis, options, 3, 2), InputError);
    EXPECT_THROW(LimitSampler(m.basis, options, -1, 2), InputError);
    EXPECT_THROW(LimitSampler(m.basis, options, 0, faces + 1), InputError);
}

// The weights are stored in blocks of 2^16 entries, each thread filling its own: every sample's
// vertices and weights are still exactly its own evaluation's, on 1, 2 and 3 threads, over more
// entries than several blocks hold.
TEST(LimitSampler, EverySampleKeepsItsOwnWeightsAcrossBlocksAndThreads) {
    const Loaded m("dodecahedron");
    for (const int threads : {1, 2, 3}) {
        const LimitSampler sampler(m.basis, SamplerOptions{10, 6, threads});
        std::size_t entries = 0;
        LimitWeights expected;
        for (Index s = 0; s < sampler.num_samples(); ++s) {
            m.basis.evaluate(sampler.point(s), expected, DerivativeOrder::Second);
            const auto vertices = sampler.vertices(s);
            ASSERT_TRUE(std::ranges::equal(vertices, expected.vertices)) << "sample " << s << ", " << threads;
            ASSERT_TRUE(sampler.limit_weights(s) == expected.w) << "sample " << s << ", " << threads;
            entries += vertices.size();
        }
        EXPECT_GT(entries, std::size_t{4} << 16) << "the test should span several blocks per thread";
    }
}

TEST(LimitSampler, EvaluateAllMatchesEvaluateOne) {
    const Loaded torus("quad_torus");
    const LimitSampler sampler(torus.basis, SamplerOptions{6, 0, 3});
    const auto all = sampler.evaluate(torus.X());
    ASSERT_EQ(static_cast<Index>(all.size()), sampler.num_samples());
    for (Index s = 0; s < sampler.num_samples(); s += 7) {
        EXPECT_EQ(all[static_cast<std::size_t>(s)], sampler.evaluate(torus.X(), s));
    }
}

/// Central differences of f with respect to every control coordinate.
template <class F>
Points finite_difference(const Points& X, F f, double h = 1e-6) {
    Points g(X.rows(), 3);
    for (Index k = 0; k < X.rows(); ++k) {
        for (int c = 0; c < 3; ++c) {
            Points plus = X;
            Points minus = X;
            plus(k, c) += h;
            minus(k, c) -= h;
            g(k, c) = (f(plus) - f(minus)) / (2 * h);
        }
    }
    return g;
}

TEST(Integrals, AreaAndVolumeGradientsMatchFiniteDifferences) {
    for (const auto& [name, scheme] :
         {std::pair{"cube", SchemeKind::CatmullClark}, std::pair{"cube_ngons", SchemeKind::CatmullClark},
          std::pair{"octahedron", SchemeKind::Loop}}) {
        SCOPED_TRACE(name);
        const Loaded m(name, scheme);
        const LimitSampler sampler(m.basis, 6, 2);
        Points X = m.X();
        X.col(0) += 0.1 * X.col(1).cwiseProduct(X.col(1));  // break symmetry
        const Points ga = area_gradient(sampler, X);
        const Points fa = finite_difference(X, [&](const Points& Y) { return area(sampler, Y); });
        EXPECT_LT((ga - fa).cwiseAbs().maxCoeff(), 1e-7 * ga.cwiseAbs().maxCoeff());
        const Points gv = volume_gradient(sampler, X);
        const Points fv = finite_difference(X, [&](const Points& Y) { return enclosed_volume(sampler, Y); });
        EXPECT_LT((gv - fv).cwiseAbs().maxCoeff(), 1e-7 * gv.cwiseAbs().maxCoeff());
        // Translating every control point moves only positions: the discrete area is exactly translation
        // invariant (derivative weights sum to 0), so its gradient sums to 0. (Σ_k ∂V/∂X_k = 1/3 Σ w a is
        // ∫ n dA / 3 = 0 only up to the quadrature error, so it is not tested here.)
        EXPECT_LT(ga.colwise().sum().norm(), 1e-10);
    }
}

TEST(Integrals, RigidMotionsKeepAndScalingMultipliesAreaAndVolume) {
    const Loaded m("genus2");
    const LimitSampler sampler(m.basis, 6, 1);
    const Points& X = m.X();
    const double a = area(sampler, X);
    const double v = enclosed_volume(sampler, X);
    EXPECT_GT(v, 0.0);  // faces counter-clockwise seen from outside
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::RowVector3d t(3.0, -1.5, 0.25);
    const Points moved = (X * R.transpose()).rowwise() + t;
    EXPECT_NEAR(area(sampler, moved), a, 1e-12 * a);
    EXPECT_NEAR(enclosed_volume(sampler, moved), v, 1e-12 * v);
    const Points translated = X.rowwise() + t;
    EXPECT_NEAR(enclosed_volume(sampler, translated), v, 1e-12 * v);
    EXPECT_LT((centroid(sampler, translated) - centroid(sampler, X) - t.transpose()).norm(), 1e-12);
    EXPECT_LT((surface_centroid(sampler, translated) - surface_centroid(sampler, X) - t.transpose()).norm(), 1e-12);
    const double s = 1.7;
    EXPECT_NEAR(area(sampler, s * X), s * s * a, 1e-12 * a);
    EXPECT_NEAR(enclosed_volume(sampler, s * X), s * s * s * v, 1e-12 * v);
    // Reversing the orientation (a reflection) flips the sign of the volume.
    Points mirrored = X;
    mirrored.col(2) *= -1.0;
    EXPECT_NEAR(enclosed_volume(sampler, mirrored), -v, 1e-12 * v);
}

TEST(Integrals, SymmetricSurfacesHaveTheirCentroidOnTheSymmetryCentre) {
    const Loaded m("cube");
    const LimitSampler sampler(m.basis, 6, 2);
    const Points X = m.X().rowwise() + Eigen::RowVector3d(1.0, 2.0, 3.0);
    EXPECT_LT((centroid(sampler, X) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
    EXPECT_LT((surface_centroid(sampler, X) - Eigen::Vector3d(1, 2, 3)).norm(), 1e-12);
}

/// Area enclosed by the limit boundary of a planar grid (EdgeAndCorner): each side between two
/// corners is the uniform cubic B-spline of (2 P0 - P1, P0, ..., Pm, 2 Pm - Pm-1), the curve
/// the boundary rules (1/8, 6/8, 1/8), (1/2, 1/2) with fixed corners refine to. Green's theorem
/// per span, Gauss–Legendre exact for the degree-5 integrand.
double boundary_spline_area(const Topology& t, const Points& X) {
    std::map<Index, Index> next;  // boundary edges in the direction of their face (counter-clockwise)
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto fv = t.face_vertices(f);
        for (std::size_t i = 0; i < fv.size(); ++i) {
            const Index a = fv[i];
            const Index b = fv[(i + 1) % fv.size()];
            if (t.is_boundary_edge(t.find_edge(a, b))) {
                next[a] = b;
            }
        }
    }
    Index start = next.begin()->first;
    while (t.valence(start) != 2) {
        start = next.at(start);
    }
    const QuadratureRule gauss = gauss_legendre_1d(4);
    double twice_area = 0.0;
    Index corner = start;
    do {
        std::vector<Eigen::Vector2d> P{X.row(corner).head<2>().transpose()};
        Index v = corner;
        do {
            v = next.at(v);
            P.emplace_back(X.row(v).head<2>().transpose());
        } while (t.valence(v) != 2);
        std::vector<Eigen::Vector2d> Q{2 * P[0] - P[1]};
        Q.insert(Q.end(), P.begin(), P.end());
        Q.push_back(2 * P.back() - P[P.size() - 2]);
        for (std::size_t i = 0; i + 3 < Q.size(); ++i) {
            for (int q = 0; q < gauss.num_points(); ++q) {
                const double s = gauss.u[static_cast<std::size_t>(q)];
                const double r = 1 - s;
                const Eigen::Vector2d x = (r * r * r * Q[i] + (3 * s * s * s - 6 * s * s + 4) * Q[i + 1] +
                                           (-3 * s * s * s + 3 * s * s + 3 * s + 1) * Q[i + 2] + s * s * s * Q[i + 3]) /
                                          6.0;
                const Eigen::Vector2d dx = (-3 * r * r * Q[i] + (9 * s * s - 12 * s) * Q[i + 1] +
                                            (-9 * s * s + 6 * s + 3) * Q[i + 2] + 3 * s * s * Q[i + 3]) /
                                           6.0;
                twice_area += gauss.weight[static_cast<std::size_t>(q)] * (x.x() * dx.y() - x.y() * dx.x());
            }
        }
        corner = v;
    } while (corner != start);
    return twice_area / 2.0;
}

/// The paper's degenerate cube (volume-trilinear-forms): [0,1]³ refined bilinearly @p times, each
/// vertex moved onto the nearest corner. Its Doo–Sabin (times = 2) and Catmull–Clark (times = 3)
/// limit surfaces are the unit cube itself.
std::pair<Topology, Points> degenerate_cube(int times) {
    Points X(8, 3);
    for (int v = 0; v < 8; ++v) {
        X.row(v) << (v & 1), ((v >> 1) & 1), ((v >> 2) & 1);
    }
    Topology t = Topology::from_polygons(
        8, {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}});
    for (int i = 0; i < times; ++i) {
        Level level = refine_bilinear(t);
        X = level.S0 * X;
        t = std::move(level.topology);
    }
    X = (X.array() > 0.5).cast<double>();
    return {t, X};
}

TEST(Integrals, InertiaOfTheDegenerateCubesIsTheUnitCubes) {
    // The unit cube: volume 1, centroid (½, ½, ½), inertia about it diag(1/6, 1/6, 1/6). The limit
    // surface is flat and polynomial on every tile away from the 8 collapsed corners, so quadrature
    // is exact there; measured errors 1e-15 (Doo–Sabin) and 1e-14 (Catmull–Clark).
    for (const auto& [scheme, times] : {std::pair{SchemeKind::DooSabin, 2}, std::pair{SchemeKind::CatmullClark, 3}}) {
        const auto [t, X] = degenerate_cube(times);
        const LimitBasis basis(t, scheme);
        const SurfaceMeasures m = measure(LimitSampler(basis, 8, 4), X, true);
        EXPECT_NEAR(m.volume, 1.0, 1e-12) << to_string(scheme);
        EXPECT_LT((m.centroid - Eigen::Vector3d::Constant(0.5)).norm(), 1e-12) << to_string(scheme);
        EXPECT_LT((m.inertia - Eigen::Matrix3d::Identity() / 6.0).norm(), 1e-12) << to_string(scheme);
    }
}

TEST(Integrals, InertiaFollowsRigidMotionsAndScaling) {
    // I(X + b) = I(X) and I(sX) = s⁵ I(X) hold for the quadrature sums themselves (they are taken about
    // the mean control point); I(QX) = Q I(X) Qᵀ holds for the integral, so for the sums only up to the
    // quadrature error (the second-moment integrands are not rotation covariant one by one).
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const Eigen::RowVector3d b(5, -3, 2);
    for (const auto& [name, scheme] :
         {std::pair{"genus2", SchemeKind::CatmullClark}, std::pair{"icosahedron", SchemeKind::Loop}}) {
        const Loaded m(name, scheme);
        const SamplerOptions options{8, 4, 0};
        const LimitSampler sampler(m.basis, options);
        const Eigen::Matrix3d I = inertia(sampler, m.X());
        EXPECT_LT((I - I.transpose()).norm(), 1e-14 * I.norm()) << name;
        EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues().minCoeff(), 0.0) << name;
        const Points shifted = m.X().rowwise() + b;
        EXPECT_LT((inertia(sampler, shifted) - I).norm(), 1e-12 * I.norm()) << name;
        EXPECT_LT((inertia(sampler, 2.0 * m.X()) - 32.0 * I).norm(), 1e-12 * 32.0 * I.norm()) << name;
        const double estimate = measure_with_error(m.basis, m.X(), options).error.inertia;
        const Points rotated = m.X() * Q.transpose();
        EXPECT_LT((inertia(sampler, rotated) - Q * I * Q.transpose()).norm(), 3 * estimate + 1e-13 * I.norm())
            << name << " estimate " << estimate;
    }
}

TEST(Integrals, MeasureWithErrorEqualsMeasureThroughSamplersBitForBit) {
    // measure_with_error keeps no weights (each sample's computed, applied and dropped); it must give
    // what two LimitSamplers with the same options give, to the last bit: the same samples, weights and
    // order of summation. Seen failing with the weights of first derivatives only (other rounding).
    for (const auto& [name, scheme] :
         {std::pair{"genus2", SchemeKind::CatmullClark}, std::pair{"icosahedron", SchemeKind::Loop},
          std::pair{"cube_creases", SchemeKind::CatmullClark}, std::pair{"annulus", SchemeKind::CatmullClark},
          std::pair{"cube", SchemeKind::DooSabin}, std::pair{"tetra_2", SchemeKind::C2g0}}) {
        const Loaded m(name, scheme);
        for (const int threads : {1, 3}) {
            const SamplerOptions options{7, 3, threads};
            const MeasureReport report = measure_with_error(m.basis, m.X(), options);
            const LimitSampler coarse(m.basis, options), fine(m.basis, report.finer);
            const QuadratureSamples samples = quadrature_samples(m.basis, options, 0, m.basis.num_ptex_faces());
            ASSERT_EQ(static_cast<Index>(samples.points.size()), coarse.num_samples()) << name;
            for (Index s = 0; s < coarse.num_samples(); ++s) {
                const auto i = static_cast<std::size_t>(s);
                ASSERT_EQ(samples.weights[i], coarse.weight(s)) << name;
                ASSERT_EQ(samples.points[i].face, coarse.point(s).face) << name;
                ASSERT_EQ(samples.points[i].u, coarse.point(s).u) << name;
                ASSERT_EQ(samples.points[i].v, coarse.point(s).v) << name;
            }
            const SurfaceMeasures value = measure(coarse, m.X(), report.closed);
            const SurfaceMeasures better = measure(fine, m.X(), report.closed);
            EXPECT_EQ(report.value.area, value.area) << name;
            EXPECT_EQ(report.value.volume, value.volume) << name;
            EXPECT_EQ(report.value.centroid, value.centroid) << name;
            EXPECT_EQ(report.value.surface_centroid, value.surface_centroid) << name;
            EXPECT_EQ(report.value.inertia, value.inertia) << name;
            EXPECT_EQ(report.error.area, std::abs(value.area - better.area)) << name;
            EXPECT_EQ(report.error.volume, std::abs(value.volume - better.volume)) << name;
        }
    }
}

TEST(Integrals, PlanarGridAreaEqualsTheAreaInsideItsBSplineBoundary) {
    const Loaded grid("quad_grid");
    Points X = grid.X();
    // Move every vertex in the plane (smoothly, keeping the map one-to-one) so that the
    // boundary is a genuine B-spline curve rather than the straight sides of the square.
    for (Index v = 0; v < X.rows(); ++v) {
        const double x = X(v, 0);
        const double y = X(v, 1);
        X(v, 0) = x + 0.08 * std::sin(2.0 * y + 0.3) + 0.05 * x * y;
        X(v, 1) = y + 0.06 * std::cos(1.5 * x) - 0.04 * x * x;
    }
    const double expected = boundary_spline_area(grid.basis.topology(), X);
    EXPECT_NEAR(area(LimitSampler(grid.basis, 5), X), expected, 1e-13 * expected);
    EXPECT_NEAR(area(LimitSampler(grid.basis, 5, 2), X), expected, 1e-13 * expected);
    EXPECT_NEAR(
        area(grid.basis.topology().num_vertices() > 0 ? LimitSampler(grid.basis, 5) : LimitSampler(grid.basis, 5),
             grid.X()),
        4.0, 1e-13);  // straight sides: the square [-1, 1]² itself
}

/// Polyhedral area and volume of a level of control mesh (faces fanned about their centroid).
std::pair<double, double> polyhedral_measures(const Topology& t, const Points& X) {
    double a = 0.0;
    double v = 0.0;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto fv = t.face_vertices(f);
        Eigen::Vector3d c = Eigen::Vector3d::Zero();
        for (const Index i : fv) {
            c += X.row(i).transpose();
        }
        c /= static_cast<double>(fv.size());
        for (std::size_t i = 0; i < fv.size(); ++i) {
            const Eigen::Vector3d p = X.row(fv[i]).transpose();
            const Eigen::Vector3d q = X.row(fv[(i + 1) % fv.size()]).transpose();
            const Eigen::Vector3d n = (p - c).cross(q - c);
            a += 0.5 * n.norm();
            v += c.dot(p.cross(q)) / 6.0;
        }
    }
    return {a, v};
}

struct Witness {
    std::string mesh;
    SchemeKind scheme;
    double tolerance;  ///< relative agreement that holds (see the test's comment)
};

class IntegralsWitness : public ::testing::TestWithParam<Witness> {};

/// Richardson tableau for errors c1 4^-L + c2 16^-L ...: returns the most extrapolated value and
/// the difference between the last two estimates of the highest order.
std::pair<double, double> richardson(const std::vector<double>& values) {
    std::vector<double> row = values;
    double factor = 4.0;
    double last_change = 0.0;
    while (row.size() > 1) {
        std::vector<double> next;
        for (std::size_t i = 0; i + 1 < row.size(); ++i) {
            next.push_back((factor * row[i + 1] - row[i]) / (factor - 1));
        }
        last_change = row.size() >= 2 ? std::abs(row.back() - row[row.size() - 2]) : 0.0;
        row = next;
        factor *= 2.0;  // then 8^-L (from the (C1) geometry next to extraordinary vertices), 16^-L, ...
    }
    return {row.back(), last_change};
}

TEST_P(IntegralsWitness, AgreesWithExtrapolatedPolyhedralMeasuresOfDeepSubdivision) {
    const Loaded m(GetParam().mesh, GetParam().scheme);
    RefineOptions refine;
    refine.scheme = GetParam().scheme;
    refine.levels = 6;
    const Hierarchy hierarchy(m.built.mesh.topology(), refine);
    std::vector<double> areas;
    std::vector<double> volumes;
    for (int level = 2; level <= refine.levels; ++level) {
        const auto [a, v] = polyhedral_measures(hierarchy.topology(level), hierarchy.positions(level, m.X()));
        areas.push_back(a);
        volumes.push_back(v);
    }
    const auto [area_limit, area_change] = richardson(areas);
    const auto [volume_limit, volume_change] = richardson(volumes);
    const LimitSampler sampler(m.basis, SamplerOptions{14, 10, 0});
    const double a = area(sampler, m.X());
    const double v = enclosed_volume(sampler, m.X());
    const double tolerance = GetParam().tolerance;
    std::printf("%s: relative differences to the extrapolated polyhedral values: area %.2g, volume %.2g "
                "(extrapolation's last change %.2g, %.2g)\n",
                GetParam().mesh.c_str(), std::abs(a - area_limit) / area_limit,
                std::abs(v - volume_limit) / volume_limit, area_change / area_limit, volume_change / volume_limit);
    EXPECT_NEAR(a, area_limit, tolerance * area_limit);
    EXPECT_NEAR(v, volume_limit, tolerance * volume_limit);
}

// Levels 2..6, Richardson with 4^-L, 8^-L, 16^-L, ... The polyhedral values converge like 4^-L
// (h²) and the tableau removes that; what is left is limited by the levels a test can afford.
// Observed relative agreement of the quadrature (degree 14, 10 tile levels) with the
// extrapolation: quad_torus 3e-12 (area) / 1.6e-11 (volume), tri_torus 1.5e-11 / 1.6e-11, so the
// issue's 1e-9 (here 1e-10) holds on regular meshes. Next to extraordinary vertices the
// correction terms decay like powers of the subdominant eigenvalues rather than of 1/2, the
// tableau's orders are only approximate (its last change is 1e-8..1e-7), and the agreement is
// cube 1.4e-9 / 1.5e-9, icosahedron (Loop) 6.6e-10 / 2.5e-10: 5e-9 is what honestly holds there,
// limited by the extrapolation, not by the quadrature. C2g0 (refine_c2g0 against its own limit
// basis): the 4×5 torus is too coarse for levels 2..6 to be asymptotic (the tableau's last change
// 7e-8 / 1.6e-7; agreement 1.0e-9 / 2.7e-9); F_tetra,2, whose valence-3 corrections decay with
// powers of ¼ and 1/16, agrees to 1.3e-8 / 1.1e-8 with a last change of 1e-8.
INSTANTIATE_TEST_SUITE_P(Meshes, IntegralsWitness,
                         ::testing::Values(Witness{"quad_torus", SchemeKind::CatmullClark, 1e-10},
                                           Witness{"cube", SchemeKind::CatmullClark, 5e-9},
                                           Witness{"icosahedron", SchemeKind::Loop, 5e-9},
                                           Witness{"tri_torus", SchemeKind::Loop, 1e-10},
                                           Witness{"torus_4x5", SchemeKind::C2g0, 5e-9},
                                           Witness{"tetra_2", SchemeKind::C2g0, 3e-8}),
                         [](const auto& param_info) { return param_info.param.mesh; });

// C2g0 on the subdivided tetrahedra F_tetra,j with vertices on the unit sphere (the paper's
// spheres, Fig. 7): the limit surface is a smoothed sphere whose area and volume approach 4π and
// 4π/3 like h² (an approximating scheme shrinks by O(h²) next to a surface of bounded curvature),
// so each level divides the errors by about 4.
TEST(Integrals, C2g0TetrahedraApproachTheSphereQuadratically) {
    std::vector<double> area_errors;
    std::vector<double> volume_errors;
    for (const char* name : {"tetra_1", "tetra_2", "tetra_3", "tetra_4"}) {
        const Loaded m(name, SchemeKind::C2g0);
        const LimitSampler sampler(m.basis, SamplerOptions{10, 8, 0});
        area_errors.push_back(4.0 * std::numbers::pi - area(sampler, m.X()));
        volume_errors.push_back(4.0 * std::numbers::pi / 3.0 - enclosed_volume(sampler, m.X()));
        std::printf("%s: area %.12f (4π − area %.3g), volume %.12f (4π/3 − volume %.3g)\n", name,
                    4.0 * std::numbers::pi - area_errors.back(), area_errors.back(),
                    4.0 * std::numbers::pi / 3.0 - volume_errors.back(), volume_errors.back());
    }
    for (std::size_t j = 0; j < area_errors.size(); ++j) {
        EXPECT_GT(area_errors[j], 0.0);  // inside the sphere: the scheme is a convex combination
        EXPECT_GT(volume_errors[j], 0.0);
    }
    // The ratios tend to 4 from below (pre-asymptotic at j = 1, 2).
    const double area_ratio = area_errors[2] / area_errors[3];
    const double volume_ratio = volume_errors[2] / volume_errors[3];
    EXPECT_GT(area_ratio, 3.3);
    EXPECT_LT(area_ratio, 4.2);
    EXPECT_GT(volume_ratio, 3.3);
    EXPECT_LT(volume_ratio, 4.2);
}

}  // namespace
}  // namespace limsurf::test
