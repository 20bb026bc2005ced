#include "limsurf/limit/patch_basis.h"

#include <algorithm>

namespace limsurf {
namespace detail {
namespace {

/// Values and first and second derivatives of the 1D basis pieces at one parameter.
template <int n>
struct Basis1d {
    double b[n];
    double d[n];
    double dd[n];
};

Basis1d<4> cubic_bspline_1d(double t) noexcept {
    const double tc = 1.0 - t;
    const double t2 = t * t;
    Basis1d<4> r{};
    r.b[0] = tc * tc * tc / 6.0;
    r.b[1] = (3.0 * t2 * t - 6.0 * t2 + 4.0) / 6.0;
    r.b[2] = (-3.0 * t2 * t + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    r.b[3] = t2 * t / 6.0;
    r.d[0] = -0.5 * tc * tc;
    r.d[1] = 1.5 * t2 - 2.0 * t;
    r.d[2] = -1.5 * t2 + t + 0.5;
    r.d[3] = 0.5 * t2;
    r.dd[0] = tc;
    r.dd[1] = 3.0 * t - 2.0;
    r.dd[2] = 1.0 - 3.0 * t;
    r.dd[3] = t;
    return r;
}

Basis1d<3> quadratic_bspline_1d(double t) noexcept {
    const double tc = 1.0 - t;
    Basis1d<3> r{};
    r.b[0] = 0.5 * tc * tc;
    r.b[1] = 0.5 + t * tc;
    r.b[2] = 0.5 * t * t;
    r.d[0] = -tc;
    r.d[1] = 1.0 - 2.0 * t;
    r.d[2] = t;
    r.dd[0] = 1.0;
    r.dd[1] = -2.0;
    r.dd[2] = 1.0;
    return r;
}

/// Tensor product of two 1D bases; column 4*j + i (n = 4) or 3*j + i (n = 3).
template <int n>
void tensor_weights(const Basis1d<n>& bs, const Basis1d<n>& bt, Eigen::Matrix<double, 6, n * n>& w) noexcept {
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const int k = n * j + i;
            w(0, k) = bs.b[i] * bt.b[j];
            w(1, k) = bs.d[i] * bt.b[j];
            w(2, k) = bs.b[i] * bt.d[j];
            w(3, k) = bs.dd[i] * bt.b[j];
            w(4, k) = bs.d[i] * bt.d[j];
            w(5, k) = bs.b[i] * bt.dd[j];
        }
    }
}

/// Exponents (a, b) of the 15 monomials s^a t^b of total degree <= 4, in the order
/// 1, s, t, s², st, t², s³, s²t, st², t³, s⁴, s³t, s²t², st³, t⁴.
constexpr int monomial_exponents[15][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}, {3, 0}, {2, 1},
                                           {1, 2}, {0, 3}, {4, 0}, {3, 1}, {2, 2}, {1, 3}, {0, 4}};

/// 12 × Stam's quartic box-spline basis functions in the monomials above (one row per
/// control point; the coefficient table of OpenSubdiv's patchBasis.cpp comments).
constexpr int box_spline_coefficients[12][15] = {
    {1, -2, -4, 0, 6, 6, 2, 0, -6, -4, -1, -2, 0, 2, 1},
    {1, 2, -2, 0, -6, 0, -4, 0, 6, 2, 2, 4, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -1, -2, 0, 0, 0},
    {1, -4, -2, 6, 6, 0, -4, -6, 0, 2, 1, 2, 0, -2, -1},
    {6, 0, 0, -12, -12, -12, 8, 12, 12, 8, -1, -2, 0, -2, -1},
    {1, 4, 2, 6, 6, 0, -4, -6, -12, -4, -1, -2, 0, 4, 2},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 2, 0, 0, 0},
    {1, -2, 2, 0, -6, 0, 2, 6, 0, -4, -1, -2, 0, 4, 2},
    {1, 2, 4, 0, 6, 6, -4, -12, -6, -4, 2, 4, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 2, 6, 6, 2, -1, -2, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, -2, -1},
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 1},
};

/// Derivative orders (∂s, ∂t) of the six output rows.
constexpr int row_orders[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};

/// a (a-1) ... (a-k+1), the factor that k derivatives bring down from x^a (0 when k > a).
constexpr double falling_factorial(int a, int k) noexcept {
    double r = 1.0;
    for (int i = 0; i < k; ++i) {
        r *= a - i;
    }
    return r;
}

}  // namespace
}  // namespace detail

void cubic_bspline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 16>& w) noexcept {
    detail::tensor_weights<4>(detail::cubic_bspline_1d(s), detail::cubic_bspline_1d(t), w);
}

void quadratic_bspline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 9>& w) noexcept {
    detail::tensor_weights<3>(detail::quadratic_bspline_1d(s), detail::quadratic_bspline_1d(t), w);
}

namespace detail {
namespace {

/// The coefficient matrix of box_spline_coefficients as a fixed-size Eigen matrix (scaled by
/// 1/12; one row per monomial), built once.
const Eigen::Matrix<double, 15, 12, Eigen::RowMajor>& box_spline_matrix() {
    static const Eigen::Matrix<double, 15, 12, Eigen::RowMajor> coefficients = [] {
        Eigen::Matrix<double, 15, 12, Eigen::RowMajor> c;
        for (int k = 0; k < 12; ++k) {
            for (int m = 0; m < 15; ++m) {
                c(m, k) = box_spline_coefficients[k][m] / 12.0;
            }
        }
        return c;
    }();
    return coefficients;
}

/// Derivative row r of monomial m is factor[r][m] · s^ea[r][m] · t^eb[r][m] (factor 0 where the
/// derivative vanishes), tabulated at compile time.
struct MonomialTable {
    double factor[6][15];
    int ea[6][15];
    int eb[6][15];
};
constexpr MonomialTable monomial_table = [] {
    MonomialTable tb{};
    for (int r = 0; r < 6; ++r) {
        const int ds = row_orders[r][0];
        const int dt = row_orders[r][1];
        for (int m = 0; m < 15; ++m) {
            const int a = monomial_exponents[m][0];
            const int b = monomial_exponents[m][1];
            const bool vanishes = ds > a || dt > b;
            tb.factor[r][m] = vanishes ? 0.0 : falling_factorial(a, ds) * falling_factorial(b, dt);
            tb.ea[r][m] = vanishes ? 0 : a - ds;
            tb.eb[r][m] = vanishes ? 0 : b - dt;
        }
    }
    return tb;
}();

/// The first Rows rows of monomial_rows: fully unrolled over a compile-time table, so every
/// power is a register and every factor a constant.
template <int Rows>
void fill_monomial_rows(const double (&ps)[5], const double (&pt)[5], Eigen::Matrix<double, 6, 15>& d) {
#pragma GCC unroll 15
    for (int m = 0; m < 15; ++m) {
#pragma GCC unroll 6
        for (int r = 0; r < Rows; ++r) {
            d(r, m) = monomial_table.factor[r][m] * ps[monomial_table.ea[r][m]] * pt[monomial_table.eb[r][m]];
        }
    }
}

/// The first @p rows (1, 3 or 6) derivative rows of the 15 monomials at (s, t).
Eigen::Matrix<double, 6, 15> monomial_rows(double s, double t, int rows) {
    const double ps[5] = {1.0, s, s * s, s * s * s, s * s * s * s};
    const double pt[5] = {1.0, t, t * t, t * t * t, t * t * t * t};
    Eigen::Matrix<double, 6, 15> d;
    if (rows <= 1) {
        fill_monomial_rows<1>(ps, pt, d);
    } else if (rows <= 3) {
        fill_monomial_rows<3>(ps, pt, d);
    } else {
        fill_monomial_rows<6>(ps, pt, d);
    }
    return d;
}

}  // namespace
}  // namespace detail

void quartic_box_spline_patch_weights(double s, double t, Eigen::Matrix<double, 6, 12>& w, int rows) noexcept {
    rows = std::clamp(rows, 1, 6);
    const Eigen::Matrix<double, 15, 12, Eigen::RowMajor>& coefficients = detail::box_spline_matrix();
    const Eigen::Matrix<double, 6, 15> d = detail::monomial_rows(s, t, rows);
    // Row-major accumulation: up to 90 AXPYs of length 12 (vectorised), cheaper than a general
    // product; each row sums its monomials in the same order whatever `rows` is.
    Eigen::Matrix<double, 6, 12, Eigen::RowMajor> sum = Eigen::Matrix<double, 6, 12, Eigen::RowMajor>::Zero();
    for (int m = 0; m < 15; ++m) {
        for (int r = 0; r < rows; ++r) {
            if (d(r, m) != 0.0) {
                sum.row(r) += d(r, m) * coefficients.row(m);
            }
        }
    }
    w = sum;
}

void quartic_box_spline_patch_values(double s, double t, const Eigen::Matrix<double, 12, 3>& P,
                                     Eigen::Matrix<double, 6, 3>& out, int rows) noexcept {
    rows = std::clamp(rows, 1, 6);
    // The patch as a polynomial: its 15 monomial coefficients (each a point), then the rows. (A loop
    // over the 108 non-zero coefficients only measured slower than this unrolled product.)
    const Eigen::Matrix<double, 15, 3> Q = detail::box_spline_matrix().lazyProduct(P);
    const Eigen::Matrix<double, 6, 15> d = detail::monomial_rows(s, t, rows);
    out.setZero();
    for (int m = 0; m < 15; ++m) {
        for (int r = 0; r < rows; ++r) {
            if (d(r, m) != 0.0) {
                out.row(r) += d(r, m) * Q.row(m);
            }
        }
    }
}

}  // namespace limsurf
