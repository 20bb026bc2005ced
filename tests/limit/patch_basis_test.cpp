// The regular patch bases: partition of unity, derivatives against finite
// differences, polynomial reproduction, known values, and — the independent
// witness — exact agreement with the patches of the uniformly subdivided net
// (Catmull–Clark / Chaikin / Loop rules on the regular lattice, written here by hand).
#include <cmath>
#include <functional>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "limsurf/limit/patch_basis.h"

namespace limsurf {
namespace {

template <int n>
using Weights = Eigen::Matrix<double, 6, n>;

template <int n>
using Basis = std::function<void(double, double, Weights<n>&)>;

const Basis<16> cubic = [](double s, double t, Weights<16>& w) { cubic_bspline_patch_weights(s, t, w); };
const Basis<9> quadratic = [](double s, double t, Weights<9>& w) { quadratic_bspline_patch_weights(s, t, w); };
const Basis<12> quartic = [](double s, double t, Weights<12>& w) { quartic_box_spline_patch_weights(s, t, w); };

// Lattice positions of the control points (header documentation), in the patch's (s, t).
std::vector<Eigen::Vector2d> cubic_positions() {
    std::vector<Eigen::Vector2d> p;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            p.emplace_back(i - 1.0, j - 1.0);
        }
    }
    return p;
}

std::vector<Eigen::Vector2d> quadratic_positions() {
    std::vector<Eigen::Vector2d> p;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            p.emplace_back(i - 0.5, j - 0.5);
        }
    }
    return p;
}

const int box_lattice[12][2] = {{0, -1}, {1, -1}, {2, -1}, {-1, 0}, {0, 0},  {1, 0},
                                {2, 0},  {-1, 1}, {0, 1},  {1, 1},  {-1, 2}, {0, 2}};

std::vector<Eigen::Vector2d> quartic_positions() {
    std::vector<Eigen::Vector2d> p;
    for (const auto& ij : box_lattice) {
        p.emplace_back(ij[0], ij[1]);
    }
    return p;
}

// Random points of the square (triangle = false) or the triangle s, t >= 0, s + t <= 1.
std::vector<Eigen::Vector2d> sample_points(bool triangle, int count, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Eigen::Vector2d> points;
    while (static_cast<int>(points.size()) < count) {
        const Eigen::Vector2d p(unit(random), unit(random));
        if (!triangle || p.sum() < 1.0) {
            points.push_back(p);
        }
    }
    // the corners and edge midpoints too
    points.emplace_back(0.0, 0.0);
    points.emplace_back(1.0, 0.0);
    points.emplace_back(0.0, 1.0);
    points.emplace_back(0.5, 0.5);
    if (!triangle) {
        points.emplace_back(1.0, 1.0);
    }
    return points;
}

template <int n>
void expect_partition_of_unity(const Basis<n>& basis, bool triangle) {
    Weights<n> w;
    for (const auto& p : sample_points(triangle, 200, 1)) {
        basis(p.x(), p.y(), w);
        EXPECT_NEAR(w.row(0).sum(), 1.0, 1e-14) << "at " << p.transpose();
        for (int r = 1; r < 6; ++r) {
            EXPECT_NEAR(w.row(r).sum(), 0.0, 1e-13) << "row " << r << " at " << p.transpose();
        }
    }
}

TEST(PatchBasis, PartitionOfUnity) {
    expect_partition_of_unity<16>(cubic, false);
    expect_partition_of_unity<9>(quadratic, false);
    expect_partition_of_unity<12>(quartic, true);
}

// Each derivative row against central differences of the row below it.
template <int n>
void expect_finite_differences(const Basis<n>& basis, bool triangle) {
    const double h = 1e-5;
    // (derivative row, differentiated row, direction 0 = s / 1 = t)
    const int checks[6][3] = {{1, 0, 0}, {2, 0, 1}, {3, 1, 0}, {4, 1, 1}, {4, 2, 0}, {5, 2, 1}};
    Weights<n> w;
    Weights<n> plus;
    Weights<n> minus;
    for (const auto& p : sample_points(triangle, 100, 2)) {
        basis(p.x(), p.y(), w);
        for (const auto& c : checks) {
            const Eigen::Vector2d step = c[2] == 0 ? Eigen::Vector2d(h, 0.0) : Eigen::Vector2d(0.0, h);
            basis(p.x() + step.x(), p.y() + step.y(), plus);
            basis(p.x() - step.x(), p.y() - step.y(), minus);
            const Eigen::Matrix<double, 1, n> fd = (plus.row(c[1]) - minus.row(c[1])) / (2.0 * h);
            EXPECT_LT((fd - w.row(c[0])).cwiseAbs().maxCoeff(), 1e-8)
                << "row " << c[0] << " vs row " << c[1] << " at " << p.transpose();
        }
    }
}

TEST(PatchBasis, DerivativesMatchFiniteDifferences) {
    expect_finite_differences<16>(cubic, false);
    expect_finite_differences<9>(quadratic, false);
    expect_finite_differences<12>(quartic, true);
}

// Σ w_k x_k = (s, t), with the derivatives of (s, t).
template <int n>
void expect_linear_precision(const Basis<n>& basis, const std::vector<Eigen::Vector2d>& positions, bool triangle) {
    Eigen::Matrix<double, n, 2> X;
    for (int k = 0; k < n; ++k) {
        X.row(k) = positions[static_cast<std::size_t>(k)].transpose();
    }
    Weights<n> w;
    for (const auto& p : sample_points(triangle, 100, 3)) {
        basis(p.x(), p.y(), w);
        Eigen::Matrix<double, 6, 2> expected = Eigen::Matrix<double, 6, 2>::Zero();
        expected.row(0) = p.transpose();
        expected(1, 0) = 1.0;
        expected(2, 1) = 1.0;
        EXPECT_LT((w * X - expected).cwiseAbs().maxCoeff(), 1e-13) << "at " << p.transpose();
    }
}

TEST(PatchBasis, LinearPrecision) {
    expect_linear_precision<16>(cubic, cubic_positions(), false);
    expect_linear_precision<9>(quadratic, quadratic_positions(), false);
    expect_linear_precision<12>(quartic, quartic_positions(), true);
}

// The monomial x^a (a <= degree) as a B-spline: coefficient of the point at x_k is the
// blossom of x^a at the point's knots: cubic (x-1, x, x+1), quadratic (x-1/2, x+1/2).
double cubic_blossom(int a, double x) {
    const double values[4] = {1.0, x, x * x - 1.0 / 3.0, x * x * x - x};
    return values[a];
}

double quadratic_blossom(int a, double x) {
    const double values[3] = {1.0, x, x * x - 0.25};
    return values[a];
}

template <int n>
void expect_tensor_reproduction(const Basis<n>& basis, const std::vector<Eigen::Vector2d>& positions, int degree,
                                double (*blossom)(int, double)) {
    Weights<n> w;
    for (int a = 0; a <= degree; ++a) {
        for (int b = 0; b <= degree; ++b) {
            Eigen::Matrix<double, n, 1> coefficients;
            for (int k = 0; k < n; ++k) {
                const auto& x = positions[static_cast<std::size_t>(k)];
                coefficients(k) = blossom(a, x.x()) * blossom(b, x.y());
            }
            for (const auto& p : sample_points(false, 50, 4)) {
                basis(p.x(), p.y(), w);
                const Eigen::Matrix<double, 6, 1> got = w * coefficients;
                const double s = p.x();
                const double t = p.y();
                // value and derivatives of s^a t^b
                const auto pw = [](double x, int e) { return e < 0 ? 0.0 : std::pow(x, e); };
                Eigen::Matrix<double, 6, 1> expected;
                expected << pw(s, a) * pw(t, b), a * pw(s, a - 1) * pw(t, b), b * pw(s, a) * pw(t, b - 1),
                    a * (a - 1) * pw(s, a - 2) * pw(t, b), a * b * pw(s, a - 1) * pw(t, b - 1),
                    b * (b - 1) * pw(s, a) * pw(t, b - 2);
                EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-13)
                    << "monomial s^" << a << " t^" << b << " at " << p.transpose();
            }
        }
    }
}

TEST(PatchBasis, BSplinesReproduceTheirPolynomials) {
    expect_tensor_reproduction<16>(cubic, cubic_positions(), 3, cubic_blossom);
    expect_tensor_reproduction<9>(quadratic, quadratic_positions(), 2, quadratic_blossom);
}

TEST(PatchBasis, KnownValuesAtTheOrigin) {
    Weights<16> wc;
    cubic_bspline_patch_weights(0.0, 0.0, wc);
    const double mask[3] = {1.0, 4.0, 1.0};
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            const double expected = (i < 3 && j < 3) ? mask[i] * mask[j] / 36.0 : 0.0;
            EXPECT_NEAR(wc(0, 4 * j + i), expected, 1e-15) << "point " << 4 * j + i;
        }
    }
    Weights<9> wq;
    quadratic_bspline_patch_weights(0.0, 0.0, wq);
    const double expected_quadratic[9] = {0.25, 0.25, 0.0, 0.25, 0.25, 0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < 9; ++k) {
        EXPECT_NEAR(wq(0, k), expected_quadratic[k], 1e-15) << "point " << k;
    }
    // Loop's limit mask at a regular vertex: 1/2 and 1/12 on the six neighbours.
    Weights<12> wb;
    quartic_box_spline_patch_weights(0.0, 0.0, wb);
    const double expected_box[12] = {1, 1, 0, 1, 6, 1, 0, 1, 1, 0, 0, 0};
    for (int k = 0; k < 12; ++k) {
        EXPECT_NEAR(wb(0, k), expected_box[k] / 12.0, 1e-15) << "point " << k;
    }
    // Patch corners (1,0) and (0,1) of the box spline are the same mask around points 5 and 8.
    Weights<12> wb5;
    Weights<12> wb8;
    quartic_box_spline_patch_weights(1.0, 0.0, wb5);
    quartic_box_spline_patch_weights(0.0, 1.0, wb8);
    const double expected_at_5[12] = {0, 1, 1, 0, 1, 6, 1, 0, 1, 1, 0, 0};
    const double expected_at_8[12] = {0, 0, 0, 0, 1, 1, 0, 1, 6, 1, 1, 1};
    for (int k = 0; k < 12; ++k) {
        EXPECT_NEAR(wb5(0, k), expected_at_5[k] / 12.0, 1e-15) << "point " << k;
        EXPECT_NEAR(wb8(0, k), expected_at_8[k] / 12.0, 1e-15) << "point " << k;
    }
}

// ---------------------------------------------------------------------------
// The independent witness: uniform subdivision of a regular lattice.

// Scalar data on the square index range [lo, hi]² of a lattice.
struct Grid {
    int lo = 0;
    int hi = 0;
    std::vector<double> values;

    Grid(int first, int last)
        : lo(first), hi(last),
          values(static_cast<std::size_t>(last - first + 1) * static_cast<std::size_t>(last - first + 1)) {}
    [[nodiscard]] std::size_t index(int i, int j) const {
        return static_cast<std::size_t>(j - lo) * static_cast<std::size_t>(hi - lo + 1) +
               static_cast<std::size_t>(i - lo);
    }
    [[nodiscard]] double at(int i, int j) const {
        EXPECT_TRUE(i >= lo && i <= hi && j >= lo && j <= hi) << "index (" << i << ", " << j << ") outside the grid";
        return values[index(i, j)];
    }
    double& at(int i, int j) { return values[index(i, j)]; }
};

Grid random_grid(int lo, int hi, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Grid g(lo, hi);
    for (double& x : g.values) {
        x = unit(random);
    }
    return g;
}

int floor_div2(int i) {
    return i >= 0 ? i / 2 : -((1 - i) / 2);
}

// Cubic B-spline (tensor Catmull–Clark on the regular grid): point i at position i·h.
// Fine even index: (1, 6, 1)/8 about the coarse point; odd: (1, 1)/2 of the edge.
Grid refine_cubic(const Grid& c) {
    Grid f(2 * c.lo + 2, 2 * c.hi - 2);
    const auto mask = [](int fine, int coarse) {
        if (fine % 2 == 0) {
            const int d = coarse - fine / 2;
            return d == 0 ? 0.75 : (d == 1 || d == -1) ? 0.125 : 0.0;
        }
        const int d = coarse - (fine - 1) / 2;
        return (d == 0 || d == 1) ? 0.5 : 0.0;
    };
    for (int J = f.lo; J <= f.hi; ++J) {
        for (int I = f.lo; I <= f.hi; ++I) {
            double sum = 0.0;
            for (int b = floor_div2(J) - 1; b <= floor_div2(J) + 1; ++b) {
                for (int a = floor_div2(I) - 1; a <= floor_div2(I) + 1; ++a) {
                    const double m = mask(I, a) * mask(J, b);
                    if (m != 0.0) {
                        sum += m * c.at(a, b);
                    }
                }
            }
            f.at(I, J) = sum;
        }
    }
    return f;
}

// Quadratic B-spline (tensor Chaikin): point i at position (i - 1/2)·h.
// Fine 2i = 3/4 c_i + 1/4 c_i+1, fine 2i+1 = 1/4 c_i + 3/4 c_i+1.
Grid refine_quadratic(const Grid& c) {
    Grid f(2 * c.lo, 2 * c.hi - 1);
    const auto mask = [](int fine, int coarse) {
        const int d = coarse - floor_div2(fine);
        const bool even = fine - 2 * floor_div2(fine) == 0;
        return d == 0 ? (even ? 0.75 : 0.25) : d == 1 ? (even ? 0.25 : 0.75) : 0.0;
    };
    for (int J = f.lo; J <= f.hi; ++J) {
        for (int I = f.lo; I <= f.hi; ++I) {
            double sum = 0.0;
            for (int b = floor_div2(J); b <= floor_div2(J) + 1; ++b) {
                for (int a = floor_div2(I); a <= floor_div2(I) + 1; ++a) {
                    sum += mask(I, a) * mask(J, b) * c.at(a, b);
                }
            }
            f.at(I, J) = sum;
        }
    }
    return f;
}

// Loop on the regular triangular lattice (triangles (0,0),(1,0),(0,1) and
// (1,0),(1,1),(0,1)): vertex 10/16 + 1/16 per neighbour; edge 3/8 per end point
// and 1/8 per opposite vertex.
Grid refine_loop(const Grid& c) {
    Grid f(2 * c.lo + 2, 2 * c.hi - 2);
    for (int J = f.lo; J <= f.hi; ++J) {
        for (int I = f.lo; I <= f.hi; ++I) {
            const int i = floor_div2(I);
            const int j = floor_div2(J);
            const bool odd_i = I != 2 * i;
            const bool odd_j = J != 2 * j;
            double value = 0.0;
            if (!odd_i && !odd_j) {
                value = 10.0 / 16.0 * c.at(i, j) + (c.at(i + 1, j) + c.at(i - 1, j) + c.at(i, j + 1) + c.at(i, j - 1) +
                                                    c.at(i + 1, j - 1) + c.at(i - 1, j + 1)) /
                                                       16.0;
            } else if (odd_i && !odd_j) {  // edge (i,j)-(i+1,j)
                value = 0.375 * (c.at(i, j) + c.at(i + 1, j)) + 0.125 * (c.at(i, j + 1) + c.at(i + 1, j - 1));
            } else if (!odd_i && odd_j) {  // edge (i,j)-(i,j+1)
                value = 0.375 * (c.at(i, j) + c.at(i, j + 1)) + 0.125 * (c.at(i + 1, j) + c.at(i - 1, j + 1));
            } else {  // edge (i+1,j)-(i,j+1)
                value = 0.375 * (c.at(i + 1, j) + c.at(i, j + 1)) + 0.125 * (c.at(i, j) + c.at(i + 1, j + 1));
            }
            f.at(I, J) = value;
        }
    }
    return f;
}

// Value and derivatives of the patch over the cell / triangle of a grid.
Eigen::Matrix<double, 6, 1> cubic_patch(const Grid& g, int a, int b, double s, double t) {
    Weights<16> w;
    cubic_bspline_patch_weights(s, t, w);
    Eigen::Matrix<double, 16, 1> x;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            x(4 * j + i) = g.at(a + i - 1, b + j - 1);
        }
    }
    return w * x;
}

Eigen::Matrix<double, 6, 1> quadratic_patch(const Grid& g, int a, int b, double s, double t) {
    Weights<9> w;
    quadratic_bspline_patch_weights(s, t, w);
    Eigen::Matrix<double, 9, 1> x;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i) {
            x(3 * j + i) = g.at(a + i, b + j);
        }
    }
    return w * x;
}

// The box-spline patch over the upright triangle with corner (a, b) (sigma = +1), or
// over the point reflection of that layout about (a, b) (sigma = -1: the triangle
// (a,b), (a-1,b), (a,b-1)); the box spline is centrally symmetric.
Eigen::Matrix<double, 6, 1> quartic_patch(const Grid& g, int a, int b, int sigma, double s, double t) {
    Weights<12> w;
    quartic_box_spline_patch_weights(s, t, w);
    Eigen::Matrix<double, 12, 1> x;
    for (int k = 0; k < 12; ++k) {
        x(k) = g.at(a + sigma * box_lattice[k][0], b + sigma * box_lattice[k][1]);
    }
    Eigen::Matrix<double, 6, 1> r = w * x;
    r(1) *= sigma;
    r(2) *= sigma;
    return r;
}

// Scales derivative rows from fine parameters to coarse ones (fine = 2^level · coarse).
void to_coarse(Eigen::Matrix<double, 6, 1>& r, int level) {
    const double scale = std::ldexp(1.0, level);
    r.segment<2>(1) *= scale;
    r.segment<3>(3) *= scale * scale;
}

void expect_same(const Eigen::Matrix<double, 6, 1>& fine, const Eigen::Matrix<double, 6, 1>& coarse, int level,
                 const Eigen::Vector2d& p) {
    // derivatives grow by 2^level per order on the fine net; allow for the rounding that carries
    const double scale = std::ldexp(1.0, 2 * level);
    EXPECT_LT((fine - coarse).cwiseAbs().maxCoeff(), 1e-13 * scale)
        << "level " << level << " at " << p.transpose() << "\nfine   " << fine.transpose() << "\ncoarse "
        << coarse.transpose();
}

TEST(PatchBasis, CubicBSplineEqualsThePatchesOfTheSubdividedNet) {
    for (unsigned seed = 10; seed < 13; ++seed) {
        Grid grid = random_grid(-3, 4, seed);
        const Grid coarse = grid;
        for (int level = 1; level <= 4; ++level) {
            grid = refine_cubic(grid);
            const int cells = 1 << level;
            for (const auto& p : sample_points(false, 40, seed)) {
                const double X = p.x() * cells;
                const double Y = p.y() * cells;
                const int a = std::min(static_cast<int>(std::floor(X)), cells - 1);
                const int b = std::min(static_cast<int>(std::floor(Y)), cells - 1);
                Eigen::Matrix<double, 6, 1> fine = cubic_patch(grid, a, b, X - a, Y - b);
                to_coarse(fine, level);
                expect_same(fine, cubic_patch(coarse, 0, 0, p.x(), p.y()), level, p);
            }
        }
    }
}

TEST(PatchBasis, QuadraticBSplineEqualsThePatchesOfTheSubdividedNet) {
    for (unsigned seed = 20; seed < 23; ++seed) {
        Grid grid = random_grid(-3, 4, seed);
        const Grid coarse = grid;
        for (int level = 1; level <= 4; ++level) {
            grid = refine_quadratic(grid);
            const int cells = 1 << level;
            for (const auto& p : sample_points(false, 40, seed)) {
                const double X = p.x() * cells;
                const double Y = p.y() * cells;
                const int a = std::min(static_cast<int>(std::floor(X)), cells - 1);
                const int b = std::min(static_cast<int>(std::floor(Y)), cells - 1);
                Eigen::Matrix<double, 6, 1> fine = quadratic_patch(grid, a, b, X - a, Y - b);
                to_coarse(fine, level);
                Eigen::Matrix<double, 6, 1> coarse_value = quadratic_patch(coarse, 0, 0, p.x(), p.y());
                if (X == std::floor(X) || Y == std::floor(Y)) {
                    // on a fine knot line the (C¹) quadratic's second derivative jumps
                    fine.segment<3>(3).setZero();
                    coarse_value.segment<3>(3).setZero();
                }
                expect_same(fine, coarse_value, level, p);
            }
        }
    }
}

TEST(PatchBasis, QuarticBoxSplineEqualsThePatchesOfTheLoopSubdividedNet) {
    for (unsigned seed = 30; seed < 33; ++seed) {
        Grid grid = random_grid(-3, 4, seed);
        const Grid coarse = grid;
        for (int level = 1; level <= 4; ++level) {
            grid = refine_loop(grid);
            const int cells = 1 << level;
            for (const auto& p : sample_points(true, 60, seed)) {
                const double X = p.x() * cells;
                const double Y = p.y() * cells;
                int a = static_cast<int>(std::floor(X));
                int b = static_cast<int>(std::floor(Y));
                Eigen::Matrix<double, 6, 1> fine;
                if (X - a + (Y - b) <= 1.0) {  // upright fine triangle (a,b), (a+1,b), (a,b+1)
                    fine = quartic_patch(grid, a, b, 1, X - a, Y - b);
                } else {  // reversed fine triangle (a+1,b+1), (a,b+1), (a+1,b)
                    fine = quartic_patch(grid, a + 1, b + 1, -1, a + 1 - X, b + 1 - Y);
                }
                to_coarse(fine, level);
                expect_same(fine, quartic_patch(coarse, 0, 0, 1, p.x(), p.y()), level, p);
            }
        }
    }
}

// A uniformly random (s, t) of the triangle s, t >= 0, s + t <= 1.
std::pair<double, double> random_triangle_point(std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    const double s = uniform(rng);
    const double t = uniform(rng);
    return s + t > 1.0 ? std::pair{1.0 - s, 1.0 - t} : std::pair{s, t};
}

// Asking for fewer rows computes the leading rows bit for bit as all six and leaves the others 0.
TEST(PatchBasis, QuarticLeadingRowsAreTheSameBitsWhateverIsAskedFor) {
    std::mt19937 rng(5);
    for (int sample = 0; sample < 200; ++sample) {
        const auto [s, t] = random_triangle_point(rng);
        Weights<12> all;
        quartic_box_spline_patch_weights(s, t, all);
        for (const int rows : {1, 3}) {
            Weights<12> some;
            some.setConstant(7.0);
            quartic_box_spline_patch_weights(s, t, some, rows);
            ASSERT_EQ(some.topRows(rows), all.topRows(rows)) << "rows " << rows;
            ASSERT_TRUE(some.bottomRows(6 - rows).isZero(0.0)) << "rows " << rows;
        }
    }
}

// The values path (points contracted with the monomials first) is the weights applied to the
// points, up to rounding, for every row asked for; the rows not asked for are 0.
TEST(PatchBasis, QuarticValuesAreTheWeightsApplied) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int sample = 0; sample < 200; ++sample) {
        const auto [s, t] = random_triangle_point(rng);
        Eigen::Matrix<double, 12, 3> P;
        for (Eigen::Index i = 0; i < P.size(); ++i) {
            P(i) = 10.0 * uniform(rng) - 5.0;
        }
        Weights<12> w;
        quartic_box_spline_patch_weights(s, t, w);
        const Eigen::Matrix<double, 6, 3> expected = w * P;
        for (const int rows : {1, 3, 6}) {
            Eigen::Matrix<double, 6, 3> values;
            values.setConstant(7.0);
            quartic_box_spline_patch_values(s, t, P, values, rows);
            for (int r = 0; r < 6; ++r) {
                for (int c = 0; c < 3; ++c) {
                    if (r < rows) {
                        ASSERT_NEAR(values(r, c), expected(r, c), 1e-13 * (1.0 + std::abs(expected(r, c))))
                            << "row " << r << " of " << rows;
                    } else {
                        ASSERT_EQ(values(r, c), 0.0) << "row " << r << " of " << rows;
                    }
                }
            }
        }
    }
}

}  // namespace
}  // namespace limsurf
