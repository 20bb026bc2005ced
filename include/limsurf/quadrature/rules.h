// Quadrature rules on the parameter domains of the limit surface: the unit
// interval, the unit square [0,1]² (Catmull–Clark and Doo–Sabin ptex faces) and
// the triangle u, v >= 0, u + v <= 1 (Loop ptex faces); docs/conventions.md
// "Parameter domains".
//
// A rule is a list of points (u[i], v[i]) and weights weight[i]: ∫ f ≈ Σ weight[i] f(u[i], v[i]).
// The weights sum to the measure of the domain (1 on the interval and the square, 1/2 on
// the triangle); `degree` is the largest d such that the rule integrates every
// polynomial of degree <= d exactly (in each variable for the square, total degree
// for the triangle). All rules here have positive weights and interior points.
#pragma once

#include <vector>

namespace limsurf {

/// Points and weights of a quadrature rule; u, v and weight have the same length.
struct QuadratureRule {
    std::vector<double> u;       ///< first coordinate of each point
    std::vector<double> v;       ///< second coordinate (all 0 for 1D rules)
    std::vector<double> weight;  ///< weight of each point, > 0
    int degree = 0;              ///< exact for polynomials up to this degree

    [[nodiscard]] int num_points() const noexcept { return static_cast<int>(weight.size()); }
};

/// @brief n-point Gauss–Legendre rule on [0, 1], points in increasing order, v all 0.
/// @details Nodes by Newton's iteration on the Legendre polynomial P_n (started from
///   Tricomi's asymptotic guess), weights 2 / ((1 - x²) P_n'(x)²) mapped to [0, 1];
///   the rule is symmetric about 1/2 by construction. Newton's method in double, then three
///   steps in double-double, and one rounding: every node and weight for n <= 64 is correctly
///   rounded, the same bits on every platform (monomials of degree ~100 amplify node errors a
///   hundredfold). degree = 2n - 1.
/// @throws InputError unless 1 <= n <= 64
[[nodiscard]] QuadratureRule gauss_legendre_1d(int n);

/// @brief Tensor Gauss–Legendre rule on [0, 1]² exact for every monomial u^a v^b with
///   a, b <= @p degree.
/// @details n = ceil((degree + 1)/2) points per direction; the point of (i, j) is
///   number n*j + i (i along u). The returned degree is 2n - 1 (>= the request).
/// @throws InputError unless 1 <= degree <= max_square_rule_degree
[[nodiscard]] QuadratureRule square_rule(int degree);

/// The highest degree square_rule() and triangle_rule() provide.
inline constexpr int max_square_rule_degree = 127;
inline constexpr int max_triangle_rule_degree = 60;

/// @brief A rule on the triangle u, v >= 0, u + v <= 1 exact for every polynomial of
///   total degree <= @p degree.
/// @details Degrees 1 to 8 return a tabulated fully symmetric rule (invariant under the
///   six permutations of the barycentric coordinates (1-u-v, u, v)) with positive
///   weights and interior points, exact for exactly that degree:
///   1: the centroid (1 point); 2: 3 points (1/6, 1/6, 2/3); 3: 6 points; 4: Dunavant's 6;
///   5: Radon's 7; 6: Dunavant's 12; 7: 15 points; 8: Dunavant's 16 (Dunavant 1985, "High
///   degree efficient symmetrical Gaussian quadrature rules for the triangle"; his rules of
///   degree 3 and 7 have a negative weight and are not used). The tabulated values were
///   checked against the moment equations in 60-digit arithmetic and are given to 20 digits.
///   Degrees 9 to 60 return a collapsed (Duffy) tensor Gauss–Legendre rule, u = ξ,
///   v = (1-ξ)η with weight (1-ξ) dξ dη, ceil((degree+2)/2) points in ξ and
///   ceil((degree+1)/2) in η: positive weights and interior points, but NOT symmetric
///   (the points crowd towards the vertex (1,0)).
///   The returned degree is the request in every case.
/// @throws InputError unless 1 <= degree <= max_triangle_rule_degree
[[nodiscard]] QuadratureRule triangle_rule(int degree);

}  // namespace limsurf
