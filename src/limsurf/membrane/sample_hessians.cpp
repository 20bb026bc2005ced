// sample_hessians.h. The 36 perturbed copies of every sample (each input moved by ±h) go through
// sample_integrands as one batch, so the differences reuse its vectorised loop.
#include "limsurf/membrane/sample_hessians.h"

#include <algorithm>
#include <cmath>

namespace limsurf::detail {
namespace {

constexpr int rows_per_sample = 6;
constexpr int copies = 2 * sample_inputs;  // per sample: input p moved by +h (copy 2p) and by −h (2p + 1)

/// The step of sample @p i: 2^-17 times its tangent size rounded down to a power of two (an exact
/// move of every input that is a multiple of it; 1 for a sample with no tangent, which
/// sample_integrands reports degenerate).
double step_of(const double* rows, std::ptrdiff_t n, std::ptrdiff_t i) {
    const std::ptrdiff_t ld = rows_per_sample * n;
    double size = 0.0;
    for (int c = 0; c < 3; ++c) {
        size = std::max({size, std::fabs(rows[c * ld + RowDu * n + i]), std::fabs(rows[c * ld + RowDv * n + i])});
    }
    if (!(size > 0.0) || !std::isfinite(size)) {
        return 1.0;
    }
    int exponent = 0;
    (void)std::frexp(size, &exponent);  // size = m 2^exponent, m in [0.5, 1)
    return std::ldexp(1.0, exponent - 1 - 17);
}

}  // namespace

std::ptrdiff_t sample_hessians(const SampleBatch& batch, const double* coefficients, double* hessians,
                               std::vector<double>& scratch) {
    const std::ptrdiff_t n = batch.n;
    const std::ptrdiff_t m = copies * n;  // the perturbed batch
    const std::ptrdiff_t ld = rows_per_sample * n, ld_m = rows_per_sample * m;
    // scratch: the perturbed rows (6 m × 3), values (6 m), w N (3 m), local gradients (18 × 6 m),
    // flags (m), steps (n), weights (m).
    const auto size = [](std::ptrdiff_t k) { return static_cast<std::size_t>(k); };
    // Not cleared: every entry read below is written first (the local gradients only in the rows
    // each functional depends on, which are the only ones read).
    scratch.resize(size(3 * ld_m + 6 * m + 3 * m + 18 * ld_m + m + n + m));
    double* rows = scratch.data();
    double* values = rows + 3 * ld_m;
    double* normal_area = values + 6 * m;
    double* local = normal_area + 3 * m;
    double* flags = local + 18 * ld_m;
    double* steps = flags + m;
    double* weights = steps + n;

    for (std::ptrdiff_t i = 0; i < n; ++i) {
        steps[i] = step_of(batch.rows, n, i);
        for (int copy = 0; copy < copies; ++copy) {
            const std::ptrdiff_t j = copies * i + copy;
            weights[j] = batch.weights[i];
            for (int c = 0; c < 3; ++c) {
                for (int r = 0; r < rows_per_sample; ++r) {
                    rows[c * ld_m + r * m + j] = batch.rows[c * ld + r * n + i];
                }
            }
            const int p = copy / 2;  // input p = 3 r + c
            rows[(p % 3) * ld_m + (p / 3) * m + j] += copy % 2 == 0 ? steps[i] : -steps[i];
        }
    }
    SampleBatch perturbed = batch;
    perturbed.n = m;
    perturbed.rows = rows;
    perturbed.weights = weights;
    (void)sample_integrands(perturbed, values, normal_area, local, flags);

    // The weighted sum's gradient at copy j, input q = 3 r + c.
    const auto gradient = [&](std::ptrdiff_t j, int q) {
        const int r = q / 3, c = q % 3;
        double sum = 0.0;
        for (int f = 0; f < 6; ++f) {
            if (coefficients[f] != 0.0 && r >= local_rows_first[f] && r < local_rows_last[f]) {
                sum += coefficients[f] * local[(3 * f + c) * ld_m + r * m + j];
            }
        }
        return sum;
    };
    std::ptrdiff_t first_bad = -1;
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        double* H = hessians + i * sample_inputs * sample_inputs;
        bool bad = false;
        for (int p = 0; p < sample_inputs; ++p) {
            const std::ptrdiff_t plus = copies * i + 2 * p, minus = plus + 1;
            bad = bad || flags[plus] != 0.0 || flags[minus] != 0.0;
            for (int q = 0; q < sample_inputs; ++q) {
                H[q * sample_inputs + p] = (gradient(plus, q) - gradient(minus, q)) / (2.0 * steps[i]);
            }
        }
        for (int p = 0; p < sample_inputs; ++p) {
            for (int q = p + 1; q < sample_inputs; ++q) {
                const double mean = 0.5 * (H[p * sample_inputs + q] + H[q * sample_inputs + p]);
                H[p * sample_inputs + q] = mean;
                H[q * sample_inputs + p] = mean;
            }
        }
        if (bad && first_bad < 0) {
            first_bad = i;
        }
    }
    return first_bad;
}

}  // namespace limsurf::detail
