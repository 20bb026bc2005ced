// element_products.h. The loops are written so that the compiler vectorises them without
// reassociating anything: the forward pass across K's rows, the backward pass across K's columns
// (both independent sums, never a reduction across lanes). Both keep six vector sums in flight,
// because a sum of products is limited by the latency of the addition, not by the multiplications.
#include "limsurf/membrane/element_products.h"

#include <algorithm>
#include <array>

#include "limsurf/detail/target_clones.h"
#include "limsurf/detail/vector_lanes.h"

namespace limsurf::detail {

LIMSURF_TARGET_CLONES
void element_forward(const double* __restrict K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols,
                     const double* __restrict P, double* __restrict out, std::ptrdiff_t ld_out) noexcept {
    // 16 rows per pass, times three columns: six vector sums in flight.
    constexpr std::ptrdiff_t block = 16;
    const double* P0 = P;
    const double* P1 = P + cols;
    const double* P2 = P + 2 * cols;
    std::ptrdiff_t r = 0;
    for (; r + block <= rows; r += block) {
        Lanes a0 = {}, a1 = {}, b0 = {}, b1 = {}, c0 = {}, c1 = {};
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            Lanes k0, k1;
            load(k0, K + j * ld_k + r);
            load(k1, K + j * ld_k + r + 8);
            const double p0 = P0[j], p1 = P1[j], p2 = P2[j];
            a0 += k0 * p0;
            a1 += k1 * p0;
            b0 += k0 * p1;
            b1 += k1 * p1;
            c0 += k0 * p2;
            c1 += k1 * p2;
        }
        store(out + r, a0);
        store(out + r + 8, a1);
        store(out + ld_out + r, b0);
        store(out + ld_out + r + 8, b1);
        store(out + 2 * ld_out + r, c0);
        store(out + 2 * ld_out + r + 8, c1);
    }
    for (; r < rows; ++r) {  // the last rows % 16, summed in the same order
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            const double k = K[j * ld_k + r];
            s0 += k * P0[j];
            s1 += k * P1[j];
            s2 += k * P2[j];
        }
        out[r] = s0;
        out[ld_out + r] = s1;
        out[2 * ld_out + r] = s2;
    }
}

namespace {

/// Columns [first, first + 8 Blocks) of out = Kᵀ L for W columns of L: W × Blocks vector sums,
/// one row of K and W entries of L at a time.
template <int Blocks, int W>
[[gnu::always_inline]] inline void backward_pass(const double* __restrict Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                                 std::ptrdiff_t first, std::ptrdiff_t cols, const double* __restrict L,
                                                 std::ptrdiff_t ld_l, double* __restrict out, std::ptrdiff_t ld_out) {
    // The small loops unrolled completely, so that the sums stay in registers.
    Lanes sum[W][Blocks] = {};
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        Lanes k[Blocks];
#pragma GCC unroll 2
        for (int b = 0; b < Blocks; ++b) {
            load(k[b], Kt + r * ld_kt + first + 8 * b);
        }
#pragma GCC unroll 3
        for (int w = 0; w < W; ++w) {
            const double l = L[w * ld_l + r];
#pragma GCC unroll 2
            for (int b = 0; b < Blocks; ++b) {
                sum[w][b] += k[b] * l;
            }
        }
    }
    double lanes[W][8 * Blocks];
    for (int w = 0; w < W; ++w) {
        for (int b = 0; b < Blocks; ++b) {
            store(lanes[w] + 8 * b, sum[w][b]);
        }
    }
    const std::ptrdiff_t count = std::min<std::ptrdiff_t>(8 * Blocks, cols - first);
    for (std::ptrdiff_t j = 0; j < count; ++j) {
        for (int w = 0; w < W; ++w) {
            out[(first + j) * ld_out + w] = lanes[w][j];
        }
    }
}

/// All columns of out, for W columns of L: 16 columns of K per pass, then 8.
template <int W>
[[gnu::always_inline]] inline void backward_columns(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                                    std::ptrdiff_t cols, const double* L, std::ptrdiff_t ld_l,
                                                    double* out, std::ptrdiff_t ld_out) {
    std::ptrdiff_t first = 0;
    for (; first + 8 < cols; first += 16) {
        backward_pass<2, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
    }
    if (first < cols) {
        backward_pass<1, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
    }
}

}  // namespace

LIMSURF_TARGET_CLONES
void element_backward(const double* __restrict Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows, std::ptrdiff_t cols,
                      const double* __restrict L, std::ptrdiff_t ld_l, std::ptrdiff_t width, double* __restrict out,
                      std::ptrdiff_t ld_out) noexcept {
    std::ptrdiff_t w = 0;
    for (; w + 3 <= width; w += 3) {  // three columns of L sharing the loads of K's rows
        backward_columns<3>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    }
    if (width - w == 2) {
        backward_columns<2>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    } else if (width - w == 1) {
        backward_columns<1>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    }
}

}  // namespace limsurf::detail
