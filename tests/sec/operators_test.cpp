// Operators of SEC Table 1 and the Poisson solve.
// Identities: the dual operators are the primal ones conjugated by M1⁻¹; the Laplacian kills
// constants; the Poisson solution satisfies its system and, on closed meshes, has mean zero.
// Published (shape of SEC §3.4, operator error): on a closed Catmull–Clark mesh with extraordinary
// vertices, Poisson solutions with DEC, DECsnap and SEC at levels 1..3 against SEC at a deeper
// level: the SEC error falls by about 4 per level, SEC at level 3 is far below DEC, and DECsnap lies
// between DEC and SEC level 3. Published (shape of SEC Fig. 3, convergence): control meshes refined
// n times, DEC on the surface refined FINE times as the reference: DEC converges at order 2, SEC
// with the reference's own inner products (L = FINE − n) at order ≈ 4 on a regular torus and ≈ 3
// on genus 2 (extraordinary vertices).
#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/operators.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

Eigen::MatrixXd dense(const SparseMatrix& m) {
    return Eigen::MatrixXd(m);
}

InnerProductOptions method(InnerProductMethod m, int level = 3) {
    InnerProductOptions o;
    o.method = m;
    o.level = level;
    return o;
}

TEST(Operators, DualOperatorsAreThePrimalOnesConjugatedByM1) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const Operators ops(t, control_inner_products(t, built.mesh.positions(), SchemeKind::CatmullClark,
                                                  method(InnerProductMethod::Sec, 2)));
    const Eigen::MatrixXd M1 = dense(ops.inner_products().M1);
    const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(t.num_edges(), 0.0, 7.0).array().cos();
    // dual Hodge–Laplacian = M1⁻¹ (primal Hodge–Laplacian) M1⁻¹
    const Eigen::VectorXd M1inv_w = M1.ldlt().solve(w);
    const Eigen::VectorXd expected = M1.ldlt().solve(ops.hodge_laplacian_1(M1inv_w));
    EXPECT_LE((ops.dual_hodge_laplacian_1(w) - expected).cwiseAbs().maxCoeff(), 1e-9 * expected.cwiseAbs().maxCoeff());
    // dual Laplacian −d1 M1⁻¹ d1ᵀ, dual divergence −d1 M1⁻¹
    const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(t.num_faces(), -1.0, 1.0);
    const Eigen::VectorXd dual_lap = -dense(ops.d1()) * M1.ldlt().solve(dense(ops.d1()).transpose() * u);
    EXPECT_LE((ops.dual_laplacian(u) - dual_lap).cwiseAbs().maxCoeff(), 1e-10 * dual_lap.cwiseAbs().maxCoeff());
    // Primal: the Laplacian is d0ᵀ M1 d0 and kills constants; curl ∘ gradient = 0.
    EXPECT_LE((ops.laplacian() * Eigen::VectorXd::Ones(t.num_vertices())).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_EQ(SparseMatrix((ops.curl() * ops.gradient()).pruned()).nonZeros(), 0);
    EXPECT_LE((dense(ops.laplacian()) - dense(ops.d0()).transpose() * M1 * dense(ops.d0())).cwiseAbs().maxCoeff(),
              1e-12);
}

TEST(Operators, TheLaplacianIsTheSameOnAnyNumberOfThreadsAndEqualsEigensProduct) {
    // genus 2 refined three times (3 198 vertices): enough rows for three threads' ranges.
    const FinestLevel fine = test::refined_bundled("genus2", SchemeKind::CatmullClark, 3);
    const InnerProducts ip = control_inner_products(fine.topology, fine.positions, SchemeKind::CatmullClark,
                                                    method(InnerProductMethod::Sec, 1));
    const SparseMatrix one = Operators(fine.topology, ip, 1).laplacian();
    const SparseMatrix three = Operators(fine.topology, ip, 3).laplacian();
    ASSERT_EQ(one.nonZeros(), three.nonZeros());
    EXPECT_TRUE(std::equal(one.valuePtr(), one.valuePtr() + one.nonZeros(), three.valuePtr()));
    EXPECT_TRUE(std::equal(one.innerIndexPtr(), one.innerIndexPtr() + one.nonZeros(), three.innerIndexPtr()));
    const Operators ops(fine.topology, ip, 3);
    const SparseMatrix eigen = SparseMatrix(SparseMatrix(ops.d0().transpose()) * ip.M1) * ops.d0();
    const double scale = SparseMatrix(eigen.cwiseAbs()).coeffs().maxCoeff();
    EXPECT_LE(SparseMatrix((one - eigen).cwiseAbs()).coeffs().maxCoeff(), 1e-14 * scale);
    EXPECT_EQ(one.nonZeros(), eigen.nonZeros());  // the same pattern, structural zeros kept alike
}

TEST(Poisson, ClosedMeshSolutionSatisfiesTheSystemWithMeanZero) {
    const BuildResult built = read_mesh(test::find_bundled("quad_valence_5").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const Operators ops(t, control_inner_products(t, X, SchemeKind::CatmullClark, method(InnerProductMethod::Sec)));
    PoissonProblem problem;
    problem.f = (X.col(0).array() * 2.0).sin() + 0.3;  // not mean-zero: the solve removes the mean
    const PoissonSolution s = solve_poisson(t, ops, problem);
    EXPECT_LE(s.residual, 1e-12);
    const Eigen::VectorXd mass = ops.inner_products().M0 * Eigen::VectorXd::Ones(t.num_vertices());
    EXPECT_NEAR(s.mean_removed, mass.dot(problem.f) / mass.sum(), 1e-14);  // the M0-mean of f
    EXPECT_GT(s.mean_removed, 0.1);                                        // the 0.3 offset is seen
    EXPECT_NEAR(mass.dot(s.u), 0.0, 1e-12);
    const Eigen::VectorXd b = ops.inner_products().M0 * (problem.f.array() - s.mean_removed).matrix();
    EXPECT_LE((ops.laplacian() * s.u - b).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Poisson, OpenMeshKeepsTheDirichletValues) {
    const BuildResult built = read_mesh(test::find_bundled("disk_ev5_quads").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const Operators ops(t, control_inner_products(t, X, SchemeKind::CatmullClark, method(InnerProductMethod::Dec)));
    // DEC (Alexa–Wardetzky) is linearly precise in the plane: u = 2x − y + 1 with f = 0 exactly.
    PoissonProblem problem;
    problem.f = Eigen::VectorXd::Zero(t.num_vertices());
    const Eigen::VectorXd linear = 2.0 * X.col(0) - X.col(1) + Eigen::VectorXd::Ones(t.num_vertices());
    problem.boundary_values = linear;
    const PoissonSolution s = solve_poisson(t, ops, problem);
    EXPECT_LE((s.u - linear).cwiseAbs().maxCoeff(), 1e-12);
    problem.boundary_values.reset();
    EXPECT_THROW((void)solve_poisson(t, ops, problem), InputError);
}

TEST(Poisson, LoadVectorOfOneIsTheAreaOfLevelL) {
    // Σ_i ∫ 1·φ_i dA = area: with SEC the load is integrated on level L, so its sum is 1ᵀ M0^SEC 1.
    const BuildResult built = read_mesh(test::find_bundled("tri_valence_7").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const InnerProductOptions o = method(InnerProductMethod::Sec, 2);
    const Eigen::VectorXd b =
        load_vector(t, X, SchemeKind::Loop, o, [](const Points& P) { return Eigen::VectorXd::Ones(P.rows()).eval(); });
    const SparseMatrix M0 = control_inner_products(t, X, SchemeKind::Loop, o).M0;
    EXPECT_NEAR(b.sum(), Eigen::VectorXd::Ones(t.num_vertices()).dot(M0 * Eigen::VectorXd::Ones(t.num_vertices())),
                1e-12);
    EXPECT_THROW((void)load_vector(t, X, SchemeKind::Loop, o,
                                   [](const Points& P) { return Eigen::VectorXd::Ones(P.rows() - 1).eval(); }),
                 InputError);
}

/// The L² norm of a vertex function in the metric M0.
double l2(const SparseMatrix& M0, const Eigen::VectorXd& u) {
    return std::sqrt(u.dot(M0 * u));
}

TEST(PoissonStudy, OperatorErrorHasThePapersShape) {
    // SEC §3.4, operator error: the same control mesh (genus 2, valences 3 and 5), the inner products
    // changed. Reference: SEC at level 5 (the paper uses 7; levels ≤ 3 differ from it ≥ 16× more than
    // level 5 does from 7). Measured: DEC 0.21, DECsnap 0.15, SEC 0.039, 0.0093, 0.0022 — ratios
    // 4.2 per level as in the paper; DEC/SEC₃ = 95 here (paper, car model: 103; studies/sec_operator_error
    // has more meshes), so 50 is asserted.
    const int reference_level = 5;
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    PoissonProblem problem;
    problem.f = (3.0 * X.col(0)).array().sin() * (2.0 * X.col(1)).array().cos() + X.col(2).array();
    const auto solve = [&](InnerProductMethod m, int level) {
        const Operators ops(t, control_inner_products(t, X, SchemeKind::CatmullClark, method(m, level)));
        return solve_poisson(t, ops, problem).u;
    };
    const InnerProducts reference_m =
        control_inner_products(t, X, SchemeKind::CatmullClark, method(InnerProductMethod::Sec, reference_level));
    const Eigen::VectorXd reference = solve(InnerProductMethod::Sec, reference_level);
    const double norm = l2(reference_m.M0, reference);
    const auto error = [&](const Eigen::VectorXd& u) { return l2(reference_m.M0, u - reference) / norm; };
    const double dec = error(solve(InnerProductMethod::Dec, 0));
    const double decsnap = error(solve(InnerProductMethod::DecSnap, 0));
    std::vector<double> sec;
    for (int level = 1; level <= 3; ++level) {
        sec.push_back(error(solve(InnerProductMethod::Sec, level)));
    }
    RecordProperty("dec", std::to_string(dec));
    RecordProperty("decsnap", std::to_string(decsnap));
    for (std::size_t i = 0; i < sec.size(); ++i) {
        RecordProperty("sec_level_" + std::to_string(i + 1), std::to_string(sec[i]));
    }
    for (std::size_t i = 1; i < sec.size(); ++i) {
        EXPECT_GT(sec[i - 1] / sec[i], 3.0) << "level " << i + 1;
        EXPECT_LT(sec[i - 1] / sec[i], 6.0) << "level " << i + 1;
    }
    EXPECT_GT(dec / sec[2], 50.0);
    EXPECT_LT(decsnap, dec);
    EXPECT_GT(decsnap, sec[2]);
}

/// Relative L² errors (in the reference's M0) of DEC and SEC (L = fine − n) Poisson solutions on
/// the mesh refined n = 0..rows−1 times, against DEC on the mesh refined @p fine times; every
/// solution is carried to the fine level by subdivision (the paper's construction, and that of
/// `limsurf poisson --reference-level`).
std::string scientific(double x) {
    std::ostringstream out;
    out << std::scientific << std::setprecision(3) << x;
    return out.str();
}

struct Convergence {
    std::vector<double> dec, sec;
};

Convergence convergence(const char* mesh, const std::function<double(const Eigen::Vector3d&)>& f, int fine, int rows) {
    const BuildResult built = read_mesh(test::find_bundled(mesh).path);
    RefineOptions refine;
    refine.levels = fine;
    const Hierarchy h(built.mesh.topology(), refine);
    const auto sample = [&](const Points& P) {
        Eigen::VectorXd values(P.rows());
        for (Eigen::Index i = 0; i < P.rows(); ++i) {
            values(i) = f(P.row(i).transpose());
        }
        return values;
    };
    const Topology& tf = h.topology(fine);
    const Points XF = h.positions(fine, built.mesh.positions());
    const Operators fine_ops(tf,
                             control_inner_products(tf, XF, SchemeKind::CatmullClark, method(InnerProductMethod::Dec)));
    PoissonProblem fine_problem;
    fine_problem.f = sample(XF);
    const Eigen::VectorXd reference = solve_poisson(tf, fine_ops, fine_problem).u;
    const SparseMatrix& M0 = fine_ops.inner_products().M0;
    Convergence out;
    for (int n = 0; n < rows; ++n) {
        const Topology& t = h.topology(n);
        const Points X = h.positions(n, built.mesh.positions());
        for (const auto& [options, errors] : {std::pair{method(InnerProductMethod::Dec, 0), &out.dec},
                                              std::pair{method(InnerProductMethod::Sec, fine - n), &out.sec}}) {
            const Operators ops(t, control_inner_products(t, X, SchemeKind::CatmullClark, options));
            PoissonProblem problem;
            problem.f = sample(X);
            problem.load = load_vector(t, X, SchemeKind::CatmullClark, options, sample);
            Eigen::VectorXd u = solve_poisson(t, ops, problem).u;
            for (int l = n + 1; l <= fine; ++l) {
                u = h.step(l).S0 * u;
            }
            errors->push_back(l2(M0, u - reference) / l2(M0, reference));
            ::testing::Test::RecordProperty(std::string(mesh) + (errors == &out.dec ? "_dec_n" : "_sec_n") +
                                                std::to_string(n),
                                            scientific(errors->back()));
        }
    }
    return out;
}

double order(const std::vector<double>& errors, std::size_t i) {
    return std::log2(errors[i - 1] / errors[i]);
}

TEST(PoissonStudy, ConvergenceHasThePapersShapeOnARegularTorus) {
    // quad_torus, f = sin x, reference DEC at level 5. Measured (studies/sec_convergence.sh, same
    // construction): DEC 0.151, 0.0356, 0.00864, 0.00205 (orders 2.09, 2.04, 2.08); SEC 9.98e-4,
    // 1.90e-4, 7.82e-6, 3.90e-7 (orders 2.39, 4.60, 4.33 — order 4 once asymptotic, as Fig. 3).
    const Convergence c = convergence(
        "quad_torus", [](const Eigen::Vector3d& x) { return std::sin(x.x()); }, 5, 4);
    for (std::size_t i = 1; i < c.dec.size(); ++i) {
        EXPECT_GT(order(c.dec, i), 1.8) << "DEC, n = " << i;
        EXPECT_LT(order(c.dec, i), 2.3) << "DEC, n = " << i;
    }
    for (std::size_t i = 2; i < c.sec.size(); ++i) {
        EXPECT_GT(order(c.sec, i), 3.8) << "SEC, n = " << i;
    }
    EXPECT_GT(c.dec[0] / c.sec[0], 50.0);
}

TEST(PoissonStudy, ConvergenceIsReducedNearExtraordinaryVertices) {
    // genus2 (valences 3 and 5), f = sin 2x, reference DEC at level 5. Measured: DEC orders 1.56,
    // 1.90; SEC 6.84e-3, 6.21e-4, 7.78e-5 (orders 3.46, 3.00): above DEC's 2, below the regular 4.
    const Convergence c = convergence(
        "genus2", [](const Eigen::Vector3d& x) { return std::sin(2.0 * x.x()); }, 5, 3);
    EXPECT_GT(order(c.dec, 2), 1.7);
    EXPECT_LT(order(c.dec, 2), 2.3);
    for (std::size_t i = 1; i < c.sec.size(); ++i) {
        EXPECT_GT(order(c.sec, i), 2.6) << "SEC, n = " << i;
        EXPECT_LT(order(c.sec, i), 3.7) << "SEC, n = " << i;
    }
}

}  // namespace
}  // namespace limsurf
