// Shipped and on-demand volume forms (volume_forms.h).
#include "limsurf/volume/volume_forms.h"

#include <array>
#include <cmath>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/volume/facet_ring.h"
#include "limsurf/volume/form_generator.h"
#include "limsurf/volume/shipped_forms.h"

namespace limsurf::detail {
namespace {

/// Largest relative residual |b + F y − y| / |y| accepted for a form generated in double
/// (rounding alone leaves about 1e-14 at type 64).
constexpr double max_generated_residual = 1e-11;

const ShippedForm* find_shipped(SchemeKind scheme, int type) {
    for (const ShippedForm& form : shipped_forms()) {
        if (form.scheme == scheme && form.type == type) {
            return &form;
        }
    }
    return nullptr;
}

std::vector<double> shipped_coefficients(const ShippedForm& form) {
    const auto count = static_cast<std::size_t>(num_alternating(form.size));
    return {form.coefficients, form.coefficients + count};
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

/// ⅓∫ x·(x_s × x_t) over the bicubic patch of the 16 canonical points @p p, and its gradient:
/// δV = ⅓∫ δx·n + δx_s·(x_t × x) + δx_t·(x × x_s) with n = x_s × x_t.
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

}  // namespace

double VolumeForm::evaluate(const double* p, double* gradient) const {
    return bicubic ? bicubic_volume(p, gradient) : evaluate_by_coefficients(p, gradient);
}

double VolumeForm::evaluate_by_coefficients(const double* p, double* gradient) const {
    double volume = 0.0;
    for (const Pair& pair : pairs) {
        const double* pj = p + 3 * pair.j;
        const double* pk = p + 3 * pair.k;
        const double cross[3] = {pj[1] * pk[2] - pj[2] * pk[1], pj[2] * pk[0] - pj[0] * pk[2],
                                 pj[0] * pk[1] - pj[1] * pk[0]};
        double q[3] = {0.0, 0.0, 0.0};
        for (std::uint32_t t = pair.begin; t < pair.end; ++t) {
            const double* pi = p + 3 * term_i[t];
            const double c = term_c[t];
            q[0] += c * pi[0];
            q[1] += c * pi[1];
            q[2] += c * pi[2];
            if (gradient != nullptr) {
                double* gi = gradient + 3 * term_i[t];
                gi[0] += c * cross[0];
                gi[1] += c * cross[1];
                gi[2] += c * cross[2];
            }
        }
        volume += q[0] * cross[0] + q[1] * cross[1] + q[2] * cross[2];
        if (gradient != nullptr) {
            // ∂/∂p_j q·(p_j × p_k) = p_k × q;  ∂/∂p_k = q × p_j.
            double* gj = gradient + 3 * pair.j;
            double* gk = gradient + 3 * pair.k;
            gj[0] += pk[1] * q[2] - pk[2] * q[1];
            gj[1] += pk[2] * q[0] - pk[0] * q[2];
            gj[2] += pk[0] * q[1] - pk[1] * q[0];
            gk[0] += q[1] * pj[2] - q[2] * pj[1];
            gk[1] += q[2] * pj[0] - q[0] * pj[2];
            gk[2] += q[0] * pj[1] - q[1] * pj[0];
        }
    }
    return volume;
}

VolumeForm make_volume_form(SchemeKind scheme, int type, std::vector<double> coefficients) {
    VolumeForm form;
    form.scheme = scheme;
    form.type = type;
    form.size = facet_ring_size(scheme, type);
    const int m = form.size;
    // Lexicographic (i, j, k) -> grouped by (j, k): walk pairs, then i < j.
    for (int j = 1; j < m; ++j) {
        for (int k = j + 1; k < m; ++k) {
            VolumeForm::Pair pair{static_cast<std::uint16_t>(j), static_cast<std::uint16_t>(k),
                                  static_cast<std::uint32_t>(form.term_i.size()), 0};
            for (int i = 0; i < j; ++i) {
                const double c = coefficients[static_cast<std::size_t>(alternating_index(m, i, j, k))];
                if (c != 0.0) {
                    form.term_i.push_back(static_cast<std::uint16_t>(i));
                    form.term_c.push_back(c);
                }
            }
            pair.end = static_cast<std::uint32_t>(form.term_i.size());
            if (pair.end > pair.begin) {
                form.pairs.push_back(pair);
            }
        }
    }
    form.coefficients = std::move(coefficients);
    form.bicubic = scheme == SchemeKind::CatmullClark && type == 4;
    return form;
}

bool is_shipped(SchemeKind scheme, int type) {
    return find_shipped(scheme, type) != nullptr;
}

VolumeForm load_volume_form(SchemeKind scheme, int type) {
    if (const ShippedForm* shipped = find_shipped(scheme, type)) {
        return make_volume_form(scheme, type, shipped_coefficients(*shipped));
    }
    const ShippedForm* regular = find_shipped(scheme, regular_facet_type(scheme));
    LIMSURF_CHECK(regular != nullptr, UnsupportedError, "no volume forms for ", to_string(scheme));
    auto generated = solve_irregular_form<double>(scheme, type, shipped_coefficients(*regular), 1e-17);
    // In double the series ends at its rounding floor; the equation's residual is the real test.
    LIMSURF_CHECK(generated.residual <= max_generated_residual, NumericalError, "the volume form of ",
                  to_string(scheme), " facet type ", type, " could not be generated accurately (relative residual ",
                  generated.residual, ")");
    return make_volume_form(scheme, type, std::move(generated.coefficients));
}

}  // namespace limsurf::detail
