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

namespace limsurf::detail {
namespace {

// The orders of each row's derivatives in u and in v (SampleRow's order: value, ∂u, ∂v, ∂uu, ∂uv, ∂vv).
constexpr int row_u[6] = {0, 1, 0, 2, 1, 0};
constexpr int row_v[6] = {0, 0, 1, 0, 1, 2};

}  // namespace

LIMSURF_TARGET_CLONES
void tensor_forward(const TensorElement& element, const double* __restrict P, int first_row, double* __restrict out,
                    std::ptrdiff_t ld_out) noexcept {
    const std::ptrdiff_t n = element.n;
    constexpr std::ptrdiff_t m = max_tensor_samples;
    // The control points as a grid, per coordinate: grid[c][b][a].
    double grid[3][4][4];
    for (int c = 0; c < 3; ++c) {
        for (int b = 0; b < 4; ++b) {
            for (int a = 0; a < 4; ++a) {
                grid[c][b][a] = P[16 * c + element.slot[a + 4 * b]];
            }
        }
    }
    // Along v first: half[kv][c][j][a] = Σ_b N_b^(kv)(t_j) grid[c][b][a], b = 0, 1, 2, 3.
    bool needed[3] = {false, false, false};
    for (int r = first_row; r < 6; ++r) {
        needed[row_v[r]] = true;
    }
    double half[3][3][m][4];
    for (int kv = 0; kv < 3; ++kv) {
        if (!needed[kv]) {
            continue;
        }
        for (int c = 0; c < 3; ++c) {
            for (std::ptrdiff_t j = 0; j < n; ++j) {
                const double* w = element.basis_by_node + (n * kv + j) * 4;
                double sum[4] = {0.0, 0.0, 0.0, 0.0};
                for (int b = 0; b < 4; ++b) {
                    for (int a = 0; a < 4; ++a) {
                        sum[a] += w[b] * grid[c][b][a];
                    }
                }
                for (int a = 0; a < 4; ++a) {
                    half[kv][c][j][a] = sum[a];
                }
            }
        }
    }
    // Then along u: row r at (t_i, t_j) = Σ_a N_a^(ku)(t_i) half[kv][c][j][a], a = 0, 1, 2, 3.
    const std::ptrdiff_t nn = n * n;
    for (int r = first_row; r < 6; ++r) {
        const double* U = element.basis + 4 * row_u[r] * n;
        for (int c = 0; c < 3; ++c) {
            for (std::ptrdiff_t j = 0; j < n; ++j) {
                const double* h = half[row_v[r]][c][j];
                double* d = out + c * ld_out + r * nn + j * n;
                for (std::ptrdiff_t i = 0; i < n; ++i) {
                    d[i] = 0.0;
                }
                for (int a = 0; a < 4; ++a) {
                    const double t = h[a];
                    const double* u = U + a * n;
                    for (std::ptrdiff_t i = 0; i < n; ++i) {
                        d[i] += t * u[i];
                    }
                }
            }
        }
    }
}

LIMSURF_TARGET_CLONES
void tensor_backward(const TensorElement& element, const double* __restrict L, std::ptrdiff_t ld_l, int first_row,
                     int last_row, double* __restrict out, std::ptrdiff_t ld_out) noexcept {
    const std::ptrdiff_t n = element.n;
    const std::ptrdiff_t nn = n * n;
    constexpr std::ptrdiff_t m = max_tensor_samples;
    // Along u first: half[kv][c][j][a] = Σ_r Σ_i N_a^(ku)(t_i) L(r n² + n j + i, c) over the rows r
    // whose v-order is kv, in increasing r, then i.
    bool have[3] = {false, false, false};
    double half[3][3][m][4];
    for (int r = first_row; r < last_row; ++r) {
        const int kv = row_v[r];
        const double* U = element.basis_by_node + 4 * n * row_u[r];
        for (int c = 0; c < 3; ++c) {
            for (std::ptrdiff_t j = 0; j < n; ++j) {
                double sum[4] = {0.0, 0.0, 0.0, 0.0};
                if (have[kv]) {
                    for (int a = 0; a < 4; ++a) {
                        sum[a] = half[kv][c][j][a];
                    }
                }
                const double* l = L + c * ld_l + r * nn + j * n;
                for (std::ptrdiff_t i = 0; i < n; ++i) {
                    for (int a = 0; a < 4; ++a) {
                        sum[a] += l[i] * U[4 * i + a];
                    }
                }
                for (int a = 0; a < 4; ++a) {
                    half[kv][c][j][a] = sum[a];
                }
            }
        }
        have[kv] = true;
    }
    // Then along v: out(slot(a, b), c) = Σ_kv Σ_j N_b^(kv)(t_j) half[kv][c][j][a], kv then j increasing.
    for (int c = 0; c < 3; ++c) {
        for (int b = 0; b < 4; ++b) {
            double sum[4] = {0.0, 0.0, 0.0, 0.0};
            for (int kv = 0; kv < 3; ++kv) {
                if (!have[kv]) {
                    continue;
                }
                const double* V = element.basis + (4 * kv + b) * n;
                for (std::ptrdiff_t j = 0; j < n; ++j) {
                    for (int a = 0; a < 4; ++a) {
                        sum[a] += V[j] * half[kv][c][j][a];
                    }
                }
            }
            for (int a = 0; a < 4; ++a) {
                out[element.slot[a + 4 * b] * ld_out + c] = sum[a];
            }
        }
    }
}

}  // namespace limsurf::detail
