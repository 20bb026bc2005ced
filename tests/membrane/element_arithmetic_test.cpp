// The shape functionals' element arithmetic (private: src/limsurf/membrane/element_products.h and
// sample_integrands.h). The products (dense and sum-factorised) must sum in the order their header
// documents, bit for bit
// (that order is what makes every CPU's copy give the same bits), and agree with Eigen's products;
// the integrands must give the analytic values on a sphere of radius r (H = 1/r, K = 1/r²) and
// local gradients equal to finite differences of those values.
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/membrane/element_products.h"
#include "limsurf/membrane/sample_integrands.h"

namespace limsurf {
namespace {

using detail::element_backward;
using detail::element_forward;

std::vector<double> random_values(std::size_t count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<double> v(count);
    for (double& x : v) {
        x = uniform(rng);
    }
    return v;
}

struct Shape {
    std::ptrdiff_t rows, cols, width;
};
// Row and column counts on either side of the eight lanes and of the 16-row (forwards) and
// 16-column (backwards) blocks, a Loop element (96 rows of 12 columns), a Catmull–Clark one (150 of
// 16), a C2g0-sized one (40 columns), widths not a multiple of three, and empty ones. With AVX2 the
// backward passes take 12, 8 or 4 columns: 21 columns end with a pass of 12 at column 12, reading
// up to the 24 that K's rows are padded to.
constexpr std::array<Shape, 13> shapes{{{0, 3, 3},
                                        {20, 21, 3},
                                        {5, 4, 6},
                                        {1, 1, 1},
                                        {7, 5, 2},
                                        {8, 12, 3},
                                        {9, 13, 4},
                                        {17, 2, 9},
                                        {96, 12, 9},
                                        {150, 16, 10},
                                        {33, 17, 5},
                                        {80, 40, 3},
                                        {80, 0, 3}}};

TEST(ElementProducts, ForwardSumsEachEntryOverTheColumnsInOrder) {
    for (const Shape& s : shapes) {
        SCOPED_TRACE(testing::Message() << s.rows << " x " << s.cols);
        const std::ptrdiff_t ld_k = s.rows + 3;  // a leading dimension beyond the rows
        const auto K = random_values(static_cast<std::size_t>(ld_k * s.cols), 1);
        const auto P = random_values(static_cast<std::size_t>(3 * s.cols), 2);
        // out's leading dimension beyond its rows: the rows between are left as they are.
        const std::ptrdiff_t ld_out = s.rows + 2;
        const double untouched = -7.25;
        std::vector<double> out(static_cast<std::size_t>(3 * ld_out), untouched);
        element_forward(K.data(), ld_k, s.rows, s.cols, P.data(), out.data(), ld_out);
        const Eigen::Map<const Eigen::MatrixXd> k(K.data(), ld_k, s.cols);
        const Eigen::Map<const Eigen::MatrixXd> p(P.data(), s.cols, 3);
        const Eigen::MatrixXd expected = k.topRows(s.rows) * p;
        for (std::ptrdiff_t c = 0; c < 3; ++c) {
            for (std::ptrdiff_t r = 0; r < s.rows; ++r) {
                double sum = 0.0;  // the documented order
                for (std::ptrdiff_t j = 0; j < s.cols; ++j) {
                    sum += K[static_cast<std::size_t>(j * ld_k + r)] * P[static_cast<std::size_t>(c * s.cols + j)];
                }
                const double got = out[static_cast<std::size_t>(c * ld_out + r)];
                EXPECT_EQ(got, sum) << "row " << r << ", column " << c;
                EXPECT_NEAR(got, expected(r, c), 1e-14 * static_cast<double>(s.cols + 1));
            }
            for (std::ptrdiff_t r = s.rows; r < ld_out; ++r) {
                EXPECT_EQ(out[static_cast<std::size_t>(c * ld_out + r)], untouched) << "a row beyond rows was written";
            }
        }
    }
}

TEST(ElementProducts, BackwardSumsEachEntryOverTheRowsInOrderAndWritesOnlyItsColumns) {
    for (const Shape& s : shapes) {
        SCOPED_TRACE(testing::Message() << s.rows << " x " << s.cols << " x " << s.width);
        // K by rows, padded past a multiple of 8 with NaN: the padding is read, and must not reach out.
        const std::ptrdiff_t ld_kt = (s.cols + 7) / 8 * 8 + 8, ld_l = s.rows + 5, ld_out = s.width + 2;
        std::vector<double> Kt = random_values(static_cast<std::size_t>(ld_kt * s.rows), 3);
        for (std::ptrdiff_t r = 0; r < s.rows; ++r) {
            for (std::ptrdiff_t j = s.cols; j < ld_kt; ++j) {
                Kt[static_cast<std::size_t>(r * ld_kt + j)] = std::numeric_limits<double>::quiet_NaN();
            }
        }
        const auto L = random_values(static_cast<std::size_t>(ld_l * s.width), 4);
        const double untouched = -7.25;
        std::vector<double> out(static_cast<std::size_t>(ld_out * s.cols), untouched);
        element_backward(Kt.data(), ld_kt, s.rows, s.cols, L.data(), ld_l, s.width, out.data(), ld_out);
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const Eigen::Map<const RowMajor> k(Kt.data(), s.rows, ld_kt);
        const Eigen::Map<const Eigen::MatrixXd> l(L.data(), ld_l, s.width);
        const Eigen::MatrixXd expected = k.leftCols(s.cols).transpose() * l.topRows(s.rows);
        for (std::ptrdiff_t j = 0; j < s.cols; ++j) {
            for (std::ptrdiff_t w = 0; w < ld_out; ++w) {
                const double got = out[static_cast<std::size_t>(j * ld_out + w)];
                if (w >= s.width) {
                    EXPECT_EQ(got, untouched) << "a column beyond the width was written";
                    continue;
                }
                double sum = 0.0;  // the documented order
                for (std::ptrdiff_t r = 0; r < s.rows; ++r) {
                    sum += Kt[static_cast<std::size_t>(r * ld_kt + j)] * L[static_cast<std::size_t>(w * ld_l + r)];
                }
                EXPECT_EQ(got, sum) << "slot " << j << ", column " << w;
                EXPECT_NEAR(got, expected(j, w), 1e-14 * static_cast<double>(s.rows + 1));
            }
        }
    }
}

/// Samples of the sphere x(u, v) = r (cos v cos u, cos v sin u, sin v) at latitudes @p v, in
/// sample_integrands.h's layout (6 n × 3, column-major; rows value, ∂u, ∂v, ∂uu, ∂uv, ∂vv).
std::vector<double> sphere_rows(double r, double u, const std::vector<double>& v) {
    const auto n = static_cast<std::ptrdiff_t>(v.size());
    std::vector<double> rows(static_cast<std::size_t>(18 * n));
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const double cu = std::cos(u), su = std::sin(u), cv = std::cos(v[static_cast<std::size_t>(i)]),
                     sv = std::sin(v[static_cast<std::size_t>(i)]);
        const double row[6][3] = {{cv * cu, cv * su, sv},    {-cv * su, cv * cu, 0.0}, {-sv * cu, -sv * su, cv},
                                  {-cv * cu, -cv * su, 0.0}, {sv * su, -sv * cu, 0.0}, {-cv * cu, -cv * su, -sv}};
        for (std::ptrdiff_t k = 0; k < 6; ++k) {
            for (std::ptrdiff_t c = 0; c < 3; ++c) {
                rows[static_cast<std::size_t>(c * 6 * n + k * n + i)] = r * row[k][c];
            }
        }
    }
    return rows;
}

struct Integrands {
    std::vector<double> values, normal_area, local, flags;
    std::ptrdiff_t first_bad = 0;
};

Integrands integrands(const std::vector<double>& rows, const std::vector<double>& weights, bool triangle) {
    const auto n = static_cast<std::ptrdiff_t>(weights.size());
    Integrands out;
    out.values.assign(static_cast<std::size_t>(6 * n), 0.0);
    out.normal_area.assign(static_cast<std::size_t>(3 * n), 0.0);
    out.local.assign(static_cast<std::size_t>(18 * 6 * n), 0.0);
    out.flags.assign(static_cast<std::size_t>(n), -1.0);
    detail::SampleBatch batch;
    batch.n = n;
    batch.rows = rows.data();
    batch.weights = weights.data();
    batch.triangle = triangle;
    out.first_bad =
        detail::sample_integrands(batch, out.values.data(), out.normal_area.data(), out.local.data(), out.flags.data());
    return out;
}

// 11 samples: more than one vector of eight, and a remainder.
/// Random tables and a random assignment of the 16 control points to slots, for n samples per
/// direction, with the dense kernel they stand for (6 n² × 16, column-major).
struct TensorCase {
    explicit TensorCase(std::ptrdiff_t samples, unsigned seed)
        : n(samples), basis(random_values(static_cast<std::size_t>(12 * samples), seed)),
          by_node(static_cast<std::size_t>(12 * samples)), slot(16) {
        const auto un = static_cast<std::size_t>(n);
        for (std::size_t k = 0; k < 3; ++k) {
            for (std::size_t a = 0; a < 4; ++a) {
                for (std::size_t i = 0; i < un; ++i) {
                    by_node[(un * k + i) * 4 + a] = table(static_cast<int>(k), static_cast<int>(a), i);
                }
            }
        }
        for (int g = 0; g < 16; ++g) {
            slot[static_cast<std::size_t>(g)] = (5 * g + 3) % 16;  // a permutation
        }
        kernel = Eigen::MatrixXd::Zero(6 * n * n, 16);
        for (int r = 0; r < 6; ++r) {
            for (std::ptrdiff_t j = 0; j < n; ++j) {
                for (std::ptrdiff_t i = 0; i < n; ++i) {
                    for (int g = 0; g < 16; ++g) {
                        kernel(r * n * n + j * n + i, slot[static_cast<std::size_t>(g)]) =
                            table(row_u[r], g % 4, static_cast<std::size_t>(i)) *
                            table(row_v[r], g / 4, static_cast<std::size_t>(j));
                    }
                }
            }
        }
    }
    [[nodiscard]] double table(int k, int a, std::size_t i) const {
        return basis[(4 * static_cast<std::size_t>(k) + static_cast<std::size_t>(a)) * static_cast<std::size_t>(n) + i];
    }
    [[nodiscard]] detail::TensorElement element() const { return {n, basis.data(), by_node.data(), slot.data()}; }

    static constexpr int row_u[6] = {0, 1, 0, 2, 1, 0};
    static constexpr int row_v[6] = {0, 0, 1, 0, 1, 2};
    std::ptrdiff_t n;
    std::vector<double> basis, by_node;
    std::vector<int> slot;
    Eigen::MatrixXd kernel;
};

// The unrolled sizes (3, 4, 5), one with n known only at run time (7) and one with two vectors of
// four per row (9): every entry is the header's order bit for bit, and the dense kernel's product
// to rounding; the rows before first_row are left as they are.
TEST(TensorProducts, ForwardSumsAlongVThenUInTheHeadersOrder) {
    for (const std::ptrdiff_t n : {3, 4, 5, 7, 9}) {
        const TensorCase t(n, static_cast<unsigned>(10 + n));
        const auto P = random_values(48, 5);
        for (const int first_row : {0, 1}) {
            SCOPED_TRACE(testing::Message() << "n " << n << ", first row " << first_row);
            const std::ptrdiff_t ld_out = 6 * n * n + 3;
            const double untouched = -7.25;
            std::vector<double> out(static_cast<std::size_t>(3 * ld_out), untouched);
            detail::tensor_forward(t.element(), P.data(), first_row, out.data(), ld_out);
            const Eigen::MatrixXd dense = t.kernel * Eigen::Map<const Eigen::MatrixXd>(P.data(), 16, 3);
            for (int c = 0; c < 3; ++c) {
                for (int r = 0; r < 6; ++r) {
                    for (std::ptrdiff_t j = 0; j < n; ++j) {
                        for (std::ptrdiff_t i = 0; i < n; ++i) {
                            const std::ptrdiff_t row = r * n * n + j * n + i;
                            const double got = out[static_cast<std::size_t>(c * ld_out + row)];
                            if (r < first_row) {
                                EXPECT_EQ(got, untouched) << "row " << row;
                                continue;
                            }
                            double sum = 0.0;
                            for (int a = 0; a < 4; ++a) {
                                double h = 0.0;
                                for (int b = 0; b < 4; ++b) {
                                    h += t.table(TensorCase::row_v[r], b, static_cast<std::size_t>(j)) *
                                         P[static_cast<std::size_t>(16 * c +
                                                                    t.slot[static_cast<std::size_t>(a + 4 * b)])];
                                }
                                sum += t.table(TensorCase::row_u[r], a, static_cast<std::size_t>(i)) * h;
                            }
                            EXPECT_EQ(got, sum) << "row " << row << ", column " << c;
                            EXPECT_NEAR(got, dense(row, c), 1e-14 * 16);
                        }
                    }
                }
            }
        }
    }
}

TEST(TensorProducts, BackwardSumsAlongUThenVInTheHeadersOrder) {
    for (const std::ptrdiff_t n : {3, 4, 5, 7, 9}) {
        const TensorCase t(n, static_cast<unsigned>(20 + n));
        const std::ptrdiff_t ld_l = 6 * n * n + 2;
        const auto L = random_values(static_cast<std::size_t>(3 * ld_l), 6);
        for (const auto& [first_row, last_row] : {std::pair{1, 6}, std::pair{1, 3}, std::pair{0, 3}, std::pair{2, 5}}) {
            SCOPED_TRACE(testing::Message() << "n " << n << ", rows " << first_row << "–" << last_row);
            const std::ptrdiff_t ld_out = 5;
            const double untouched = -7.25;
            std::vector<double> out(static_cast<std::size_t>(16 * ld_out), untouched);
            detail::tensor_backward(t.element(), L.data(), ld_l, first_row, last_row, out.data(), ld_out);
            const std::ptrdiff_t first = first_row * n * n, count = (last_row - first_row) * n * n;
            const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> l(L.data(), ld_l, 3,
                                                                               Eigen::OuterStride<>(ld_l));
            const Eigen::MatrixXd dense = t.kernel.middleRows(first, count).transpose() * l.middleRows(first, count);
            for (int g = 0; g < 16; ++g) {
                const int a = g % 4, b = g / 4;
                const auto k = static_cast<std::size_t>(t.slot[static_cast<std::size_t>(g)]);
                for (int c = 0; c < 3; ++c) {
                    double sum = 0.0;
                    for (int kv = 0; kv < 3; ++kv) {
                        bool present = false;
                        for (int r = first_row; r < last_row; ++r) {
                            present = present || TensorCase::row_v[r] == kv;
                        }
                        if (!present) {
                            continue;
                        }
                        for (std::ptrdiff_t j = 0; j < n; ++j) {
                            double h = 0.0;
                            for (int r = first_row; r < last_row; ++r) {
                                if (TensorCase::row_v[r] != kv) {
                                    continue;
                                }
                                for (std::ptrdiff_t i = 0; i < n; ++i) {
                                    h += t.table(TensorCase::row_u[r], a, static_cast<std::size_t>(i)) *
                                         L[static_cast<std::size_t>(c * ld_l + r * n * n + j * n + i)];
                                }
                            }
                            sum += t.table(kv, b, static_cast<std::size_t>(j)) * h;
                        }
                    }
                    const double got = out[k * ld_out + static_cast<std::size_t>(c)];
                    EXPECT_EQ(got, sum) << "slot " << k << ", column " << c;
                    EXPECT_NEAR(got, dense(static_cast<Eigen::Index>(k), c), 1e-14 * static_cast<double>(count));
                }
                for (std::ptrdiff_t c = 3; c < ld_out; ++c) {
                    EXPECT_EQ(out[k * ld_out + static_cast<std::size_t>(c)], untouched)
                        << "a column beyond 3 was written";
                }
            }
        }
    }
}

TEST(SampleIntegrands, SphereValuesAreAnalytic) {
    const double r = 1.7, u = 0.3;
    std::vector<double> v, weights;
    for (int i = 0; i < 11; ++i) {
        v.push_back(-1.2 + 0.22 * i);
        weights.push_back(0.5 + 0.1 * i);
    }
    for (const bool triangle : {true, false}) {
        const Integrands at = integrands(sphere_rows(r, u, v), weights, triangle);
        EXPECT_EQ(at.first_bad, -1);
        const std::size_t n = v.size();
        for (std::size_t i = 0; i < n; ++i) {
            SCOPED_TRACE(testing::Message() << "sample " << i);
            EXPECT_EQ(at.flags[i], 0.0);
            const double w = weights[i], cv = std::cos(v[i]);
            const double J = r * r * cv;  // dA per du dv; H = 1/r, K = 1/r²
            const double hs = triangle ? 2.0 / std::sqrt(3.0) : 1.0;
            const double expected[6] = {J * w,           r / 3.0 * J * w, J / r * w,
                                        J / (r * r) * w, J / (r * r) * w, hs * (r * r * cv * cv + r * r) * w};
            for (std::size_t f = 0; f < 6; ++f) {
                EXPECT_NEAR(at.values[f * n + i], expected[f], 1e-13 * r * r * r) << "functional " << f;
            }
            // w N = w J n, n the outward normal: the position over r.
            const std::vector<double> x = sphere_rows(1.0, u, {v[i]});
            for (std::size_t c = 0; c < 3; ++c) {
                EXPECT_NEAR(at.normal_area[c * n + i], w * J * x[c * 6], 1e-14);
            }
        }
    }
}

TEST(SampleIntegrands, LocalGradientsAreFiniteDifferencesOfTheValues) {
    // A generic surface point: the sphere's rows, perturbed, with a centroid off the origin.
    const std::vector<double> v{-0.4, 0.1, 0.7};
    std::vector<double> rows = sphere_rows(1.3, 0.8, v);
    const auto noise = random_values(rows.size(), 5);
    for (std::size_t k = 0; k < rows.size(); ++k) {
        rows[k] += 0.2 * noise[k];
    }
    const std::vector<double> weights{0.3, 0.9, 0.6};
    const auto n = static_cast<std::ptrdiff_t>(v.size());
    for (const bool triangle : {true, false}) {
        const Integrands at = integrands(rows, weights, triangle);
        ASSERT_EQ(at.first_bad, -1);
        for (std::ptrdiff_t f = 0; f < 6; ++f) {
            for (std::ptrdiff_t k = detail::local_rows_first[f]; k < detail::local_rows_last[f]; ++k) {
                for (std::ptrdiff_t c = 0; c < 3; ++c) {
                    for (std::ptrdiff_t i = 0; i < n; ++i) {
                        const auto entry = static_cast<std::size_t>(c * 6 * n + k * n + i);
                        const double h = 1e-6;
                        std::vector<double> plus = rows, minus = rows;
                        plus[entry] += h;
                        minus[entry] -= h;
                        const auto value = static_cast<std::size_t>(f * n + i);
                        const double central = (integrands(plus, weights, triangle).values[value] -
                                                integrands(minus, weights, triangle).values[value]) /
                                               (2.0 * h);
                        const double local = at.local[static_cast<std::size_t>((3 * f + c) * 6 * n + k * n + i)];
                        EXPECT_NEAR(local, central, 1e-6 * (1.0 + std::abs(central)))
                            << "functional " << f << ", row " << k << ", coordinate " << c << ", sample " << i;
                    }
                }
            }
        }
        // The rows a functional does not depend on: its value does not move with them.
        for (std::ptrdiff_t f = 0; f < 6; ++f) {
            for (std::ptrdiff_t k = 0; k < 6; ++k) {
                if (k >= detail::local_rows_first[f] && k < detail::local_rows_last[f]) {
                    continue;
                }
                std::vector<double> moved = rows;
                for (std::ptrdiff_t c = 0; c < 3; ++c) {
                    moved[static_cast<std::size_t>(c * 6 * n + k * n)] += 0.1;
                }
                EXPECT_EQ(integrands(moved, weights, triangle).values[static_cast<std::size_t>(f * n)],
                          at.values[static_cast<std::size_t>(f * n)])
                    << "functional " << f << " depends on row " << k;
            }
        }
    }
}

TEST(SampleIntegrands, DegenerateSamplesAreFlaggedAndTheFirstIsReturned) {
    const std::vector<double> v{0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
    const std::vector<double> weights(v.size(), 1.0);
    const auto n = static_cast<std::ptrdiff_t>(v.size());
    std::vector<double> rows = sphere_rows(1.0, 0.2, v);
    const auto at = [&](std::ptrdiff_t row, std::ptrdiff_t c, std::ptrdiff_t i) -> double& {
        return rows[static_cast<std::size_t>(c * 6 * n + row * n + i)];
    };
    for (std::ptrdiff_t c = 0; c < 3; ++c) {
        at(detail::RowDv, c, 8) = 2.0 * at(detail::RowDu, c, 8);  // parallel tangents
        at(detail::RowDv, c, 9) = 0.0;                            // no second tangent
    }
    at(detail::RowDuu, 0, 4) = std::numeric_limits<double>::quiet_NaN();  // a value that is not finite
    at(detail::RowDvv, 1, 6) = std::numeric_limits<double>::infinity();
    const Integrands result = integrands(rows, weights, true);
    EXPECT_EQ(result.first_bad, 4);
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const bool bad = i == 4 || i == 6 || i == 8 || i == 9;
        EXPECT_EQ(result.flags[static_cast<std::size_t>(i)], bad ? 1.0 : 0.0) << "sample " << i;
    }
}

}  // namespace
}  // namespace limsurf
