// Basis functions of the regular patches of subdivision surfaces: the uniform
// bicubic B-spline (regular Catmull–Clark patch), the uniform biquadratic
// B-spline (regular Doo–Sabin patch) and the quartic three-direction box spline
// (regular Loop patch).
//
// Each function writes a 6 × N matrix of weights: column k belongs to control
// point k, rows are the value and the derivatives with respect to the patch
// parameters, in the order of limit_basis.h:
//     row 0 value, 1 ∂s, 2 ∂t, 3 ∂ss, 4 ∂st, 5 ∂tt.
// Applied to control data X (N × d) as w * X they give the surface point and its
// derivatives. The value row sums to 1 and the derivative rows to 0.
//
// The functions are pure, never allocate and never throw. A parameter outside the
// patch domain evaluates the polynomial piece of the patch continued beyond it
// (useful for finite differences at the domain's edge); non-finite parameters give
// non-finite weights.
#pragma once

#include <Eigen/Core>

namespace limsurf {

/// @brief Weights of the uniform bicubic B-spline patch at (s, t).
/// @details Control point k = 4*j + i, i = 0..3 along s, j = 0..3 along t, lies at
///   lattice position (i - 1, j - 1): rows 0-3 at the bottom, 12-15 at the top (the
///   layout of OpenSubdiv's patchBasis.cpp). The domain [0,1]² is the cell spanned by
///   points 5 (0,0), 6 (1,0), 10 (1,1) and 9 (0,1):
///   @code
///   12---13---14---15
///    |    |    |    |
///    8----9---10---11
///    |    | ## |    |
///    4----5----6----7
///    |    |    |    |
///    0----1----2----3
///   @endcode
///   The weight of point (i, j) is B_i(s) B_j(t) with the cubic B-spline pieces
///   B_0 = (1-t)³/6, B_1 = (3t³ - 6t² + 4)/6, B_2 = (-3t³ + 3t² + 3t + 1)/6, B_3 = t³/6.
/// @param[out] w 6 × 16 weights (rows value, ∂s, ∂t, ∂ss, ∂st, ∂tt)
/// @see iga-with-catmull-clark §4 (the regular patch), Stam 1998 "Exact evaluation of
///   Catmull–Clark subdivision surfaces at arbitrary parameter values" §2
void cubic_bspline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 16>& w) noexcept;

/// @brief Weights of the uniform biquadratic B-spline patch at (s, t).
/// @details Control point k = 3*j + i, i = 0..2 along s, j = 0..2 along t, lies at
///   lattice position (i - 1/2, j - 1/2): the domain [0,1]² joins the centres of the
///   four cells of the 3 × 3 net, so (0,0) is the centre of the cell of points 0, 1, 3, 4
///   and (1,1) the centre of the cell of points 4, 5, 7, 8:
///   @code
///   6----7----8
///   |  ##|##  |
///   3----4----5
///   |  ##|##  |
///   0----1----2
///   @endcode
///   The weight of point (i, j) is b_i(s) b_j(t) with the quadratic B-spline pieces
///   b_0 = (1-t)²/2, b_1 = (1 + 2t - 2t²)/2, b_2 = t²/2.
/// @param[out] w 6 × 9 weights (rows value, ∂s, ∂t, ∂ss, ∂st, ∂tt)
/// @see Doo & Sabin 1978 (the regular Doo–Sabin surface is this tensor B-spline)
void quadratic_bspline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 9>& w) noexcept;

/// @brief Weights of the quartic three-direction box spline patch (the regular Loop
///   patch) at (s, t), s, t >= 0, s + t <= 1.
/// @details The 12 control points lie on the triangular lattice; in lattice coordinates
///   (i along s, j along t; the lattice triangles are (0,0),(1,0),(0,1) and
///   (1,0),(1,1),(0,1)):
///   0=(0,-1) 1=(1,-1) 2=(2,-1) 3=(-1,0) 4=(0,0) 5=(1,0) 6=(2,0) 7=(-1,1) 8=(0,1)
///   9=(1,1) 10=(-1,2) 11=(0,2). The patch is the triangle of points 4 (s,t) = (0,0),
///   5 (1,0) and 8 (0,1):
///   @code
///          10-----11
///          . .   . .
///         .   . .   .
///        7-----8-----9
///       . .   . .   . .
///      .   . .   . .   .
///     3-----4-----5-----6
///      .   . .   . .   .
///       . .   . .   . .
///        0-----1-----2
///   @endcode
///   The weights are Stam's quartic polynomials (the layout and the monomial form of
///   OpenSubdiv's patchBasis.cpp). At (0,0) they are 1/2 on point 4 and 1/12 on each of
///   its six neighbours (Loop's limit mask at a regular vertex).
/// @param[out] w 6 × 12 weights (rows value, ∂s, ∂t, ∂ss, ∂st, ∂tt)
/// @param rows  how many leading rows to compute (1, 3 or 6; the others are 0): each computed row
///   is bit for bit the same whatever @p rows is. The weights are half of a warm Loop evaluation,
///   so first derivatives alone should not pay for the second.
/// @see Stam 1998 "Evaluation of Loop subdivision surfaces", appendix
void quartic_box_spline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 12>& w, int rows = 6) noexcept;

/// @brief The same patch applied to its 12 points @p P (12 × 3): value and derivatives (rows as
///   above; the first @p rows computed, the others 0). Equal to w · P up to rounding, at about half
///   the arithmetic: P is contracted with the monomial coefficients first (15 points), and the
///   rows are sums over those instead of over 12 weights each.
void quartic_box_spline_patch_values(double s, double t, const Eigen::Matrix<double, 12, 3>& P,
                                     Eigen::Matrix<double, 6, 3>& out, int rows = 6) noexcept;

}  // namespace limsurf
