// The weight tuning of iga-tuned-catmull-clark-weights §3 against the paper's Table 1, the
// eigen-analysis of the scheme's own refinement (an independent computation of the same
// eigenvalues), the regular case's exact quadratic reproduction, and planted quadratics for the
// shape decomposition of §3.4.
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/analysis/weight_tuning.h"
#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf::test {
namespace {

using Complex = std::complex<double>;

/// Whether @p spectrum has an eigenvalue @p value (real) of frequency @p frequency.
bool has_eigenvalue(const SchemeSpectrum& spectrum, double value, int frequency) {
    return std::any_of(spectrum.eigenvalues.begin(), spectrum.eigenvalues.end(), [&](const EigenvalueEntry& e) {
        return e.frequency == frequency && std::abs(e.value - Complex(value)) < 1e-9;
    });
}

SchemeSpectrum analyse_weights(int valence, const VertexRuleWeights& w) {
    EigenRequest request;
    request.valence = valence;
    request.weights = w;
    return analyse_scheme(request);
}

// The closed-form one-ring eigenvalues are eigenvalues of the matrix the analysis reads off the
// scheme's own refinement of a two-ring complex, in the frequency the tuning says.
TEST(WeightTuning, OneRingClosedFormsAreEigenvaluesOfTheRefinement) {
    const std::vector<VertexRuleWeights> weights{
        {0, 1, 1}, {13.4575, 0.999938, 0.999938}, {9.0, 0.6, 1.7}, {30.0, 0.3, 0.45}};
    for (int n : {3, 5, 6, 7, 9, 12}) {
        for (VertexRuleWeights w : weights) {
            if (w.alpha == 0) {
                w = catmull_clark_weights(n);
            }
            SCOPED_TRACE(testing::Message()
                         << "valence " << n << " weights " << w.alpha << ", " << w.beta << ", " << w.gamma);
            const TunedVertex s = one_ring_spectrum(n, w);
            const SchemeSpectrum a = analyse_weights(n, w);
            if (s.lambda > std::abs(s.lambda3) && s.lambda > std::abs(s.lambda4)) {
                EXPECT_NEAR(s.lambda, a.subdominant, 1e-10);
            }
            EXPECT_TRUE(has_eigenvalue(a, s.lambda, 1));
            EXPECT_TRUE(has_eigenvalue(a, s.lambda3, 0));
            EXPECT_TRUE(has_eigenvalue(a, s.lambda4, 2 % n));
        }
    }
    EXPECT_NEAR(one_ring_spectrum(5, catmull_clark_weights(5)).lambda, catmull_clark_subdominant(5), 1e-14);
}

// Table 1 (valence 5): the weights at the paper's λ to the digits it prints (α to 5e-5, β = γ to
// half a unit of the sixth digit; the saddle's β is 0.8248855, which the paper prints as 0.824885).
TEST(WeightTuning, Table1WeightsAtThePapersLambda) {
    const auto cup = weights_for_subdominant(5, 0.550);
    ASSERT_EQ(cup.size(), 1u);
    EXPECT_EQ(cup[0].constraint, TuningConstraint::Relaxed);  // (30) has no real solution below 0.608
    EXPECT_NEAR(cup[0].weights.alpha, 13.4575, 5e-5);
    EXPECT_NEAR(cup[0].weights.beta, 0.999938, 5e-7);
    EXPECT_NEAR(cup[0].weights.gamma, 0.999938, 5e-7);
    const auto saddle = weights_for_subdominant(5, 0.585);
    ASSERT_EQ(saddle.size(), 1u);
    EXPECT_NEAR(saddle[0].weights.alpha, 13.9851, 5e-5);
    EXPECT_NEAR(saddle[0].weights.beta, 0.824885, 1e-6);
    EXPECT_NEAR(saddle[0].weights.gamma, 0.824885, 1e-6);
    // The presets carry the same numbers.
    const VertexRuleWeights preset = TunedWeights::preset("saddle").at(0, 5);
    EXPECT_NEAR(preset.alpha, saddle[0].weights.alpha, 5e-5);
    EXPECT_NEAR(preset.beta, saddle[0].weights.beta, 1e-6);
}

// Table 1's λ: the cup and saddle optima are the ends of the interval in which both shapes' errors
// are at most Catmull–Clark's (§3.3, Fig. 7), to the paper's three decimals.
TEST(WeightTuning, Table1LambdaIsTheProtectedOptimum) {
    for (const auto& [shape, lambda] :
         {std::pair{QuadraticShape::Cup, 0.550}, std::pair{QuadraticShape::Saddle, 0.585}}) {
        SCOPED_TRACE(to_string(shape));
        TuningRequest request;
        request.valence = 5;
        request.shape = shape;
        request.curve_samples = 41;
        const TuningResult r = tune_weights(request);
        EXPECT_NEAR(r.tuned.lambda, lambda, 5e-4);
        EXPECT_TRUE(r.protection_binds);
        const bool cup = shape == QuadraticShape::Cup;
        const double own = cup ? r.tuned_errors.cup : r.tuned_errors.saddle;
        const double own_classical = cup ? r.classical_errors.cup : r.classical_errors.saddle;
        const double other = cup ? r.tuned_errors.saddle : r.tuned_errors.cup;
        const double other_classical = cup ? r.classical_errors.saddle : r.classical_errors.cup;
        EXPECT_LT(own, 0.7 * own_classical);
        EXPECT_LE(other, other_classical * (1 + 1e-12));
        // The shape alone would go further: its unconstrained optimum is better still.
        const double free = cup ? r.unconstrained.errors.cup : r.unconstrained.errors.saddle;
        EXPECT_LT(free, own);
        EXPECT_TRUE(std::is_sorted(r.curve.begin(), r.curve.end(), [](const TuningSample& a, const TuningSample& b) {
            return a.vertex.lambda < b.vertex.lambda;
        }));
    }
    const TunedVertex cup = tuned_vertex_weights(5, QuadraticShape::Cup);
    EXPECT_DOUBLE_EQ(cup.lambda, 0.550);
    EXPECT_NEAR(cup.weights.alpha, 13.4575, 5e-5);
}

// Catmull–Clark's own weights at valence 4 are the bicubic B-spline, which reproduces quadratics:
// both errors vanish (an exact identity of the whole pipeline: eigenvectors, projection,
// characteristic map, second derivatives through the map, quadrature).
TEST(WeightTuning, RegularVerticesReproduceQuadratics) {
    const ShapeErrors e = quadratic_shape_errors(4, catmull_clark_weights(4));
    EXPECT_LT(e.cup, 1e-10);
    EXPECT_LT(e.saddle, 1e-10);
}

// The paper's observation that the number of Gauss points is irrelevant (Fig. 6), and that the
// tiles towards the vertex have converged.
TEST(WeightTuning, ErrorsDoNotDependOnTheQuadrature) {
    const VertexRuleWeights w = weights_for_subdominant(5, 0.57)[0].weights;
    TuningOptions coarse;
    TuningOptions fine;
    fine.quadrature_points = 6;
    fine.tile_levels = 14;
    const ShapeErrors a = quadratic_shape_errors(5, w, coarse);
    const ShapeErrors b = quadratic_shape_errors(5, w, fine);
    EXPECT_NEAR(a.cup, b.cup, 1e-3 * b.cup);
    EXPECT_NEAR(a.saddle, b.saddle, 1e-3 * b.saddle);
}

// For every valence the optimiser handles, the tuned weights' eigen-analysis (the scheme's own
// refinement) gives exactly the λ they were tuned for, λ₁ = λ₂ dominant from frequencies 1 and n−1,
// λ₃ = λ² in frequency 0, and a regular, injective characteristic map (C¹).
TEST(WeightTuning, TunedWeightsAreC1WithTheirLambdaAtEveryValence) {
    for (int n : {3, 5, 6, 7, 8, 9, 10, 11, 12}) {
        for (const QuadraticShape shape : {QuadraticShape::Cup, QuadraticShape::Saddle}) {
            SCOPED_TRACE(testing::Message() << "valence " << n << " " << to_string(shape));
            TuningRequest request;
            request.valence = n;
            request.shape = shape;
            request.curve_samples = 15;
            request.lambda_tolerance = 1e-3;
            const TuningResult r = tune_weights(request);
            const SchemeSpectrum a = analyse_weights(n, r.tuned.weights);
            EXPECT_NEAR(a.subdominant, r.tuned.lambda, 1e-10);
            EXPECT_EQ(a.subdominant_multiplicity, 2);
            EXPECT_TRUE(a.c1.passed) << a.c1.detail;
            EXPECT_TRUE(has_eigenvalue(a, r.tuned.lambda * r.tuned.lambda, 0));
        }
    }
}

// Where (30) has real solutions (valence 5 just above 0.608) both λ₃ and λ₄ = λ₅ equal λ²: the
// necessary C² condition (17) holds in the analysis.
TEST(WeightTuning, ExactConstraintGivesTheC2Spectrum) {
    const auto candidates = weights_for_subdominant(5, 0.615);
    ASSERT_EQ(candidates.size(), 2u);  // β and γ swapped
    for (const TunedVertex& v : candidates) {
        EXPECT_EQ(v.constraint, TuningConstraint::Exact);
        const SchemeSpectrum a = analyse_weights(5, v.weights);
        EXPECT_NEAR(a.subdominant, 0.615, 1e-10);
        EXPECT_TRUE(a.c2_necessary.passed) << a.c2_necessary.detail;
    }
    EXPECT_NEAR(candidates[0].weights.beta, candidates[1].weights.gamma, 1e-12);
}

TEST(WeightTuning, BadInput) {
    EXPECT_THROW((void)feasible_subdominant_range(4), InputError);
    EXPECT_THROW((void)feasible_subdominant_range(2), InputError);
    EXPECT_THROW((void)weights_for_subdominant(5, 0.9), InputError);
    EXPECT_THROW((void)weights_for_subdominant(5, std::nan("")), InputError);
    EXPECT_THROW((void)quadratic_shape_errors(4, {13.0, 1.0, 1.0}), InputError);
    EXPECT_THROW((void)one_ring_spectrum(5, {-1.0, 1.0, 1.0}), InputError);
    TuningRequest request;
    request.curve_samples = 2;
    EXPECT_THROW((void)tune_weights(request), InputError);
    request.curve_samples = 11;
    request.lambda_low = 0.1;
    request.lambda_high = 0.5;
    EXPECT_THROW((void)tune_weights(request), InputError);
    EXPECT_THROW((void)parse_quadratic_shape("bowl"), InputError);
    TuningOptions threads;
    threads.num_threads = -1;
    EXPECT_THROW((void)quadratic_shape_errors(5, catmull_clark_weights(5), threads), InputError);
}

// The faces of the 2-neighbourhood are shared among threads and summed in face order after: the
// errors have the same bits for any thread count (classical and tuned weights, a low and a high
// valence).
TEST(WeightTuning, ErrorsDoNotDependOnTheThreadCount) {
    for (const int n : {5, 11}) {
        for (const VertexRuleWeights& w :
             {catmull_clark_weights(n), weights_for_subdominant(n, 0.55).front().weights}) {
            TuningOptions options;
            options.num_threads = 1;
            const ShapeErrors one = quadratic_shape_errors(n, w, options);
            for (const int threads : {2, 3, 0}) {
                options.num_threads = threads;
                const ShapeErrors many = quadratic_shape_errors(n, w, options);
                EXPECT_EQ(many.cup, one.cup) << "valence " << n << ", " << threads << " threads";
                EXPECT_EQ(many.saddle, one.saddle) << "valence " << n << ", " << threads << " threads";
            }
        }
    }
}

// ---- the decomposition (§3.4) ----------------------------------------------------------------

/// A one-ring of n quads around vertex 0 (edge neighbours 1..n, face neighbours n+1..2n).
Topology one_ring(int n) {
    std::vector<std::vector<Index>> faces;
    for (int j = 0; j < n; ++j) {
        faces.push_back({0, 1 + j, 1 + n + j, 1 + (j + 1) % n});
    }
    return Topology::from_polygons(2 * n + 1, faces);
}

/// The characteristic map on the one-ring, from the scheme's own refinement: the real eigenspace
/// of the subdominant eigenvalue of S (read off S0), combined into the frequency-1 mode along the
/// centre's edge order and scaled to put the first edge neighbour at 1.
std::vector<Complex> characteristic_one_ring(const Topology& t, const TunedWeights& weights, int n) {
    const Level level = refine(t, SchemeKind::CatmullClark, SchemeOptions{}, weights);
    // Child rows of the one-ring: the centre's child, the spokes' edge points, the faces' points.
    std::vector<Index> rows(static_cast<std::size_t>(t.num_vertices()), invalid_index);
    const Provenance& p = level.provenance;
    for (Index c = 0; c < level.topology.num_vertices(); ++c) {
        const Index parent = p.vertex_parent[static_cast<std::size_t>(c)];
        if (p.vertex_parent_kind[static_cast<std::size_t>(c)] == ParentKind::Vertex && parent == 0) {
            rows[0] = c;
        } else if (p.vertex_parent_kind[static_cast<std::size_t>(c)] == ParentKind::Edge) {
            const Index a = t.edge_vertices(parent)[0], b = t.edge_vertices(parent)[1];
            if (a == 0 || b == 0) {
                rows[static_cast<std::size_t>(a == 0 ? b : a)] = c;
            }
        } else if (p.vertex_parent_kind[static_cast<std::size_t>(c)] == ParentKind::Face) {
            rows[static_cast<std::size_t>(1 + n + parent)] = c;  // face j's opposite corner is 1 + n + j
        }
    }
    const Eigen::MatrixXd dense = Eigen::MatrixXd(level.S0);
    Eigen::MatrixXd S(2 * n + 1, 2 * n + 1);
    for (Index i = 0; i < S.rows(); ++i) {
        S.row(i) = dense.row(rows[static_cast<std::size_t>(i)]);
    }
    const Eigen::EigenSolver<Eigen::MatrixXd> solver(S);
    double lambda = 0.0;
    for (Index i = 0; i < S.rows(); ++i) {
        const Complex v = solver.eigenvalues()(i);
        if (std::abs(v - 1.0) > 1e-9 && std::abs(v.imag()) < 1e-9) {
            lambda = std::max(lambda, v.real());
        }
    }
    std::vector<Eigen::VectorXcd> basis;
    for (Index i = 0; i < S.rows(); ++i) {
        if (std::abs(solver.eigenvalues()(i) - lambda) < 1e-9) {
            basis.push_back(solver.eigenvectors().col(i));
        }
    }
    EXPECT_EQ(basis.size(), 2u);
    // z = c₀ b₀ + c₁ b₁ with z(e₁) = ω z(e₀) in the centre's edge order, and z(e₀) = 1.
    const auto edges = t.vertex_edges(0);
    const Index e0 = t.other_vertex(edges[0], 0), e1 = t.other_vertex(edges[1], 0);
    const Complex omega = std::polar(1.0, 2.0 * std::numbers::pi / n);
    Eigen::Matrix2cd A;
    A << basis[0](e0), basis[1](e0), basis[0](e1) - omega * basis[0](e0), basis[1](e1) - omega * basis[1](e0);
    const Eigen::Vector2cd c = A.partialPivLu().solve(Eigen::Vector2cd(1.0, 0.0));
    std::vector<Complex> z(static_cast<std::size_t>(S.rows()));
    for (Index i = 0; i < S.rows(); ++i) {
        z[static_cast<std::size_t>(i)] = c(0) * basis[0](i) + c(1) * basis[1](i);
    }
    return z;
}

// Control points that are exactly k₃ u₃ + k₄ u₄ + k₅ u₅ over the characteristic one-ring come back
// with those coefficients (u₃ = |z|², u₄ = Re z², u₅ = Im z²), for Catmull–Clark and tuned weights,
// and R of (38) follows; a rigid motion changes nothing.
TEST(ShapeDecomposition, PlantedQuadraticsComeBack) {
    for (int n : {5, 6, 8}) {
        for (const bool tuned : {false, true}) {
            SCOPED_TRACE(testing::Message() << "valence " << n << (tuned ? " tuned" : " classical"));
            const Topology t = one_ring(n);
            TunedWeights weights;
            if (tuned) {
                weights.set_vertex(
                    0, weights_for_subdominant(n, one_ring_spectrum(n, catmull_clark_weights(n)).lambda + 0.02)[0]
                           .weights);
            }
            const std::vector<Complex> z = characteristic_one_ring(t, weights, n);
            const double k3 = 0.7, k4 = -0.3, k5 = 0.45;
            Points P(t.num_vertices(), 3);
            for (Index i = 0; i < t.num_vertices(); ++i) {
                const Complex zi = z[static_cast<std::size_t>(i)];
                const Complex z2 = zi * zi;
                P.row(i) << zi.real(), zi.imag(), k3 * std::norm(zi) + k4 * z2.real() + k5 * z2.imag();
            }
            const auto d = decompose_shapes(t, P, weights);
            ASSERT_EQ(d.size(), 1u);
            const double sign = d[0].normal.z() > 0 ? 1.0 : -1.0;
            EXPECT_NEAR(std::abs(d[0].normal.z()), 1.0, 1e-12);
            EXPECT_NEAR(sign * d[0].k3, k3, 1e-10);
            EXPECT_NEAR(sign * d[0].k4, k4, 1e-10);
            EXPECT_NEAR(sign * d[0].k5, k5, 1e-10);
            const double R = k3 * k3 / (k4 * k4 + k5 * k5) * 1.3 / 0.7;
            EXPECT_NEAR(d[0].ratio, R, 1e-9 * R);
            EXPECT_TRUE(d[0].cup_dominates());
            // (x, y) = (ξ₁, ξ₂): the tangents are the unit axes, and the limit point lies above ξ = 0.
            EXPECT_LT((d[0].tangent1 - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
            EXPECT_LT((d[0].tangent2 - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);
            EXPECT_LT(d[0].position.head<2>().norm(), 1e-12);
            if (!tuned) {  // Catmull–Clark's limit stencil (n² c + 4 Σ e + Σ f) / (n (n + 5)), c = 0 here
                double sum = 0.0;
                for (Index i = 1; i < t.num_vertices(); ++i) {
                    sum += (i <= n ? 4.0 : 1.0) * P(i, 2);  // one_ring(): edge neighbours 1..n, then faces'
                }
                EXPECT_NEAR(d[0].position.z(), sum / (n * (n + 5)), 1e-12);
            }
            // A rigid motion: rotate about an oblique axis and translate.
            const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
            const Points moved = (P * Q.transpose()).rowwise() + Eigen::RowVector3d(3, -1, 2);
            const auto e = decompose_shapes(t, moved, weights);
            ASSERT_EQ(e.size(), 1u);
            EXPECT_NEAR(e[0].ratio, d[0].ratio, 1e-9 * R);
            EXPECT_NEAR(std::abs(e[0].k3), k3, 1e-10);
            EXPECT_LT((e[0].position - (Q * d[0].position + Eigen::Vector3d(3, -1, 2))).norm(), 1e-12);
            EXPECT_LT((e[0].tangent1 - Q * d[0].tangent1).norm(), 1e-12);
            EXPECT_LT((e[0].tangent2 - Q * d[0].tangent2).norm(), 1e-12);
        }
    }
}

// A plane — here the characteristic one-ring (classical and tuned weights) mapped by random affine
// maps, turned, and moved up to 1e6 one-ring sizes away from the origin — has no quadratic part:
// what rounding makes of it stays below the floor of 2e-15 of the one-ring's scale (its size or
// its distance from the origin; measured: at most 6e-17 over 6 000 such planes), R is NaN and
// neither shape dominates. A bend of 1e-11 on a plane 2.3e3 from the origin (floor 4.6e-12) is
// still seen.
TEST(ShapeDecomposition, AFlatOneRingHasNoQuadraticPart) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int n : {3, 5, 6, 8, 12}) {
        const Topology t = one_ring(n);
        for (int trial = 0; trial < 40; ++trial) {
            TunedWeights weights;  // every other trial with tuned weights
            if (n >= 5 && trial % 2 == 1) {
                weights.set_vertex(
                    0, weights_for_subdominant(n, one_ring_spectrum(n, catmull_clark_weights(n)).lambda + 0.02)[0]
                           .weights);
            }
            const std::vector<Complex> z = characteristic_one_ring(t, weights, n);
            Eigen::Matrix3d A;
            A << 1.0 + 0.5 * unit(random), 0.5 * unit(random), 0.0, 0.5 * unit(random), 1.0 + 0.5 * unit(random), 0.0,
                unit(random), unit(random), 1.0;  // (x, y) sheared, the plane's height affine in x, y
            const Eigen::Matrix3d Q =
                Eigen::AngleAxisd(3.0 * unit(random),
                                  Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized())
                    .toRotationMatrix();
            const Eigen::RowVector3d shift =
                std::pow(10.0, 6.0 * (trial % 7) / 6.0) * Eigen::RowVector3d(unit(random), unit(random), unit(random));
            Points P(t.num_vertices(), 3);
            for (Index i = 0; i < t.num_vertices(); ++i) {
                const Complex zi = z[static_cast<std::size_t>(i)];
                P.row(i) = (A * Eigen::Vector3d(zi.real(), zi.imag(), 0.0)).transpose() * Q.transpose() + shift;
            }
            const auto d = decompose_shapes(t, P, weights, 3);
            ASSERT_EQ(d.size(), 1u);
            EXPECT_FALSE(d[0].has_quadratic_part) << "valence " << n << " trial " << trial;
            EXPECT_EQ(d[0].k3, 0.0);
            EXPECT_EQ(d[0].k4, 0.0);
            EXPECT_TRUE(std::isnan(d[0].ratio));
            EXPECT_FALSE(d[0].cup_dominates());
        }
    }
    // A faint bend on a plane far from the origin is a shape.
    const Topology t = one_ring(5);
    const std::vector<Complex> z = characteristic_one_ring(t, {}, 5);
    Points P(t.num_vertices(), 3);
    const double k3 = 1e-11;
    for (Index i = 0; i < t.num_vertices(); ++i) {
        const Complex zi = z[static_cast<std::size_t>(i)];
        P.row(i) << zi.real() + 1e3, zi.imag() - 2e3, 0.3 * zi.real() + k3 * std::norm(zi) + 5e2;
    }
    const auto d = decompose_shapes(t, P, {});
    ASSERT_EQ(d.size(), 1u);
    EXPECT_TRUE(d[0].has_quadratic_part);
    EXPECT_NEAR(std::abs(d[0].k3), k3 / std::hypot(1.0, 0.3), 1e-3 * k3);
    EXPECT_EQ(d[0].k4, 0.0);  // the saddle part is rounding: R = +inf, a pure cup
    EXPECT_EQ(d[0].ratio, std::numeric_limits<double>::infinity());
    EXPECT_TRUE(d[0].cup_dominates());
}

TEST(ShapeDecomposition, SaddleDominatesAPureSaddleAndBadInputIsRefused) {
    const Topology t = one_ring(5);
    const std::vector<Complex> z = characteristic_one_ring(t, {}, 5);
    Points P(t.num_vertices(), 3);
    for (Index i = 0; i < t.num_vertices(); ++i) {
        const Complex zi = z[static_cast<std::size_t>(i)];
        P.row(i) << zi.real(), zi.imag(), 0.01 * std::norm(zi) + (zi * zi).real();
    }
    const auto d = decompose_shapes(t, P, {});
    ASSERT_EQ(d.size(), 1u);
    EXPECT_FALSE(d[0].cup_dominates());
    EXPECT_THROW((void)decompose_shapes(t, Points(3, 3), {}), InputError);
    // A neighbour with its own weights breaks the one-ring's closed form.
    TunedWeights both;
    both.set_vertex(0, {13.4575, 0.999938, 0.999938});
    both.set_vertex(1, {13.4575, 0.8, 0.8});
    EXPECT_THROW((void)decompose_shapes(t, P, both), InputError);
}

}  // namespace
}  // namespace limsurf::test
