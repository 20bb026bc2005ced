// The evaluation kernels of the volume forms: the pair weights are the same form as the
// coefficients (value and gradient), the regular Catmull–Clark facet's form is ⅓∫ x·n over its
// bicubic patch (a Gauss rule written here), and the gradient is the derivative of the value.
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/volume/facet_ring.h"
#include "limsurf/volume/volume_forms.h"

namespace limsurf {
namespace {

std::vector<double> random_points(std::size_t m, std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<double> p(3 * m);
    for (double& x : p) {
        x = uniform(rng);
    }
    return p;
}

/// The uniform cubic B-spline basis at the five Gauss–Legendre nodes of [0, 1]: values, derivatives.
struct BicubicRule {
    std::array<double, 5> weight{};
    std::array<std::array<double, 4>, 5> value{};
    std::array<std::array<double, 4>, 5> slope{};
    BicubicRule() {
        const double a = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
        const double b = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
        const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
        const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
        const std::array<double, 5> x{-b, -a, 0.0, a, b};
        const std::array<double, 5> w{wb, wa, 128.0 / 225.0, wa, wb};
        for (std::size_t q = 0; q < 5; ++q) {
            const double s = 0.5 * (x[q] + 1.0);
            weight[q] = 0.5 * w[q];
            const double t = 1.0 - s;
            value[q] = {t * t * t / 6.0, (3.0 * s * s * s - 6.0 * s * s + 4.0) / 6.0,
                        (-3.0 * s * s * s + 3.0 * s * s + 3.0 * s + 1.0) / 6.0, s * s * s / 6.0};
            slope[q] = {-t * t / 2.0, (9.0 * s * s - 12.0 * s) / 6.0, (-9.0 * s * s + 6.0 * s + 3.0) / 6.0,
                        s * s / 2.0};
        }
    }
};

/// Grid position (a, b), a along s = c0 -> c1, of each canonical point of the regular
/// Catmull–Clark facet (facet_ring.h): the facet spans a, b in 1..2.
constexpr std::array<std::array<int, 2>, 16> bicubic_grid{{{1, 1},
                                                           {2, 1},
                                                           {2, 2},
                                                           {1, 2},
                                                           {0, 2},
                                                           {0, 1},
                                                           {0, 0},
                                                           {1, 0},
                                                           {2, 0},
                                                           {3, 0},
                                                           {3, 1},
                                                           {3, 2},
                                                           {3, 3},
                                                           {2, 3},
                                                           {1, 3},
                                                           {0, 3}}};

/// ⅓∫ x·(x_s × x_t) over the bicubic patch of the 16 canonical points @p p (a 5×5 Gauss rule, exact
/// for the degree-(8,8) integrand), and its gradient added to @p gradient unless null:
/// δV = ⅓∫ δx·n + δx_s·(x_t × x) + δx_t·(x × x_s) with n = x_s × x_t. The regular Catmull–Clark
/// facet's form by another road than the coefficients: the divergence theorem on the patch.
double bicubic_volume(const double* p, double* gradient) {
    static const BicubicRule rule;
    double P[4][4][3];  // [b][a][coordinate]
    for (std::size_t i = 0; i < 16; ++i) {
        const auto [a, b] = bicubic_grid[i];
        for (int c = 0; c < 3; ++c) {
            P[b][a][c] = p[3 * i + static_cast<std::size_t>(c)];
        }
    }
    // Along s: A[q][b] = Σ_a N_a(s_q) P[b][a], As[q][b] = Σ_a N'_a(s_q) P[b][a].
    double A[5][4][3] = {};
    double As[5][4][3] = {};
    for (std::size_t q = 0; q < 5; ++q) {
        for (int b = 0; b < 4; ++b) {
            for (int a = 0; a < 4; ++a) {
                const double n = rule.value[q][static_cast<std::size_t>(a)];
                const double d = rule.slope[q][static_cast<std::size_t>(a)];
                for (int c = 0; c < 3; ++c) {
                    A[q][b][c] += n * P[b][a][c];
                    As[q][b][c] += d * P[b][a][c];
                }
            }
        }
    }
    double volume = 0.0;
    // Per node: the vectors multiplying N_a N_b (gv), N'_a N_b (gs) and N_a N'_b (gt) in δV.
    double gv[5][5][3];
    double gs[5][5][3];
    double gt[5][5][3];
    for (std::size_t q = 0; q < 5; ++q) {
        for (std::size_t r = 0; r < 5; ++r) {
            double x[3] = {};
            double xs[3] = {};
            double xt[3] = {};
            for (std::size_t b = 0; b < 4; ++b) {
                const double n = rule.value[r][b];
                const double d = rule.slope[r][b];
                for (int c = 0; c < 3; ++c) {
                    x[c] += n * A[q][b][c];
                    xs[c] += n * As[q][b][c];
                    xt[c] += d * A[q][b][c];
                }
            }
            const double w = rule.weight[q] * rule.weight[r] / 3.0;
            const double n[3] = {xs[1] * xt[2] - xs[2] * xt[1], xs[2] * xt[0] - xs[0] * xt[2],
                                 xs[0] * xt[1] - xs[1] * xt[0]};
            volume += w * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]);
            if (gradient != nullptr) {
                gv[q][r][0] = w * n[0];
                gv[q][r][1] = w * n[1];
                gv[q][r][2] = w * n[2];
                gs[q][r][0] = w * (xt[1] * x[2] - xt[2] * x[1]);
                gs[q][r][1] = w * (xt[2] * x[0] - xt[0] * x[2]);
                gs[q][r][2] = w * (xt[0] * x[1] - xt[1] * x[0]);
                gt[q][r][0] = w * (x[1] * xs[2] - x[2] * xs[1]);
                gt[q][r][1] = w * (x[2] * xs[0] - x[0] * xs[2]);
                gt[q][r][2] = w * (x[0] * xs[1] - x[1] * xs[0]);
            }
        }
    }
    if (gradient == nullptr) {
        return volume;
    }
    // G[b][a] = Σ_q Σ_r N_a(s_q) N_b(t_r) gv + N'_a(s_q) N_b(t_r) gs + N_a(s_q) N'_b(t_r) gt, first over r.
    double H[5][4][3] = {};   // Σ_r N_b(t_r) gv   (multiplies N_a)
    double Hs[5][4][3] = {};  // Σ_r N_b(t_r) gs   (multiplies N'_a)
    for (std::size_t q = 0; q < 5; ++q) {
        for (std::size_t r = 0; r < 5; ++r) {
            for (std::size_t b = 0; b < 4; ++b) {
                const double n = rule.value[r][b];
                const double d = rule.slope[r][b];
                for (int c = 0; c < 3; ++c) {
                    H[q][b][c] += n * gv[q][r][c] + d * gt[q][r][c];
                    Hs[q][b][c] += n * gs[q][r][c];
                }
            }
        }
    }
    for (std::size_t i = 0; i < 16; ++i) {
        const auto [a, b] = bicubic_grid[i];
        for (std::size_t q = 0; q < 5; ++q) {
            const double n = rule.value[q][static_cast<std::size_t>(a)];
            const double d = rule.slope[q][static_cast<std::size_t>(a)];
            for (int c = 0; c < 3; ++c) {
                gradient[3 * i + static_cast<std::size_t>(c)] += n * H[q][b][c] + d * Hs[q][b][c];
            }
        }
    }
    return volume;
}

TEST(VolumeKernel, BicubicGaussRuleIsTheRegularCatmullClarkForm) {
    const detail::VolumeForm form = detail::load_volume_form(SchemeKind::CatmullClark, 4);
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const std::vector<double> p = random_points(16, rng);
        std::vector<double> g_gauss(p.size(), 0.0);
        std::vector<double> g_form(p.size(), 0.0);
        std::vector<double> g_table(p.size(), 0.0);
        const double v_gauss = bicubic_volume(p.data(), g_gauss.data());
        const double v_form = form.evaluate(p.data(), g_form.data());
        const double v_table = form.evaluate_by_coefficients(p.data(), g_table.data());
        EXPECT_NEAR(v_form, v_gauss, 1e-15);
        EXPECT_NEAR(v_table, v_gauss, 1e-15);
        for (std::size_t i = 0; i < p.size(); ++i) {
            EXPECT_NEAR(g_form[i], g_gauss[i], 1e-15) << i;
            EXPECT_NEAR(g_table[i], g_gauss[i], 1e-15) << i;
        }
    }
}

// The pair weights against the coefficients they were laid out from, for the shipped types and
// generated ones on either side of max_pair_form_points (Loop 26: m = 32; Catmull–Clark 13: m = 34).
TEST(VolumeKernel, PairWeightsAreTheFormOfTheCoefficients) {
    std::mt19937 rng(5);
    const std::vector<std::pair<SchemeKind, int>> cases{
        {SchemeKind::Loop, 3},         {SchemeKind::Loop, 6},          {SchemeKind::Loop, 12},
        {SchemeKind::Loop, 26},        {SchemeKind::CatmullClark, 3},  {SchemeKind::CatmullClark, 4},
        {SchemeKind::CatmullClark, 5}, {SchemeKind::CatmullClark, 12}, {SchemeKind::CatmullClark, 13},
        {SchemeKind::DooSabin, 3},     {SchemeKind::DooSabin, 4},      {SchemeKind::DooSabin, 12}};
    for (const auto& [scheme, type] : cases) {
        const detail::VolumeForm form = detail::load_volume_form(scheme, type);
        const int m = detail::facet_ring_size(scheme, type);
        const std::string name = std::string(to_string(scheme)) + " type " + std::to_string(type);
        if (m > detail::max_pair_form_points) {
            EXPECT_EQ(form.lanes, 0) << name;
            continue;
        }
        ASSERT_EQ(form.lanes % 8, 0) << name;
        ASSERT_GE(form.lanes, m) << name;
        for (int trial = 0; trial < 10; ++trial) {
            const std::vector<double> p = random_points(static_cast<std::size_t>(m), rng);
            std::vector<double> g_pairs(p.size(), 0.25);  // the kernels add to what is there
            std::vector<double> g_table(p.size(), 0.25);
            const double v_pairs = form.evaluate_by_pairs(p.data(), g_pairs.data());
            const double v_table = form.evaluate_by_coefficients(p.data(), g_table.data());
            EXPECT_NEAR(v_pairs, v_table, 1e-15 * m * m) << name;
            for (std::size_t i = 0; i < p.size(); ++i) {
                EXPECT_NEAR(g_pairs[i], g_table[i], 1e-15 * m * m) << name << " " << i;
            }
            // The value's bits do not depend on whether the gradient is asked for.
            EXPECT_EQ(form.evaluate_by_pairs(p.data(), nullptr), v_pairs) << name;
        }
    }
}

TEST(VolumeKernel, GradientIsTheDerivativeOfTheFormForEveryScheme) {
    std::mt19937 rng(11);
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin}) {
        for (const int type : {3, 4, 5, 6, 12}) {
            const detail::VolumeForm form = detail::load_volume_form(scheme, type);
            const auto m = static_cast<std::size_t>(detail::facet_ring_size(scheme, type));
            std::vector<double> p = random_points(m, rng);
            std::vector<double> g(p.size(), 0.0);
            form.evaluate(p.data(), g.data());
            // The form is cubic: the central difference is exact up to rounding (h² term vanishes
            // only for quadratics, so keep h small; the h² error is O(h² · |coefficients|)).
            const double h = 1e-5;
            for (std::size_t i = 0; i < p.size(); ++i) {
                const double x = p[i];
                p[i] = x + h;
                const double plus = form.evaluate(p.data(), nullptr);
                p[i] = x - h;
                const double minus = form.evaluate(p.data(), nullptr);
                p[i] = x;
                EXPECT_NEAR((plus - minus) / (2 * h), g[i], 1e-9) << to_string(scheme) << " type " << type << " " << i;
            }
        }
    }
}

}  // namespace
}  // namespace limsurf
