#include "limsurf/quadrature/rules.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <span>

#include "limsurf/core/error.h"

namespace limsurf {
namespace detail {
namespace {

/// Orbits of a fully symmetric triangle rule, in barycentric coordinates:
/// S3 the centroid, S21 (a, a, 1-2a) (3 points), S111 (a, b, 1-a-b) (6 points).
enum class Orbit { S3, S21, S111 };

struct OrbitEntry {
    Orbit orbit;
    double a;
    double b;
    double weight;  ///< of each point of the orbit; the weights of a rule sum to 1/2
};

// Published values (see rules.h), solved again from the moment equations
// ∫ u^i v^j = i! j! / (i+j+2)! in 60-digit arithmetic (a Gauss–Newton iteration from
// the published digits; every value moved by less than 1e-16) and rounded to 21 digits.
constexpr OrbitEntry degree1[] = {{Orbit::S3, 0.0, 0.0, 0.5}};
constexpr OrbitEntry degree2[] = {{Orbit::S21, 1.0 / 6.0, 0.0, 1.0 / 6.0}};
constexpr OrbitEntry degree3[] = {
    {Orbit::S21, 0.162882850395891907725, 0.0, 0.140574901220489816747},
    {Orbit::S21, 0.477919883567563687805, 0.0, 0.0260917654461768499199},
};
constexpr OrbitEntry degree4[] = {
    {Orbit::S21, 0.445948490915964886318, 0.0, 0.111690794839005732848},
    {Orbit::S21, 0.0915762135097707434596, 0.0, 0.0549758718276609338192},
};
constexpr OrbitEntry degree5[] = {
    {Orbit::S3, 0.0, 0.0, 0.1125},
    {Orbit::S21, 0.101286507323456338801, 0.0, 0.0629695902724135762978},
    {Orbit::S21, 0.47014206410511508977, 0.0, 0.0661970763942530903688},
};
constexpr OrbitEntry degree6[] = {
    {Orbit::S21, 0.0630890144915022283403, 0.0, 0.0254224531851034084605},
    {Orbit::S21, 0.249286745170910421292, 0.0, 0.0583931378631896830126},
    {Orbit::S111, 0.0531450498448169473532, 0.310352451033784405417, 0.0414255378091867875968},
};
constexpr OrbitEntry degree7[] = {
    {Orbit::S21, 0.0282639241560763237719, 0.0, 0.00676693125783277673021},
    {Orbit::S21, 0.474311323267222575283, 0.0, 0.0394756272160054931459},
    {Orbit::S21, 0.241143325849848808871, 0.0, 0.0643039639094530383376},
    {Orbit::S111, 0.761222748024523819072, 0.0462708777988089082457, 0.0280600721416876792264},
};
constexpr OrbitEntry degree8[] = {
    {Orbit::S3, 0.0, 0.0, 0.0721578038388935841255},
    {Orbit::S21, 0.170569307751760206622, 0.0, 0.0516086852673591251409},
    {Orbit::S21, 0.0505472283170309754584, 0.0, 0.0162292488115990401555},
    {Orbit::S21, 0.459292588292723156029, 0.0, 0.0475458171336423123969},
    {Orbit::S111, 0.263112829634638113422, 0.00839477740995760533721, 0.0136151570872174971324},
};

constexpr int max_tabulated_triangle_degree = 8;

std::span<const OrbitEntry> tabulated_triangle_rule(int degree) {
    switch (degree) {
    case 1:
        return degree1;
    case 2:
        return degree2;
    case 3:
        return degree3;
    case 4:
        return degree4;
    case 5:
        return degree5;
    case 6:
        return degree6;
    case 7:
        return degree7;
    default:
        return degree8;
    }
}

void add_point(QuadratureRule& rule, double u, double v, double weight) {
    rule.u.push_back(u);
    rule.v.push_back(v);
    rule.weight.push_back(weight);
}

QuadratureRule expand_orbits(std::span<const OrbitEntry> orbits, int degree) {
    QuadratureRule rule;
    rule.degree = degree;
    for (const OrbitEntry& o : orbits) {
        switch (o.orbit) {
        case Orbit::S3:
            add_point(rule, 1.0 / 3.0, 1.0 / 3.0, o.weight);
            break;
        case Orbit::S21: {
            const double c = 1.0 - 2.0 * o.a;
            add_point(rule, o.a, o.a, o.weight);
            add_point(rule, c, o.a, o.weight);
            add_point(rule, o.a, c, o.weight);
            break;
        }
        case Orbit::S111: {
            const double c = 1.0 - o.a - o.b;
            add_point(rule, o.a, o.b, o.weight);
            add_point(rule, o.b, o.a, o.weight);
            add_point(rule, o.a, c, o.weight);
            add_point(rule, c, o.a, o.weight);
            add_point(rule, o.b, c, o.weight);
            add_point(rule, c, o.b, o.weight);
            break;
        }
        }
    }
    return rule;
}

/// A double-double number hi + lo, |lo| ≤ ulp(hi) / 2: 106 bits from double arithmetic alone
/// (Dekker; Hida, Li & Bailey's QD library). Each product's rounding error comes from std::fma,
/// which the C++ standard requires to round once, so these are exact transformations on every
/// IEEE platform whatever the width of long double.
struct DoubleDouble {
    double hi = 0.0;
    double lo = 0.0;
};

DoubleDouble two_sum(double a, double b) {
    const double s = a + b;
    const double bb = s - a;
    return {s, (a - (s - bb)) + (b - bb)};
}

DoubleDouble quick_two_sum(double a, double b) {  // |a| ≥ |b|
    const double s = a + b;
    return {s, b - (s - a)};
}

DoubleDouble operator+(DoubleDouble x, DoubleDouble y) {
    const DoubleDouble s = two_sum(x.hi, y.hi);
    const DoubleDouble t = two_sum(x.lo, y.lo);
    DoubleDouble r = quick_two_sum(s.hi, s.lo + t.hi);
    return quick_two_sum(r.hi, r.lo + t.lo);
}

DoubleDouble operator-(DoubleDouble x) {
    return {-x.hi, -x.lo};
}

DoubleDouble operator-(DoubleDouble x, DoubleDouble y) {
    return x + -y;
}

DoubleDouble operator*(DoubleDouble x, DoubleDouble y) {
    const double p = x.hi * y.hi;
    const double e = std::fma(x.hi, y.hi, -p);
    return quick_two_sum(p, e + (x.hi * y.lo + x.lo * y.hi));
}

DoubleDouble operator/(DoubleDouble x, DoubleDouble y) {
    // Long division: three quotient digits, each from the remainder of the last.
    const double q1 = x.hi / y.hi;
    DoubleDouble r = x - y * DoubleDouble{q1};
    const double q2 = r.hi / y.hi;
    r = r - y * DoubleDouble{q2};
    const double q3 = r.hi / y.hi;
    const DoubleDouble q = quick_two_sum(q1, q2);
    return q + DoubleDouble{q3};
}

DoubleDouble dd(double v) {
    return {v, 0.0};
}

/// P_n(z) and P_n'(z) by the three-term recurrence, in double-double.
void legendre(int n, DoubleDouble z, DoubleDouble& p, DoubleDouble& dp) {
    DoubleDouble p0 = dd(1.0);
    DoubleDouble p1 = z;
    for (int k = 2; k <= n; ++k) {
        const DoubleDouble p2 = (dd(2.0 * k - 1.0) * z * p1 - dd(k - 1.0) * p0) / dd(k);
        p0 = p1;
        p1 = p2;
    }
    p = p1;
    dp = dd(n) * (z * p1 - p0) / (z * z - dd(1.0));
}

/// Gauss–Legendre nodes mapped to [0, 1] (increasing) and their weights on [0, 1], each the
/// correctly rounded double of the exact value (checked against 40-digit references in
/// tests/quadrature/rules_test.cpp). Newton's method in double finds each root of P_n to a few
/// ulps, three more steps in double-double take it to ~1e-32, and the node (1 − z)/2, the weight
/// 1/((1 − z²) P_n'(z)²) are formed in double-double and rounded once: the nodes near 0 are
/// (1 − z)/2 with z close to 1, which would lose digits in double, and monomials of degree ~100
/// amplify any error in the nodes a hundredfold. Until 2026-12-05 this ran in long double, which
/// is x87's 64-bit significand on x86-64 (29 of the 4 160 values for n ≤ 64 one ulp off, from
/// n = 11 on), 113 bits on AArch64 Linux and plain double on MSVC and macOS on Apple silicon —
/// other digits on other machines; now every platform gets the same bits.
void gauss_legendre_unit(int n, std::vector<double>& u, std::vector<double>& w) {
    u.assign(static_cast<std::size_t>(n), 0.0);
    w.assign(static_cast<std::size_t>(n), 0.0);
    const double pi = std::numbers::pi;
    for (int i = 0; i < (n + 1) / 2; ++i) {
        DoubleDouble z;
        DoubleDouble p;
        DoubleDouble dp;
        if (2 * i + 1 == n) {
            z = dd(0.0);  // the middle node, exactly
        } else {
            // the i-th largest root; Tricomi's first-order guess lies in the basin of Newton's method
            double guess = std::cos(pi * (i + 0.75) / (n + 0.5));
            for (int iteration = 0; iteration < 100; ++iteration) {
                legendre(n, dd(guess), p, dp);
                const double step = p.hi / dp.hi;
                guess -= step;
                if (std::abs(step) <= 4.0 * std::numeric_limits<double>::epsilon()) {
                    break;
                }
            }
            z = dd(guess);
            for (int iteration = 0; iteration < 3; ++iteration) {  // quadratic: 1e-16 → 1e-32 and beyond
                legendre(n, z, p, dp);
                z = z - p / dp;
            }
        }
        legendre(n, z, p, dp);
        const DoubleDouble weight = dd(1.0) / ((dd(1.0) - z * z) * dp * dp);  // half of the weight on [-1, 1]
        const DoubleDouble lo = (dd(1.0) - z) * dd(0.5);
        const DoubleDouble hi = (dd(1.0) + z) * dd(0.5);
        u[static_cast<std::size_t>(i)] = lo.hi + lo.lo;
        u[static_cast<std::size_t>(n - 1 - i)] = hi.hi + hi.lo;
        w[static_cast<std::size_t>(i)] = weight.hi + weight.lo;
        w[static_cast<std::size_t>(n - 1 - i)] = weight.hi + weight.lo;
    }
}

}  // namespace
}  // namespace detail

QuadratureRule gauss_legendre_1d(int n) {
    LIMSURF_CHECK(n >= 1 && n <= 64, InputError, "gauss_legendre_1d: number of points ", n, " is outside [1, 64]");
    QuadratureRule rule;
    rule.degree = 2 * n - 1;
    detail::gauss_legendre_unit(n, rule.u, rule.weight);
    rule.v.assign(rule.u.size(), 0.0);
    return rule;
}

QuadratureRule square_rule(int degree) {
    LIMSURF_CHECK(degree >= 1 && degree <= max_square_rule_degree, InputError,
                  "the quadrature rule on the square: degree ", degree, " is outside [1, ", max_square_rule_degree,
                  "]");
    const QuadratureRule line = gauss_legendre_1d((degree + 2) / 2);
    const std::size_t n = line.u.size();
    QuadratureRule rule;
    rule.degree = line.degree;
    rule.u.reserve(n * n);
    rule.v.reserve(n * n);
    rule.weight.reserve(n * n);
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < n; ++i) {
            detail::add_point(rule, line.u[i], line.u[j], line.weight[i] * line.weight[j]);
        }
    }
    return rule;
}

QuadratureRule triangle_rule(int degree) {
    LIMSURF_CHECK(degree >= 1 && degree <= max_triangle_rule_degree, InputError,
                  "the quadrature rule on the triangle: degree ", degree, " is outside [1, ", max_triangle_rule_degree,
                  "]");
    if (degree <= detail::max_tabulated_triangle_degree) {
        return detail::expand_orbits(detail::tabulated_triangle_rule(degree), degree);
    }
    // Collapsed square: u^a v^b on the triangle is ξ^a (1-ξ)^(b+1) η^b dξ dη, of degree
    // <= degree + 1 in ξ and <= degree in η.
    const QuadratureRule xi = gauss_legendre_1d((degree + 3) / 2);
    const QuadratureRule eta = gauss_legendre_1d((degree + 2) / 2);
    QuadratureRule rule;
    rule.degree = degree;
    for (std::size_t j = 0; j < eta.u.size(); ++j) {
        for (std::size_t i = 0; i < xi.u.size(); ++i) {
            const double one_minus_xi = 1.0 - xi.u[i];
            detail::add_point(rule, xi.u[i], one_minus_xi * eta.u[j], xi.weight[i] * eta.weight[j] * one_minus_xi);
        }
    }
    return rule;
}

}  // namespace limsurf
