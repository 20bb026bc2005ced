// The Galerkin layer: identities of the assembled matrices, the patch tests (linear functions are
// in the space, so the Galerkin solution reproduces them), and the convergence rate of the
// Laplace–Beltrami solution on a fixed limit surface under refinement of its control mesh.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/fem/galerkin.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/limit/surface_frame.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

struct Problem {
    Topology topology;
    Points X;
};

Problem load(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    return {built.mesh.topology(), built.mesh.positions()};
}

Problem refined(Problem p, SchemeKind scheme, int levels) {
    for (int l = 0; l < levels; ++l) {
        Level level = refine(p.topology, scheme);
        p.X = level.S0 * p.X;
        p.topology = std::move(level.topology);
    }
    return p;
}

/// b_i = ∫ f φ_i dA with f(frame, position) — for loads that need the normal and the curvature.
template <class F>
Eigen::VectorXd load_with_frame(const LimitSampler& sampler, const Points& X, F&& f) {
    Eigen::VectorXd b = Eigen::VectorXd::Zero(sampler.num_vertices());
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
        const SurfaceFrame frame = surface_frame(D);
        const double dA = sampler.weight(s) * std::sqrt(frame.E * frame.G - frame.F * frame.F);
        const double value = f(frame, Eigen::Vector3d(D.row(Value).transpose()));
        const auto W = sampler.limit_weights(s);
        const auto verts = sampler.vertices(s);
        for (std::size_t j = 0; j < verts.size(); ++j) {
            b(verts[j]) += dA * value * W(Value, static_cast<Index>(j));
        }
    }
    return b;
}

struct Case {
    std::string mesh;
    SchemeKind scheme;
};

class GalerkinIdentity : public ::testing::TestWithParam<Case> {};

TEST_P(GalerkinIdentity, MatricesAreSymmetricSemiDefiniteAndKillConstants) {
    const Problem p = load(GetParam().mesh);
    const LimitBasis basis(p.topology, GetParam().scheme);
    const LimitSampler sampler(basis, SamplerOptions{8, 6, 0});
    const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
    const Index V = p.topology.num_vertices();
    EXPECT_LT((m.stiffness - SparseMatrix(m.stiffness.transpose())).norm(), 1e-14 * m.stiffness.norm());
    EXPECT_LT((m.mass - SparseMatrix(m.mass.transpose())).norm(), 1e-14 * m.mass.norm());
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(V);
    EXPECT_LT((m.stiffness * ones).norm(), 1e-12 * m.stiffness.norm());  // Σ φ_i = 1
    // 1ᵀ M 1 is the area: the same quadrature as the integrals layer.
    EXPECT_NEAR(ones.dot(m.mass * ones), area(sampler, p.X), 1e-12 * area(sampler, p.X));
    std::mt19937 random(7);
    std::normal_distribution<double> normal;
    for (int trial = 0; trial < 5; ++trial) {
        Eigen::VectorXd x(V);
        for (Index i = 0; i < V; ++i) {
            x(i) = normal(random);
        }
        EXPECT_GT(x.dot(m.mass * x), 0.0);
        EXPECT_GE(x.dot(m.stiffness * x), -1e-12 * x.squaredNorm() * m.stiffness.norm());
    }
}

TEST_P(GalerkinIdentity, TheElementGatherIsExactlySymmetricAndEqualsTheSampleSum) {
    // The elements are gathered row by row (detail/element_gather.h): the mass matrix equals
    // Σ_s w_s |x_u × x_v| φ_i φ_j summed sample by sample into a dense matrix, and both matrices
    // equal their transposes bit for bit, on one thread and on three.
    const Problem p = load(GetParam().mesh);
    const LimitBasis basis(p.topology, GetParam().scheme);
    const LimitSampler sampler(basis, SamplerOptions{6, 4, 1});
    const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
    const Index V = p.topology.num_vertices();
    Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(V, V);
    for (Index s = 0; s < sampler.num_samples(); ++s) {
        const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(p.X, s);
        const Eigen::Vector3d du = D.row(1).transpose();
        const double dA = sampler.weight(s) * du.cross(Eigen::Vector3d(D.row(2).transpose())).norm();
        const auto W = sampler.limit_weights(s);
        const auto verts = sampler.vertices(s);
        for (std::size_t i = 0; i < verts.size(); ++i) {
            for (std::size_t j = 0; j < verts.size(); ++j) {
                mass(verts[i], verts[j]) += dA * W(0, static_cast<Index>(i)) * W(0, static_cast<Index>(j));
            }
        }
    }
    // Measured: 1.0e-14 of the largest entry (genus2); the library forms dA from the metric.
    EXPECT_LT((Eigen::MatrixXd(m.mass) - mass).cwiseAbs().maxCoeff(), 1e-13 * mass.cwiseAbs().maxCoeff());
    for (const SparseMatrix* A : {&m.mass, &m.stiffness}) {
        const SparseMatrix At = A->transpose();
        EXPECT_EQ((*A - At).cwiseAbs().sum(), 0.0);
    }
    const LimitSampler three(basis, SamplerOptions{6, 4, 3});
    const GalerkinMatrices m3 = assemble_laplace_beltrami(three, p.X);
    EXPECT_EQ((m3.stiffness - m.stiffness).cwiseAbs().sum(), 0.0);
    EXPECT_EQ((m3.mass - m.mass).cwiseAbs().sum(), 0.0);
}

// −Δ_S x = 2H n_x on any surface (H = 1 on the unit sphere with the outward normal): the
// coordinate functions are in the space (the limit basis reproduces linear functions of the
// control points), so the Galerkin solution with this load is the control points' x up to a
// constant — to the quadrature error, which the Stam tiles keep small next to extraordinary vertices.
TEST_P(GalerkinIdentity, CoordinateFunctionsAreReproducedOnTheCurvedSurface) {
    const Problem p = load(GetParam().mesh);
    const LimitBasis basis(p.topology, GetParam().scheme);
    const LimitSampler sampler(basis, SamplerOptions{16, 12, 0});
    const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
    for (int axis = 0; axis < 3; ++axis) {
        const Eigen::VectorXd b = load_with_frame(sampler, p.X, [&](const SurfaceFrame& frame, const Eigen::Vector3d&) {
            return 2.0 * frame.mean_curvature * frame.normal(axis);
        });
        const GalerkinPoissonSolution s = solve_galerkin_poisson(p.topology, m, b, std::nullopt);
        // Compare the functions u_h, not the control values: on the cube the limit basis is linearly
        // dependent (the checkerboard of ±1 at its corners has limit zero after one step), so the
        // control values are not unique while u_h is.
        const auto coordinate = [axis](const Points& P) { return Eigen::VectorXd(P.col(axis)); };
        const auto unit = [axis](const Points& P) {
            Points G = Points::Zero(P.rows(), 3);
            G.col(axis).setOnes();
            return G;
        };
        const GalerkinErrors e = galerkin_errors(sampler, p.X, s.u, coordinate, unit, true);
        std::printf("%s axis %d: relative L2 %.2e, H1 %.2e\n", GetParam().mesh.c_str(), axis, e.l2 / e.l2_norm,
                    e.h1 / e.h1_norm);
        // Quadrature-limited: 1e-12 (cube, icosahedron, torus), 1e-9 (genus2, whose valence-5 curvature
        // is unbounded). C2g0 9e-7: the sampler integrates its type-II triangles next to a valence-3
        // vertex, piecewise polynomial on four sub-triangles, with one rule (docs/fem.md).
        const double tolerance = GetParam().scheme == SchemeKind::C2g0 ? 2e-6 : 2e-9;
        EXPECT_LT(e.l2, tolerance * e.l2_norm) << "axis " << axis;
        EXPECT_LT(e.h1, tolerance * e.h1_norm) << "axis " << axis;
        EXPECT_LT(s.residual, 1e-10);
        EXPECT_NEAR(s.mean_removed, 0.0, 1e-8);  // ∫ 2H n dA = 0 on a closed surface
    }
}

INSTANTIATE_TEST_SUITE_P(Meshes, GalerkinIdentity,
                         ::testing::Values(Case{"cube", SchemeKind::CatmullClark},
                                           Case{"genus2", SchemeKind::CatmullClark},
                                           Case{"icosahedron", SchemeKind::Loop}, Case{"tri_torus", SchemeKind::Loop},
                                           Case{"tetra_2", SchemeKind::C2g0}),
                         [](const auto& param_info) { return param_info.param.mesh; });

// The planar patch test with essential conditions: a linear function's control values on the
// boundary of an irregular planar mesh (valence-5 centre) give that linear function everywhere.
TEST(Galerkin, PlanarPatchTestReproducesLinearFunctions) {
    for (const auto& [name, scheme] :
         {std::pair{"disk_ev5_quads", SchemeKind::CatmullClark}, std::pair{"tri_grid", SchemeKind::Loop}}) {
        const Problem p = load(name);
        const LimitBasis basis(p.topology, scheme);
        const LimitSampler sampler(basis, SamplerOptions{12, 12, 0});
        const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
        const Eigen::VectorXd u = 1.0 + 2.0 * p.X.col(0).array() - 3.0 * p.X.col(1).array();
        const Eigen::VectorXd zero = Eigen::VectorXd::Zero(p.topology.num_vertices());
        const GalerkinPoissonSolution s = solve_galerkin_poisson(p.topology, m, zero, u);
        // Exact but for the quadrature of the non-polynomial metric terms next to the valence-5
        // centre (6e-11 at degree 12; the affine triangle grid is exact to rounding).
        EXPECT_LT((s.u - u).cwiseAbs().maxCoeff(), 2e-10) << name;
    }
}

// Convergence on one fixed limit surface: the control mesh of the regular quad torus refined
// 0..3 times describes the same Catmull–Clark surface, so the Galerkin solutions of one problem
// converge at the rate of the bicubic space: L2 errors fall by 2⁴ = 16 per level, H1 by 2³ = 8.
// Manufactured solution u = sin x cos y + z, f = −Δ_S u = −(Δu − nᵀ∇²u n − 2H n·∇u).
TEST(Galerkin, LaplaceBeltramiConvergesAtTheOrderOfTheBicubicSpace) {
    const auto exact = [](const Points& P) {
        return Eigen::VectorXd(P.col(0).array().sin() * P.col(1).array().cos() + P.col(2).array());
    };
    const auto gradient = [](const Points& P) {
        Points G(P.rows(), 3);
        G.col(0) = P.col(0).array().cos() * P.col(1).array().cos();
        G.col(1) = -P.col(0).array().sin() * P.col(1).array().sin();
        G.col(2).setOnes();
        return G;
    };
    const auto f = [](const SurfaceFrame& frame, const Eigen::Vector3d& x) {
        const double sx = std::sin(x(0)), cx = std::cos(x(0)), sy = std::sin(x(1)), cy = std::cos(x(1));
        const Eigen::Vector3d grad(cx * cy, -sx * sy, 1.0);
        Eigen::Matrix3d hessian;
        hessian << -sx * cy, -cx * sy, 0, -cx * sy, -sx * cy, 0, 0, 0, 0;
        const Eigen::Vector3d& n = frame.normal;
        const double surface_laplacian =
            hessian.trace() - n.dot(hessian * n) - 2.0 * frame.mean_curvature * n.dot(grad);
        return -surface_laplacian;
    };
    const Problem coarse = load("quad_torus");
    std::vector<double> l2, h1;
    for (int level = 0; level <= 3; ++level) {
        const Problem p = refined(coarse, SchemeKind::CatmullClark, level);
        const LimitBasis basis(p.topology, SchemeKind::CatmullClark);
        const LimitSampler sampler(basis, SamplerOptions{10, 0, 0});
        const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
        const GalerkinPoissonSolution s =
            solve_galerkin_poisson(p.topology, m, load_with_frame(sampler, p.X, f), std::nullopt);
        const GalerkinErrors e = galerkin_errors(sampler, p.X, s.u, exact, gradient, true);
        l2.push_back(e.l2 / e.l2_norm);
        h1.push_back(e.h1 / e.h1_norm);
        std::printf("level %d (%ld vertices): L2 %.3e, H1 %.3e\n", level, static_cast<long>(p.topology.num_vertices()),
                    l2.back(), h1.back());
    }
    for (std::size_t k = 2; k < l2.size(); ++k) {
        EXPECT_GT(l2[k - 1] / l2[k], 12.0) << "level " << k;  // 16 asymptotically
        EXPECT_GT(h1[k - 1] / h1[k], 6.5) << "level " << k;   // 8 asymptotically
    }
}

TEST(Galerkin, BadInputIsRefused) {
    const Problem p = load("quad_grid");
    const LimitBasis basis(p.topology, SchemeKind::CatmullClark);
    const LimitSampler sampler(basis, 4);
    EXPECT_THROW((void)assemble_laplace_beltrami(sampler, Points::Zero(3, 3)), InputError);
    const GalerkinMatrices m = assemble_laplace_beltrami(sampler, p.X);
    const Eigen::VectorXd b = Eigen::VectorXd::Zero(p.topology.num_vertices());
    EXPECT_THROW((void)solve_galerkin_poisson(p.topology, m, b, std::nullopt), InputError);  // open: needs values
    const auto nan = [](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), std::nan("")); };
    EXPECT_THROW((void)galerkin_load(sampler, p.X, nan), InputError);
    // A flat (degenerate) surface: every control point at one place.
    EXPECT_THROW((void)assemble_laplace_beltrami(sampler, Points::Zero(p.X.rows(), 3)), NumericalError);
}

}  // namespace
}  // namespace limsurf::test
