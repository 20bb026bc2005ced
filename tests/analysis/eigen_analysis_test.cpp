// The eigen-analysis of schemes against closed forms from the literature, the C2g0 paper's
// spectrum (§2.1, §2.7) and the tuned Catmull–Clark weights' Table 1, plus identities of the
// decomposition itself (blocks against the whole matrix).
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include "limsurf/analysis/eigen_analysis.h"
#include "limsurf/core/error.h"

namespace limsurf::test {
namespace {

/// All eigenvalues with their algebraic multiplicities, by decreasing modulus.
std::vector<std::complex<double>> flatten(const SchemeSpectrum& s) {
    std::vector<std::complex<double>> out;
    for (const EigenvalueEntry& e : s.eigenvalues) {
        for (int i = 0; i < e.algebraic; ++i) {
            out.push_back(e.value);
        }
    }
    return out;
}

SchemeSpectrum analyse(SchemeKind scheme, int valence, bool boundary = false, int rings = 0) {
    EigenRequest r;
    r.scheme = scheme;
    r.valence = valence;
    r.boundary = boundary;
    r.rings = rings;
    return analyse_scheme(r);
}

// The Fourier blocks hold every eigenvalue of S: their union equals the spectrum of S computed
// directly (moduli sorted; dense Eigen solver on the whole matrix).
void expect_blocks_are_the_whole_spectrum(const SchemeSpectrum& s) {
    const auto blocks = flatten(s);
    ASSERT_EQ(static_cast<Index>(blocks.size()), s.S.rows());
    const Eigen::VectorXcd direct = Eigen::EigenSolver<Eigen::MatrixXd>(s.S, false).eigenvalues();
    std::vector<double> a, b;
    for (const auto& z : blocks) {
        a.push_back(std::abs(z));
    }
    for (Index i = 0; i < direct.size(); ++i) {
        b.push_back(std::abs(direct[i]));
    }
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_NEAR(a[i], b[i], 1e-6) << i;  // defective eigenvalues split by ~1e-8 in the direct solve
    }
}

// Every eigenvector satisfies S x = μ x.
void expect_eigenvectors(const SchemeSpectrum& s) {
    const Eigen::MatrixXcd S = s.S.cast<std::complex<double>>();
    for (const EigenvalueEntry& e : s.eigenvalues) {
        ASSERT_EQ(e.eigenvectors.cols(), e.geometric);
        for (Index c = 0; c < e.eigenvectors.cols(); ++c) {
            const Eigen::VectorXcd x = e.eigenvectors.col(c);
            EXPECT_LT((S * x - e.value * x).norm(), 1e-7) << e.value << " frequency " << e.frequency;
        }
    }
}

TEST(EigenAnalysis, CatmullClarkSubdominantIsTheClosedFormAtEveryValence) {
    for (int n = 3; n <= 12; ++n) {
        SCOPED_TRACE("valence " + std::to_string(n));
        const SchemeSpectrum s = analyse(SchemeKind::CatmullClark, n);
        EXPECT_EQ(s.S.rows(), 1 + 6 * n + 0 * n);  // two face rings: 6n + 1 (iga-tuned §2.1: 12n+1 for three)
        EXPECT_NEAR(s.dominant, 1.0, 1e-12);
        EXPECT_NEAR(s.subdominant, catmull_clark_subdominant(n), 1e-12);
        EXPECT_EQ(s.subdominant_multiplicity, 2);
        EXPECT_LT(s.symmetry_residual, 1e-14);
        EXPECT_TRUE(s.c1_spectrum.passed) << s.c1_spectrum.detail;
        ASSERT_TRUE(s.characteristic_map.evaluated) << s.characteristic_map.reason;
        EXPECT_TRUE(s.c1.passed) << s.c1.detail;  // Peters and Reif: Catmull–Clark is C¹ at every valence
        EXPECT_NEAR(s.characteristic_map.winding_number, 1.0, 1e-9);
        expect_blocks_are_the_whole_spectrum(s);
        expect_eigenvectors(s);
        // Peters and Reif (2008): Catmull–Clark's curvature diverges at valences above 4 (the
        // frequency-2 eigenvalue exceeds λ²), tends to zero at 3 (a flat spot: λ² above every
        // other eigenvalue); only the regular case meets (17).
        EXPECT_EQ(s.bounded_curvature.passed, n <= 4) << s.bounded_curvature.detail;
        EXPECT_EQ(s.c2_necessary.passed, n == 4) << s.c2_necessary.detail;
    }
}

TEST(EigenAnalysis, RegularCatmullClarkIsTheBicubicSpectrum) {
    // The bicubic B-spline's subdivision matrix: 1, ½ ×2, ¼ ×3 (quadratic precision), then ⅛.
    const auto values = flatten(analyse(SchemeKind::CatmullClark, 4));
    const double expected[] = {1, 0.5, 0.5, 0.25, 0.25, 0.25, 0.125};
    for (int i = 0; i < 7; ++i) {
        EXPECT_NEAR(std::abs(values[static_cast<std::size_t>(i)]), expected[i], 1e-12) << i;
    }
}

TEST(EigenAnalysis, LoopSubdominantIsTheClosedFormAndItsSquareFollows) {
    for (int n = 3; n <= 12; ++n) {
        SCOPED_TRACE("valence " + std::to_string(n));
        const SchemeSpectrum s = analyse(SchemeKind::Loop, n);
        EXPECT_EQ(s.S.rows(), 1 + 3 * n);
        EXPECT_NEAR(s.subdominant, loop_subdominant(n), 1e-12);
        EXPECT_EQ(s.subdominant_multiplicity, 2);
        EXPECT_TRUE(s.c1.passed) << s.c1.detail;
        // Loop's β is chosen so that the frequency-0 eigenvalue 5/8 − nβ is λ² (Loop 1987).
        bool square_at_zero = false;
        for (const EigenvalueEntry& e : s.eigenvalues) {
            square_at_zero =
                square_at_zero || (e.frequency == 0 && std::abs(e.value - s.subdominant * s.subdominant) < 1e-12);
        }
        EXPECT_TRUE(square_at_zero);
        // Loop's curvature diverges above valence 6 (Loop 1987; Peters and Reif 2008).
        if (n >= 4) {
            EXPECT_EQ(s.bounded_curvature.passed, n <= 6) << s.bounded_curvature.detail;
        }
        expect_blocks_are_the_whole_spectrum(s);
        expect_eigenvectors(s);
    }
}

TEST(EigenAnalysis, RegularBoundariesReproduceWhatTheBoundaryRuleKeeps) {
    // A boundary vertex in two quads (Catmull–Clark) or three triangles (Loop) is regular. The
    // boundary rule makes the boundary the cubic B-spline of the boundary points, so the surface
    // keeps 1, x, y, x², xy (eigenvalues 1, ½ ×2, ¼ ×2) but not y² across the boundary (OpenSubdiv's
    // crease rule has no phantom points): the next eigenvalue is below ¼.
    for (const auto& [scheme, valence] : {std::pair{SchemeKind::CatmullClark, 3}, std::pair{SchemeKind::Loop, 4}}) {
        SCOPED_TRACE(to_string(scheme));
        const SchemeSpectrum s = analyse(scheme, valence, true);
        const auto values = flatten(s);
        const double expected[] = {1, 0.5, 0.5, 0.25, 0.25};
        for (int i = 0; i < 5; ++i) {
            EXPECT_NEAR(std::abs(values[static_cast<std::size_t>(i)]), expected[i], 1e-12) << i;
        }
        EXPECT_LT(std::abs(values[5]), 0.25 - 1e-3);
        EXPECT_TRUE(s.c1_spectrum.passed) << s.c1_spectrum.detail;
        EXPECT_FALSE(s.characteristic_map.evaluated);
        EXPECT_EQ(s.eigenvalues.front().frequency, -1);
        expect_eigenvectors(s);
    }
}

TEST(EigenAnalysis, DooSabinIsItsCirculant) {
    // Doo and Sabin 1978: around an n-gon the new corners are a circulant of the old ones with
    // weights α₀ = 1/4 + 5/(4n), α_i = (3 + 2cos(2πi/n))/(4n): eigenvalues 1, ½ (k = ±1), ¼ (k = ±2), 0.
    for (int n = 3; n <= 9; ++n) {
        SCOPED_TRACE("n-gon " + std::to_string(n));
        const SchemeSpectrum s = analyse(SchemeKind::DooSabin, n, false, 1);
        EXPECT_EQ(s.S.rows(), 4 * n);
        for (int k = 0; k < n; ++k) {
            std::complex<double> circulant = 0.0;
            for (int i = 0; i < n; ++i) {
                const double a = i == 0 ? 0.25 + 5.0 / (4.0 * n)
                                        : (3.0 + 2.0 * std::cos(2.0 * std::numbers::pi * i / n)) / (4.0 * n);
                circulant += a * std::polar(1.0, 2.0 * std::numbers::pi * i * k / n);
            }
            bool found = false;
            for (const EigenvalueEntry& e : s.eigenvalues) {
                found = found || (e.frequency == k && std::abs(e.value - circulant) < 1e-12);
            }
            EXPECT_TRUE(found) << "k = " << k << ": " << circulant;
        }
        EXPECT_NEAR(s.subdominant, 0.5, 1e-12);
        EXPECT_TRUE(s.c1_spectrum.passed) << s.c1_spectrum.detail;
        expect_blocks_are_the_whole_spectrum(s);
    }
}

TEST(EigenAnalysis, C2g0AtValenceThreeIsThePapersSpectrum) {
    // §2.1 and §2.7: 1, 1/4 ×2, 1/16 ×3, every other eigenvalue below 1/16; the paper's weights make
    // the four parameter-dependent eigenvalues vanish; B (the 9×9 block of the third ring) adds
    // 1/32, 1/64, 1/128, each three times.
    const SchemeSpectrum s = analyse(SchemeKind::C2g0, 3);
    ASSERT_EQ(s.S.rows(), 19);
    const auto values = flatten(s);
    const double head[] = {1, 0.25, 0.25, 1.0 / 16, 1.0 / 16, 1.0 / 16};
    for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(values[static_cast<std::size_t>(i)].real(), head[i], 1e-12) << i;
        EXPECT_NEAR(values[static_cast<std::size_t>(i)].imag(), 0.0, 1e-12) << i;
    }
    EXPECT_LT(std::abs(values[6]), 1.0 / 16 - 1e-3);
    EXPECT_TRUE(s.c1_spectrum.passed) << s.c1_spectrum.detail;
    EXPECT_TRUE(s.bounded_curvature.passed) << s.bounded_curvature.detail;
    EXPECT_TRUE(s.c2_necessary.passed) << s.c2_necessary.detail;
    int zeros = 0;
    std::vector<int> zero_blocks;
    int from_b = 0;
    for (const EigenvalueEntry& e : s.eigenvalues) {
        const double m = std::abs(e.value);
        if (m < 1e-6) {
            zeros += e.algebraic;
            zero_blocks.insert(zero_blocks.end(), e.jordan_blocks.begin(), e.jordan_blocks.end());
        }
        for (const double b : {1.0 / 32, 1.0 / 64, 1.0 / 128}) {
            from_b += std::abs(e.value - b) < 1e-9 ? e.algebraic : 0;
        }
    }
    EXPECT_EQ(from_b, 9);
    EXPECT_EQ(zeros, 4);
    std::sort(zero_blocks.rbegin(), zero_blocks.rend());
    // End of §2.7: the zero eigenvalue is defective (the 10×10 M is not diagonalisable).
    EXPECT_EQ(zero_blocks, (std::vector<int>{2, 1, 1}));
    expect_eigenvectors(s);

    // Proposition 2.2(I): the characteristic map is the valence-3 Bers chart, z ↦ z² on each sector
    // mapped affinely to an equilateral triangle: a quadratic polynomial in (u, v) on every face.
    const CharacteristicMap& map = s.characteristic_map;
    ASSERT_TRUE(map.evaluated) << map.reason;
    EXPECT_TRUE(s.c1.passed) << s.c1.detail;
    EXPECT_NEAR(map.winding_number, 1.0, 1e-9);
    const int m = map.resolution;
    const Index per_face = (m + 1) * (m + 2) / 2;
    ASSERT_EQ(map.positions.rows(), 3 * per_face);
    for (Index face = 0; face < 3; ++face) {
        Eigen::MatrixXd basis(per_face, 6);
        Eigen::MatrixXd samples(per_face, 2);
        Index row = 0;
        for (int i = 0; i <= m; ++i) {
            for (int j = 0; j <= m - i; ++j, ++row) {
                const double u = static_cast<double>(i) / m, v = static_cast<double>(j) / m;
                basis.row(row) << 1, u, v, u * u, u * v, v * v;
                samples.row(row) = map.positions.row(face * per_face + row).head<2>();
            }
        }
        const Eigen::MatrixXd fit = basis.colPivHouseholderQr().solve(samples);
        const double residual = (basis * fit - samples).norm() / samples.norm();
        EXPECT_LT(residual, 1e-10) << "face " << face;
    }
}

TEST(EigenAnalysis, C2g0AtValenceSixIsTheBoxSplinesPowersOfOneHalf) {
    // The three-directional box spline reproduces polynomials of degree ≤ 5 ((2.20)): eigenvalues
    // 2^−d with multiplicity d + 1 for d = 0..5 lead the spectrum.
    const SchemeSpectrum s = analyse(SchemeKind::C2g0, 6);
    const auto values = flatten(s);
    std::size_t i = 0;
    for (int d = 0; d <= 3; ++d) {
        for (int m = 0; m <= d; ++m, ++i) {
            EXPECT_NEAR(std::abs(values[i]), std::ldexp(1.0, -d), 1e-10) << "degree " << d;
        }
    }
    EXPECT_TRUE(s.c1.passed) << s.c1.detail;
    EXPECT_TRUE(s.c2_necessary.passed) << s.c2_necessary.detail;
}

TEST(EigenAnalysis, TableOneWeightsGiveThePapersEigenvalues) {
    // iga-tuned-catmull-clark-weights Table 1 (valence 5): λ = 0.550 (cup) and 0.585 (saddle) with
    // α, β, γ read as the vertex's own weights in its vertex, edge and face rules (Fig. 1).
    struct Row {
        VertexRuleWeights w;
        double lambda;
    };
    for (const Row& row : {Row{{13.4575, 0.999938, 0.999938}, 0.550}, Row{{13.9851, 0.824885, 0.824885}, 0.585}}) {
        EigenRequest r;
        r.valence = 5;
        r.weights = row.w;
        const SchemeSpectrum s = analyse_scheme(r);
        EXPECT_NEAR(s.subdominant, row.lambda, 5e-6) << row.w.alpha;  // Table 1 prints 6 digits
        EXPECT_TRUE(s.c1.passed) << s.c1.detail;
        // (30c)/(31c): α is chosen so that λ₃ = λ² (bounded curvature).
        bool square_at_zero = false;
        for (const EigenvalueEntry& e : s.eigenvalues) {
            square_at_zero =
                square_at_zero || (e.frequency == 0 && std::abs(e.value - s.subdominant * s.subdominant) < 1e-4);
        }
        EXPECT_TRUE(square_at_zero) << row.w.alpha;
    }
    // Table 1's "Original": α = 15, β = γ = 1 is Catmull–Clark.
    EigenRequest r;
    r.valence = 5;
    r.weights = VertexRuleWeights{15, 1, 1};
    EXPECT_NEAR(analyse_scheme(r).subdominant, catmull_clark_subdominant(5), 1e-14);
}

// One ring of Catmull–Clark or Loop is invariant and gives the right subdominant eigenvalue, but
// the limit patches at the vertex read two: the characteristic map over one ring (the unknown
// points taken as 0) came out "NOT regular" at every valence, a false verdict. It is now not
// evaluated below the rings it needs, and the same with more rings than it needs.
TEST(EigenAnalysis, TheCharacteristicMapNeedsTheRingsItsPatchesRead) {
    struct Case {
        SchemeKind scheme;
        int valence;
        int too_few;
    };
    for (const Case c : {Case{SchemeKind::CatmullClark, 5, 1}, Case{SchemeKind::CatmullClark, 3, 1},
                         Case{SchemeKind::Loop, 5, 1}, Case{SchemeKind::Loop, 7, 1}, Case{SchemeKind::C2g0, 3, 2}}) {
        const SchemeSpectrum few = analyse(c.scheme, c.valence, false, c.too_few);
        const SchemeSpectrum enough = analyse(c.scheme, c.valence);
        const SchemeSpectrum more = analyse(c.scheme, c.valence, false, enough.rings + 1);
        const std::string name = detail::concat(to_string(c.scheme), " valence ", c.valence);
        EXPECT_NEAR(few.subdominant, enough.subdominant, 1e-12) << name;
        EXPECT_TRUE(few.c1_spectrum.passed) << name;
        EXPECT_FALSE(few.characteristic_map.evaluated) << name;
        EXPECT_NE(few.characteristic_map.reason.find("not evaluated with"), std::string::npos) << name;
        EXPECT_FALSE(few.c1.checked) << name;
        ASSERT_TRUE(enough.characteristic_map.evaluated && more.characteristic_map.evaluated) << name;
        EXPECT_TRUE(enough.c1.passed && more.c1.passed) << name << ": " << enough.c1.detail << " / " << more.c1.detail;
        // The eigenvector is normalised over the neighbourhood, so more rings scale the map: the
        // ratio of the Jacobian's extremes is what does not depend on the rings.
        EXPECT_NEAR(more.characteristic_map.min_jacobian / more.characteristic_map.max_jacobian,
                    enough.characteristic_map.min_jacobian / enough.characteristic_map.max_jacobian, 1e-9)
            << name;
    }
}

TEST(EigenAnalysis, TooFewRingsAndBadRequestsAreRefused) {
    EXPECT_THROW((void)analyse(SchemeKind::C2g0, 3, false, 1), NumericalError);  // the valence-3 rules read 2 rings
    EXPECT_THROW((void)analyse(SchemeKind::C2g0, 5), InputError);
    EXPECT_THROW((void)analyse(SchemeKind::C2g0, 3, true), InputError);
    EXPECT_THROW((void)analyse(SchemeKind::Loop, 2), InputError);
    EXPECT_THROW((void)analyse(SchemeKind::Bilinear, 4), InputError);
    EigenRequest r;
    r.scheme = SchemeKind::Loop;
    r.weights = VertexRuleWeights{1, 1, 1};
    EXPECT_THROW((void)analyse_scheme(r), InputError);
}

}  // namespace
}  // namespace limsurf::test
