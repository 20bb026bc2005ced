// surface_frame: fundamental forms, curvatures and principal directions on surfaces
// whose geometry is known in closed form (spheres in several parameterisations,
// cylinder, saddle, plane), invariance under rigid motions, scaling and
// reparameterisation, the orientation flip, and the refusals.
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/limit/surface_frame.h"

namespace limsurf {
namespace {

using Derivatives = Eigen::Matrix<double, 6, 3>;

Derivatives make_derivatives(const Eigen::Vector3d& x, const Eigen::Vector3d& xu, const Eigen::Vector3d& xv,
                             const Eigen::Vector3d& xuu, const Eigen::Vector3d& xuv, const Eigen::Vector3d& xvv) {
    Derivatives d;
    d << x.transpose(), xu.transpose(), xv.transpose(), xuu.transpose(), xuv.transpose(), xvv.transpose();
    return d;
}

// Sphere of radius R about c, u the polar angle, v the azimuth: outward ∂u × ∂v.
Derivatives sphere_polar(double radius, const Eigen::Vector3d& c, double u, double v) {
    const double su = std::sin(u);
    const double cu = std::cos(u);
    const double sv = std::sin(v);
    const double cv = std::cos(v);
    return make_derivatives(
        c + radius * Eigen::Vector3d(su * cv, su * sv, cu), radius * Eigen::Vector3d(cu * cv, cu * sv, -su),
        radius * Eigen::Vector3d(-su * sv, su * cv, 0.0), -radius * Eigen::Vector3d(su * cv, su * sv, cu),
        radius * Eigen::Vector3d(-cu * sv, cu * cv, 0.0), -radius * Eigen::Vector3d(su * cv, su * sv, 0.0));
}

// Upper hemisphere as the graph z = sqrt(R² - u² - v²) (upward = outward).
Derivatives sphere_graph(double radius, const Eigen::Vector3d& c, double u, double v) {
    const double z = std::sqrt(radius * radius - u * u - v * v);
    const double z3 = z * z * z;
    return make_derivatives(c + Eigen::Vector3d(u, v, z), Eigen::Vector3d(1.0, 0.0, -u / z),
                            Eigen::Vector3d(0.0, 1.0, -v / z), Eigen::Vector3d(0.0, 0.0, -(z * z + u * u) / z3),
                            Eigen::Vector3d(0.0, 0.0, -u * v / z3), Eigen::Vector3d(0.0, 0.0, -(z * z + v * v) / z3));
}

// Cylinder of radius R about the z axis: (R cos u, R sin u, v), outward.
Derivatives cylinder(double radius, double u, double v) {
    const double su = std::sin(u);
    const double cu = std::cos(u);
    return make_derivatives(Eigen::Vector3d(radius * cu, radius * su, v),
                            Eigen::Vector3d(-radius * su, radius * cu, 0.0), Eigen::Vector3d(0.0, 0.0, 1.0),
                            Eigen::Vector3d(-radius * cu, -radius * su, 0.0), Eigen::Vector3d::Zero(),
                            Eigen::Vector3d::Zero());
}

// The saddle z = xy as a graph.
Derivatives saddle(double u, double v) {
    return make_derivatives(Eigen::Vector3d(u, v, u * v), Eigen::Vector3d(1.0, 0.0, v), Eigen::Vector3d(0.0, 1.0, u),
                            Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 1.0), Eigen::Vector3d::Zero());
}

// The same surface in parameters (a, b) with (u, v) = J (a, b) + const.
Derivatives reparameterise(const Derivatives& d, const Eigen::Matrix2d& jacobian) {
    Derivatives r;
    r.row(0) = d.row(0);
    r.row(1) = jacobian(0, 0) * d.row(1) + jacobian(1, 0) * d.row(2);
    r.row(2) = jacobian(0, 1) * d.row(1) + jacobian(1, 1) * d.row(2);
    r.row(3) = jacobian(0, 0) * jacobian(0, 0) * d.row(3) + 2.0 * jacobian(0, 0) * jacobian(1, 0) * d.row(4) +
               jacobian(1, 0) * jacobian(1, 0) * d.row(5);
    r.row(4) = jacobian(0, 0) * jacobian(0, 1) * d.row(3) +
               (jacobian(0, 0) * jacobian(1, 1) + jacobian(1, 0) * jacobian(0, 1)) * d.row(4) +
               jacobian(1, 0) * jacobian(1, 1) * d.row(5);
    r.row(5) = jacobian(0, 1) * jacobian(0, 1) * d.row(3) + 2.0 * jacobian(0, 1) * jacobian(1, 1) * d.row(4) +
               jacobian(1, 1) * jacobian(1, 1) * d.row(5);
    return r;
}

Derivatives swap_uv(const Derivatives& d) {
    Eigen::Matrix2d J;
    J << 0.0, 1.0, 1.0, 0.0;
    return reparameterise(d, J);
}

// A generic surface point: random derivatives with well separated tangents.
Derivatives random_derivatives(std::mt19937& random) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Derivatives d;
    for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 3; ++c) {
            d(r, c) = unit(random);
        }
    }
    d.row(1) += Eigen::RowVector3d(2.0, 0.0, 0.0);
    d.row(2) += Eigen::RowVector3d(0.0, 2.0, 0.0);
    return d;
}

// d1, d2 unit, tangent, orthogonal, d1 × d2 = n.
void expect_orthonormal_frame(const SurfaceFrame& f) {
    EXPECT_NEAR(f.normal.norm(), 1.0, 1e-14);
    EXPECT_NEAR(f.d1.norm(), 1.0, 1e-14);
    EXPECT_NEAR(f.d2.norm(), 1.0, 1e-14);
    EXPECT_NEAR(f.d1.dot(f.normal), 0.0, 1e-14);
    EXPECT_NEAR(f.d2.dot(f.normal), 0.0, 1e-14);
    EXPECT_NEAR(f.d1.dot(f.d2), 0.0, 1e-14);
    EXPECT_LT((f.d1.cross(f.d2) - f.normal).norm(), 1e-14);
    EXPECT_GE(f.k1, f.k2);
}

// Parallel or antiparallel unit vectors (principal directions have no sign).
void expect_same_direction(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tolerance) {
    EXPECT_NEAR(std::abs(a.dot(b)), 1.0, tolerance) << a.transpose() << " vs " << b.transpose();
}

// The classical formulas, and each principal direction x (in (u, v)) solving -II x = k I x.
void expect_consistent(const SurfaceFrame& f, const Derivatives& d) {
    const double det = f.E * f.G - f.F * f.F;
    const double scale = 1.0 + std::abs(f.k1) + std::abs(f.k2);
    EXPECT_NEAR(f.gaussian_curvature, (f.L * f.N - f.M * f.M) / det, 1e-12 * scale * scale);
    EXPECT_NEAR(f.mean_curvature, -(f.E * f.N - 2.0 * f.F * f.M + f.G * f.L) / (2.0 * det), 1e-12 * scale);
    Eigen::Matrix<double, 3, 2> jacobian;
    jacobian << d.row(1).transpose(), d.row(2).transpose();
    Eigen::Matrix2d I;
    I << f.E, f.F, f.F, f.G;
    Eigen::Matrix2d II;
    II << f.L, f.M, f.M, f.N;
    for (const auto& [k, direction] : {std::pair{f.k1, f.d1}, std::pair{f.k2, f.d2}}) {
        const Eigen::Vector2d x = jacobian.colPivHouseholderQr().solve(direction);
        EXPECT_LT((jacobian * x - direction).norm(), 1e-12);  // tangent
        EXPECT_LT((-II * x - k * I * x).norm(), 1e-11 * scale * x.norm());
    }
}

TEST(SurfaceFrame, SpheresHaveCurvatureOneOverRadius) {
    const Eigen::Vector3d centre(0.3, -1.2, 2.0);
    for (const double R : {1.0, 0.25, 7.0}) {
        for (const auto& [u, v] : {std::pair{0.4, 0.1}, std::pair{1.3, 2.9}, std::pair{2.7, -1.0}}) {
            SCOPED_TRACE(testing::Message() << "polar R = " << R << " at " << u << ", " << v);
            const Derivatives d = sphere_polar(R, centre, u, v);
            const SurfaceFrame f = surface_frame(d);
            const Eigen::Vector3d outward = (d.row(0).transpose() - centre) / R;
            EXPECT_LT((f.normal - outward).norm(), 1e-14);
            EXPECT_NEAR(f.E, R * R, 1e-13 * R * R);
            EXPECT_NEAR(f.F, 0.0, 1e-13 * R * R);
            EXPECT_NEAR(f.G, R * R * std::sin(u) * std::sin(u), 1e-13 * R * R);
            EXPECT_NEAR(f.L, -R, 1e-13 * R);
            EXPECT_NEAR(f.M, 0.0, 1e-13 * R);
            EXPECT_NEAR(f.N, -R * std::sin(u) * std::sin(u), 1e-13 * R);
            EXPECT_NEAR(f.k1, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.k2, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.mean_curvature, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.gaussian_curvature, 1.0 / (R * R), 1e-13 / (R * R));
            expect_orthonormal_frame(f);
            expect_consistent(f, d);
        }
        for (const auto& [u, v] : {std::pair{0.0, 0.0}, std::pair{0.3, -0.2}, std::pair{-0.5, 0.6}}) {
            SCOPED_TRACE(testing::Message() << "graph R = " << R << " at " << u * R << ", " << v * R);
            const Derivatives d = sphere_graph(R, centre, u * R, v * R);
            const SurfaceFrame f = surface_frame(d);
            EXPECT_LT((f.normal - (d.row(0).transpose() - centre) / R).norm(), 1e-14);
            EXPECT_NEAR(f.k1, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.k2, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.mean_curvature, 1.0 / R, 1e-13 / R);
            EXPECT_NEAR(f.gaussian_curvature, 1.0 / (R * R), 1e-13 / (R * R));
            expect_orthonormal_frame(f);
            expect_consistent(f, d);
        }
    }
}

TEST(SurfaceFrame, CylinderHasOnePrincipalCurvature) {
    const double R = 2.5;
    for (const double u : {0.0, 0.7, 2.0, -2.4}) {
        SCOPED_TRACE(testing::Message() << "u = " << u);
        // also in skewed parameters, where the principal directions are no parameter lines
        Eigen::Matrix2d J;
        J << 1.0, 0.3, -0.4, 2.0;
        for (const Derivatives& d : {cylinder(R, u, 0.5), reparameterise(cylinder(R, u, 0.5), J)}) {
            const SurfaceFrame f = surface_frame(d);
            EXPECT_LT((f.normal - Eigen::Vector3d(std::cos(u), std::sin(u), 0.0)).norm(), 1e-14);
            EXPECT_NEAR(f.k1, 1.0 / R, 1e-14);
            EXPECT_NEAR(f.k2, 0.0, 1e-14);
            EXPECT_NEAR(f.mean_curvature, 0.5 / R, 1e-14);
            EXPECT_NEAR(f.gaussian_curvature, 0.0, 1e-14);
            expect_same_direction(f.d1, Eigen::Vector3d(-std::sin(u), std::cos(u), 0.0), 1e-14);
            expect_same_direction(f.d2, Eigen::Vector3d(0.0, 0.0, 1.0), 1e-14);
            expect_orthonormal_frame(f);
            expect_consistent(f, d);
        }
    }
}

TEST(SurfaceFrame, SaddleHasNegativeGaussianCurvature) {
    const SurfaceFrame f = surface_frame(saddle(0.0, 0.0));
    EXPECT_LT((f.normal - Eigen::Vector3d(0.0, 0.0, 1.0)).norm(), 1e-15);
    EXPECT_EQ(f.L, 0.0);
    EXPECT_EQ(f.M, 1.0);
    EXPECT_EQ(f.N, 0.0);
    EXPECT_NEAR(f.gaussian_curvature, -1.0, 1e-15);
    EXPECT_NEAR(f.mean_curvature, 0.0, 1e-15);
    EXPECT_NEAR(f.k1, 1.0, 1e-15);
    EXPECT_NEAR(f.k2, -1.0, 1e-15);
    // z = xy falls along x = -y (away from the upward normal): that is k1 = +1
    expect_same_direction(f.d1, Eigen::Vector3d(1.0, -1.0, 0.0).normalized(), 1e-15);
    expect_same_direction(f.d2, Eigen::Vector3d(1.0, 1.0, 0.0).normalized(), 1e-15);
    expect_orthonormal_frame(f);

    // Away from the origin: K = -1/(1+x²+y²)², H = xy/(1+x²+y²)^(3/2) (graph formulas,
    // with our sign: positive where the surface bends away from the upward normal).
    for (const auto& [x, y] : {std::pair{0.5, 0.3}, std::pair{-1.2, 0.7}, std::pair{2.0, 2.0}}) {
        const Derivatives d = saddle(x, y);
        const SurfaceFrame g = surface_frame(d);
        const double w = 1.0 + x * x + y * y;
        EXPECT_NEAR(g.gaussian_curvature, -1.0 / (w * w), 1e-15);
        EXPECT_NEAR(g.mean_curvature, x * y / std::pow(w, 1.5), 1e-15);
        expect_orthonormal_frame(g);
        expect_consistent(g, d);
    }
}

TEST(SurfaceFrame, PlaneIsFlat) {
    const Eigen::Vector3d a(1.0, 2.0, -0.5);
    const Eigen::Vector3d b(-0.3, 0.4, 1.5);
    const Derivatives d = make_derivatives(Eigen::Vector3d(1.0, 1.0, 1.0), a, b, Eigen::Vector3d::Zero(),
                                           Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    const SurfaceFrame f = surface_frame(d);
    EXPECT_LT((f.normal - a.cross(b).normalized()).norm(), 1e-15);
    EXPECT_EQ(f.k1, 0.0);
    EXPECT_EQ(f.k2, 0.0);
    EXPECT_EQ(f.gaussian_curvature, 0.0);
    EXPECT_EQ(f.mean_curvature, 0.0);
    EXPECT_DOUBLE_EQ(f.E, a.dot(a));
    EXPECT_DOUBLE_EQ(f.F, a.dot(b));
    EXPECT_DOUBLE_EQ(f.G, b.dot(b));
    expect_orthonormal_frame(f);
}

TEST(SurfaceFrame, InvariantUnderRigidMotionScalingAndReparameterisation) {
    std::mt19937 random(7);
    for (int trial = 0; trial < 20; ++trial) {
        SCOPED_TRACE(testing::Message() << "trial " << trial);
        const Derivatives d = random_derivatives(random);
        const SurfaceFrame f = surface_frame(d);
        expect_orthonormal_frame(f);
        expect_consistent(f, d);

        std::normal_distribution<double> normal;
        const Eigen::Matrix3d Q = Eigen::Quaterniond(normal(random), normal(random), normal(random), normal(random))
                                      .normalized()
                                      .toRotationMatrix();
        const double lambda = 0.1 + 3.0 * std::uniform_real_distribution<double>(0.0, 1.0)(random);
        Derivatives moved = lambda * d * Q.transpose();
        moved.row(0) += Eigen::RowVector3d(5.0, -2.0, 1.0);
        const SurfaceFrame g = surface_frame(moved);
        EXPECT_LT((g.normal - Q * f.normal).norm(), 1e-13);
        EXPECT_NEAR(g.k1, f.k1 / lambda, 1e-12 * (1.0 + std::abs(f.k1 / lambda)));
        EXPECT_NEAR(g.k2, f.k2 / lambda, 1e-12 * (1.0 + std::abs(f.k2 / lambda)));
        EXPECT_NEAR(g.L, lambda * f.L, 1e-12 * lambda * (1.0 + std::abs(f.L)));
        EXPECT_NEAR(g.E, lambda * lambda * f.E, 1e-12 * lambda * lambda * f.E);
        if (f.k1 - f.k2 > 1e-3 * (std::abs(f.k1) + std::abs(f.k2))) {
            expect_same_direction(g.d1, Q * f.d1, 1e-10);
            expect_same_direction(g.d2, Q * f.d2, 1e-10);
        }

        // an orientation-preserving change of parameters changes nothing geometric
        Eigen::Matrix2d J;
        J << 1.3, 0.4, -0.2, 0.7;
        const SurfaceFrame h = surface_frame(reparameterise(d, J));
        EXPECT_LT((h.normal - f.normal).norm(), 1e-13);
        EXPECT_NEAR(h.k1, f.k1, 1e-12 * (1.0 + std::abs(f.k1)));
        EXPECT_NEAR(h.k2, f.k2, 1e-12 * (1.0 + std::abs(f.k2)));
        if (f.k1 - f.k2 > 1e-3 * (std::abs(f.k1) + std::abs(f.k2))) {
            expect_same_direction(h.d1, f.d1, 1e-10);
        }
    }
}

TEST(SurfaceFrame, SwappingTheParametersFlipsTheOrientation) {
    std::mt19937 random(11);
    std::vector<Derivatives> cases = {sphere_polar(2.0, Eigen::Vector3d::Zero(), 1.0, 0.5), cylinder(1.5, 0.3, 0.0),
                                      saddle(0.4, -0.3)};
    for (int trial = 0; trial < 10; ++trial) {
        cases.push_back(random_derivatives(random));
    }
    for (const Derivatives& d : cases) {
        const SurfaceFrame f = surface_frame(d);
        const SurfaceFrame g = surface_frame(swap_uv(d));
        EXPECT_LT((g.normal + f.normal).norm(), 1e-14);
        EXPECT_NEAR(g.mean_curvature, -f.mean_curvature, 1e-12 * (1.0 + std::abs(f.mean_curvature)));
        EXPECT_NEAR(g.gaussian_curvature, f.gaussian_curvature, 1e-12 * (1.0 + std::abs(f.gaussian_curvature)));
        EXPECT_NEAR(g.k1, -f.k2, 1e-12 * (1.0 + std::abs(f.k2)));
        EXPECT_NEAR(g.k2, -f.k1, 1e-12 * (1.0 + std::abs(f.k1)));
        EXPECT_NEAR(g.L, -f.N, 1e-12 * (1.0 + std::abs(f.N)));
        EXPECT_NEAR(g.M, -f.M, 1e-12 * (1.0 + std::abs(f.M)));
        if (f.k1 - f.k2 > 1e-3 * (std::abs(f.k1) + std::abs(f.k2))) {
            expect_same_direction(g.d1, f.d2, 1e-10);
            expect_same_direction(g.d2, f.d1, 1e-10);
        }
        expect_orthonormal_frame(g);
    }
}

TEST(SurfaceFrame, RefusesDegenerateOrNonFiniteInput) {
    Derivatives d = saddle(0.2, 0.1);
    Derivatives parallel = d;
    parallel.row(2) = 2.0 * parallel.row(1);
    EXPECT_THROW((void)surface_frame(parallel), NumericalError);
    Derivatives zero = d;
    zero.row(1).setZero();
    EXPECT_THROW((void)surface_frame(zero), NumericalError);
    Derivatives nearly = d;
    nearly.row(2) = nearly.row(1) + 1e-15 * Eigen::RowVector3d(0.0, 1.0, 0.0);
    EXPECT_THROW((void)surface_frame(nearly), NumericalError);
    Derivatives nan = d;
    nan(3, 2) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW((void)surface_frame(nan), NumericalError);
    Derivatives inf = d;
    inf(0, 0) = std::numeric_limits<double>::infinity();
    EXPECT_THROW((void)surface_frame(inf), NumericalError);
    // thin but valid tangents are accepted
    Derivatives thin = d;
    thin.row(2) = thin.row(1) + 1e-10 * Eigen::RowVector3d(0.0, 1.0, 0.0);
    EXPECT_NO_THROW((void)surface_frame(thin));
}

}  // namespace
}  // namespace limsurf
