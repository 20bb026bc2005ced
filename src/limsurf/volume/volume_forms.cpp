// Shipped and on-demand volume forms (volume_forms.h).
#include "limsurf/volume/volume_forms.h"

#include <algorithm>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/detail/target_clones.h"
#include "limsurf/detail/vector_lanes.h"
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

/// Blocks [first, first + Pass) of evaluate_by_pairs()'s gradient sums (eight lanes each), N doubles
/// per register: the pairs' cross products in lexicographic order, each added to the 3 × 8 Pass
/// sums (one per point and coordinate, from +0, in pair order); out[c][i] for lane i.
template <int N, int Pass>
[[gnu::always_inline]] inline void pair_gradient_pass(int m, int lanes, int first, const double* __restrict w,
                                                      const double* x, const double* y, const double* z,
                                                      double (*out)[32]) {
    Lanes<N> gx[Pass], gy[Pass], gz[Pass];
#pragma GCC unroll 4
    for (int b = 0; b < Pass; ++b) {
        gx[b] = zero_lanes<N>();
        gy[b] = zero_lanes<N>();
        gz[b] = zero_lanes<N>();
    }
    for (int j = 0; j + 1 < m; ++j) {
        for (int k = j + 1; k < m; ++k, w += lanes) {
            const double cx = y[j] * z[k] - z[j] * y[k];
            const double cy = z[j] * x[k] - x[j] * z[k];
            const double cz = x[j] * y[k] - y[j] * x[k];
#pragma GCC unroll 4  // completely: the sums stay in registers
            for (int b = 0; b < Pass; ++b) {
                Lanes<N> row;
                load(row, w + 8 * (first + b));
                add_product(gx[b], row, cx);
                add_product(gy[b], row, cy);
                add_product(gz[b], row, cz);
            }
        }
    }
    for (int b = 0; b < Pass; ++b) {
        store(out[0] + 8 * (first + b), gx[b]);
        store(out[1] + 8 * (first + b), gy[b]);
        store(out[2] + 8 * (first + b), gz[b]);
    }
}

/// evaluate_by_pairs() for facets of m points, rows of 8 × Blocks weights, N doubles per
/// register: the gradient's sums (pair_gradient_pass, as many blocks per pass as the registers
/// hold: every block with AVX-512, two with AVX2, one with SSE2; the grouping changes no sum), then
/// the volume ⅓ Σ_i p_i · G_i in point order.
template <int N, int Blocks>
[[gnu::always_inline]] inline double pair_form_volume(int m, const double* __restrict w, const double* __restrict p,
                                                      double* __restrict gradient) {
    constexpr int lanes = 8 * Blocks;
    double x[lanes] = {};
    double y[lanes] = {};
    double z[lanes] = {};
    for (int i = 0; i < m; ++i) {
        x[i] = p[3 * i];
        y[i] = p[3 * i + 1];
        z[i] = p[3 * i + 2];
    }
    double g[3][32];
    constexpr int pass = N == 8 ? Blocks : N == 4 ? std::min(Blocks, 2) : 1;
    int first = 0;
    for (; first + pass <= Blocks; first += pass) {
        pair_gradient_pass<N, pass>(m, lanes, first, w, x, y, z, g);
    }
    if (first < Blocks) {  // pass is 2 and Blocks odd
        pair_gradient_pass<N, 1>(m, lanes, first, w, x, y, z, g);
    }
    double sum = 0.0;
    for (int i = 0; i < m; ++i) {
        sum += x[i] * g[0][i] + y[i] * g[1][i] + z[i] * g[2][i];
    }
    if (gradient != nullptr) {
        for (int i = 0; i < m; ++i) {
            gradient[3 * i] += g[0][i];
            gradient[3 * i + 1] += g[1][i];
            gradient[3 * i + 2] += g[2][i];
        }
    }
    return sum / 3.0;
}

/// The pair-weight kernel with N doubles per register; @p lanes is 8, 16, 24 or 32.
template <int N>
[[gnu::always_inline]] inline double pair_form_lanes(int m, int lanes, const double* w, const double* p,
                                                     double* gradient) {
    switch (lanes) {
    case 8:
        return pair_form_volume<N, 1>(m, w, p, gradient);
    case 16:
        return pair_form_volume<N, 2>(m, w, p, gradient);
    case 24:
        return pair_form_volume<N, 3>(m, w, p, gradient);
    default:
        return pair_form_volume<N, 4>(m, w, p, gradient);
    }
}

#ifdef LIMSURF_ISA_VARIANTS
LIMSURF_TARGET_AVX512F double pair_form_avx512f(int m, int lanes, const double* w, const double* p, double* gradient) {
    return pair_form_lanes<8>(m, lanes, w, p, gradient);
}
LIMSURF_TARGET_AVX2 double pair_form_avx2(int m, int lanes, const double* w, const double* p, double* gradient) {
    return pair_form_lanes<4>(m, lanes, w, p, gradient);
}
#endif

/// The pair-weight kernel, one copy per instruction set (target_clones.h).
double pair_form_kernel(int m, int lanes, const double* w, const double* p, double* gradient) noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    switch (vector_doubles()) {
    case 8:
        return pair_form_avx512f(m, lanes, w, p, gradient);
    case 4:
        return pair_form_avx2(m, lanes, w, p, gradient);
    default:
        break;
    }
#endif
    return pair_form_lanes<2>(m, lanes, w, p, gradient);
}

}  // namespace

double VolumeForm::evaluate(const double* p, double* gradient) const {
    return lanes > 0 ? evaluate_by_pairs(p, gradient) : evaluate_by_coefficients(p, gradient);
}

double VolumeForm::evaluate_by_pairs(const double* p, double* gradient) const {
    return pair_form_kernel(size, lanes, pair_weights.data(), p, gradient);
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
    if (m <= max_pair_form_points) {
        // W[t][i] = ∂²vol / ∂p_i ∂(p_j × p_k): the coefficient of the triple {i, j, k}, its sign
        // that of the permutation taking (i, j, k) to increasing order.
        form.lanes = (m + 7) / 8 * 8;
        const auto lanes = static_cast<std::size_t>(form.lanes);
        form.pair_weights.assign(static_cast<std::size_t>(m * (m - 1) / 2) * lanes, 0.0);
        const auto c = [&](int a, int b, int d) {
            return coefficients[static_cast<std::size_t>(alternating_index(m, a, b, d))];
        };
        std::size_t t = 0;
        for (int j = 0; j + 1 < m; ++j) {
            for (int k = j + 1; k < m; ++k, ++t) {
                for (int i = 0; i < m; ++i) {
                    if (i != j && i != k) {
                        form.pair_weights[t * lanes + static_cast<std::size_t>(i)] =
                            i < j ? c(i, j, k) : (i < k ? -c(j, i, k) : c(j, k, i));
                    }
                }
            }
        }
    }
    form.coefficients = std::move(coefficients);
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
