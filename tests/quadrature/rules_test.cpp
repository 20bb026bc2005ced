// Quadrature rules: exactness on every monomial up to the degree, the weight sums,
// positivity and interior points, symmetry of the tabulated triangle rules, that the
// degree is not overstated, and Gauss–Legendre's values correctly rounded.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/quadrature/rules.h"
#include "support/paths.h"

namespace limsurf {
namespace {

// ∫ u^a v^b over the unit square and over the triangle u, v >= 0, u + v <= 1.
double square_moment(int a, int b) {
    return 1.0 / ((a + 1.0) * (b + 1.0));
}

double triangle_moment(int a, int b) {
    double r = 1.0;  // a! b! / (a+b)!
    for (int i = 1; i <= b; ++i) {
        r *= static_cast<double>(i) / (a + i);
    }
    return r / ((a + b + 1.0) * (a + b + 2.0));
}

// Powers u^0..u^max of every point, to keep the exhaustive checks cheap.
std::vector<std::vector<double>> powers(const std::vector<double>& x, int max) {
    std::vector<std::vector<double>> p(x.size(), std::vector<double>(static_cast<std::size_t>(max) + 1, 1.0));
    for (std::size_t i = 0; i < x.size(); ++i) {
        for (int k = 1; k <= max; ++k) {
            p[i][static_cast<std::size_t>(k)] = p[i][static_cast<std::size_t>(k) - 1] * x[i];
        }
    }
    return p;
}

struct MonomialCheck {
    double worst_relative_error = 0.0;
    int a = -1;
    int b = -1;
};

// The largest relative error over the monomials u^a v^b selected by `take(a, b)`.
template <class Take, class Moment>
MonomialCheck check_monomials(const QuadratureRule& rule, int max, Take take, Moment moment) {
    const auto U = powers(rule.u, max);
    const auto V = powers(rule.v, max);
    MonomialCheck worst;
    for (int a = 0; a <= max; ++a) {
        for (int b = 0; b <= max; ++b) {
            if (!take(a, b)) {
                continue;
            }
            double sum = 0.0;
            for (std::size_t i = 0; i < rule.weight.size(); ++i) {
                sum += rule.weight[i] * U[i][static_cast<std::size_t>(a)] * V[i][static_cast<std::size_t>(b)];
            }
            const double exact = moment(a, b);
            const double error = std::abs(sum - exact) / exact;
            if (error > worst.worst_relative_error) {
                worst = {error, a, b};
            }
        }
    }
    return worst;
}

void expect_well_formed(const QuadratureRule& rule, double area) {
    ASSERT_EQ(rule.u.size(), rule.weight.size());
    ASSERT_EQ(rule.v.size(), rule.weight.size());
    ASSERT_GT(rule.num_points(), 0);
    double sum = 0.0;
    for (const double w : rule.weight) {
        EXPECT_GT(w, 0.0);
        sum += w;
    }
    EXPECT_NEAR(sum, area, 1e-14 * area);
}

TEST(QuadratureRules, GaussLegendreIsExactToDegree2nMinus1) {
    for (int n = 1; n <= 64; ++n) {
        SCOPED_TRACE(testing::Message() << "n = " << n);
        const QuadratureRule rule = gauss_legendre_1d(n);
        ASSERT_EQ(rule.num_points(), n);
        EXPECT_EQ(rule.degree, 2 * n - 1);
        expect_well_formed(rule, 1.0);
        for (int i = 0; i < n; ++i) {
            const auto k = static_cast<std::size_t>(i);
            const auto mirror = static_cast<std::size_t>(n - 1 - i);
            EXPECT_GT(rule.u[k], 0.0);
            EXPECT_LT(rule.u[k], 1.0);
            EXPECT_EQ(rule.v[k], 0.0);
            if (i > 0) {
                EXPECT_GT(rule.u[k], rule.u[k - 1]);
            }
            EXPECT_NEAR(rule.u[k] + rule.u[mirror], 1.0, 1e-15);
            EXPECT_EQ(rule.weight[k], rule.weight[mirror]);
        }
        const auto exact = check_monomials(
            rule, 2 * n - 1, [](int, int b) { return b == 0; }, square_moment);
        EXPECT_LT(exact.worst_relative_error, 1e-14) << "u^" << exact.a;
        // the next degree is not integrated (visible in double precision for small n only)
        if (n <= 5) {
            const QuadratureRule& r = rule;
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                sum += r.weight[static_cast<std::size_t>(i)] * std::pow(r.u[static_cast<std::size_t>(i)], 2 * n);
            }
            EXPECT_GT(std::abs(sum - 1.0 / (2 * n + 1)) * (2 * n + 1), 1e-12);
        }
    }
}

TEST(QuadratureRules, GaussLegendreKnownValues) {
    const QuadratureRule two = gauss_legendre_1d(2);
    EXPECT_NEAR(two.u[0], 0.5 - 0.5 / std::sqrt(3.0), 1e-16);
    EXPECT_DOUBLE_EQ(two.weight[0], 0.5);
    const QuadratureRule three = gauss_legendre_1d(3);
    EXPECT_NEAR(three.u[0], 0.5 - 0.5 * std::sqrt(0.6), 1e-16);
    EXPECT_EQ(three.u[1], 0.5);
    EXPECT_DOUBLE_EQ(three.weight[0], 5.0 / 18.0);
    EXPECT_DOUBLE_EQ(three.weight[1], 8.0 / 18.0);
}

// Every node and weight is the double nearest the exact value: 40-digit references from an
// independent computation (tools/gauss_legendre_reference.py: mpmath's Legendre functions at 60
// digits), read by strtod, which rounds correctly. The sizes are those where the earlier long-double
// computation was one ulp off on x86-64 (n = 11, 29) and the largest (64).
TEST(QuadratureRules, GaussLegendreIsCorrectlyRounded) {
    std::ifstream file(test::test_data_dir() / "quadrature" / "gauss_legendre_40_digits.txt");
    ASSERT_TRUE(file) << "tests/data/quadrature/gauss_legendre_40_digits.txt";
    std::string line;
    int checked = 0;
    int rule_size = 0;
    QuadratureRule rule;
    while (std::getline(file, line)) {
        if (line.empty() || line[0] == '#') {
            continue;
        }
        std::istringstream fields(line);
        int n = 0;
        int i = 0;
        std::string node;
        std::string weight;
        ASSERT_TRUE(fields >> n >> i >> node >> weight) << line;
        if (n != rule_size) {
            rule = gauss_legendre_1d(n);
            rule_size = n;
        }
        const auto k = static_cast<std::size_t>(i);
        EXPECT_EQ(rule.u[k], std::strtod(node.c_str(), nullptr)) << "node " << i << " of " << n;
        EXPECT_EQ(rule.weight[k], std::strtod(weight.c_str(), nullptr)) << "weight " << i << " of " << n;
        ++checked;
    }
    EXPECT_EQ(checked, 11 + 29 + 64);
}

TEST(QuadratureRules, SquareRuleIsExactOnEveryMonomialUpToTheDegree) {
    for (const int degree : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 20, 31, 64, 127}) {
        SCOPED_TRACE(testing::Message() << "degree " << degree);
        const QuadratureRule rule = square_rule(degree);
        EXPECT_GE(rule.degree, degree);
        EXPECT_LE(rule.degree, degree + 1);
        const int n = (rule.degree + 1) / 2;
        EXPECT_EQ(rule.num_points(), n * n);
        expect_well_formed(rule, 1.0);
        for (int i = 0; i < rule.num_points(); ++i) {
            const auto k = static_cast<std::size_t>(i);
            EXPECT_TRUE(rule.u[k] > 0.0 && rule.u[k] < 1.0 && rule.v[k] > 0.0 && rule.v[k] < 1.0);
        }
        const auto exact = check_monomials(
            rule, rule.degree, [](int, int) { return true; }, square_moment);
        EXPECT_LT(exact.worst_relative_error, 1e-14) << "u^" << exact.a << " v^" << exact.b;
    }
}

// Point (u, v) of the rule, looked up with the same weight.
bool contains(const QuadratureRule& rule, double u, double v, double weight) {
    for (int i = 0; i < rule.num_points(); ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (std::abs(rule.u[k] - u) < 1e-15 && std::abs(rule.v[k] - v) < 1e-15 &&
            std::abs(rule.weight[k] - weight) < 1e-17) {
            return true;
        }
    }
    return false;
}

TEST(QuadratureRules, TabulatedTriangleRulesAreSymmetricPositiveAndInterior) {
    const int expected_points[9] = {0, 1, 3, 6, 6, 7, 12, 15, 16};
    for (int degree = 1; degree <= 8; ++degree) {
        SCOPED_TRACE(testing::Message() << "degree " << degree);
        const QuadratureRule rule = triangle_rule(degree);
        EXPECT_EQ(rule.degree, degree);
        EXPECT_EQ(rule.num_points(), expected_points[degree]);
        expect_well_formed(rule, 0.5);
        for (int i = 0; i < rule.num_points(); ++i) {
            const auto k = static_cast<std::size_t>(i);
            const double b[3] = {1.0 - rule.u[k] - rule.v[k], rule.u[k], rule.v[k]};
            EXPECT_TRUE(b[0] > 0.0 && b[1] > 0.0 && b[2] > 0.0) << "point " << i << " is not interior";
            // all six permutations of the barycentric coordinates are points of the rule
            int perm[3] = {0, 1, 2};
            do {
                EXPECT_TRUE(contains(rule, b[perm[1]], b[perm[2]], rule.weight[k]))
                    << "point " << i << " (" << rule.u[k] << ", " << rule.v[k] << ") permuted (" << perm[0] << perm[1]
                    << perm[2] << ") is missing";
            } while (std::next_permutation(perm, perm + 3));
        }
    }
}

TEST(QuadratureRules, TriangleRulesAreExactUpToTheDegree) {
    for (int degree = 1; degree <= 60; ++degree) {
        SCOPED_TRACE(testing::Message() << "degree " << degree);
        const QuadratureRule rule = triangle_rule(degree);
        EXPECT_EQ(rule.degree, degree);
        expect_well_formed(rule, 0.5);
        for (int i = 0; i < rule.num_points(); ++i) {
            const auto k = static_cast<std::size_t>(i);
            EXPECT_TRUE(rule.u[k] > 0.0 && rule.v[k] > 0.0 && rule.u[k] + rule.v[k] < 1.0) << "point " << i;
        }
        const auto exact = check_monomials(
            rule, degree, [degree](int a, int b) { return a + b <= degree; }, triangle_moment);
        EXPECT_LT(exact.worst_relative_error, 1e-14) << "u^" << exact.a << " v^" << exact.b;
    }
}

TEST(QuadratureRules, TabulatedTriangleRulesDoNotOverstateTheirDegree) {
    for (int degree = 1; degree <= 8; ++degree) {
        const QuadratureRule rule = triangle_rule(degree);
        const auto next = check_monomials(
            rule, degree + 1, [degree](int a, int b) { return a + b == degree + 1; }, triangle_moment);
        EXPECT_GT(next.worst_relative_error, 1e-6) << "degree " << degree << " rule is exact at degree " << degree + 1;
    }
}

TEST(QuadratureRules, RefusesOutOfRangeArguments) {
    EXPECT_THROW((void)gauss_legendre_1d(0), InputError);
    EXPECT_THROW((void)gauss_legendre_1d(65), InputError);
    EXPECT_THROW((void)square_rule(0), InputError);
    EXPECT_THROW((void)square_rule(128), InputError);
    EXPECT_THROW((void)triangle_rule(0), InputError);
    EXPECT_THROW((void)triangle_rule(-3), InputError);
    EXPECT_THROW((void)triangle_rule(61), InputError);
    EXPECT_NO_THROW((void)triangle_rule(60));
    EXPECT_NO_THROW((void)square_rule(127));
}

}  // namespace
}  // namespace limsurf
