// element_products.h. The loops are written in vectors (detail/vector_lanes.h) without
// reassociating anything: the dense forward pass across K's rows, the dense backward pass across
// K's columns, the tensor passes across a grid row's four points (all independent sums, never a
// reduction across lanes). Each keeps several vector sums in flight, because a sum of products is
// limited by the latency of the addition, not by the multiplications. Templates on N (doubles per
// register) are instantiated once per instruction set (detail/target_clones.h).
#include "limsurf/membrane/element_products.h"

#include <algorithm>
#include <array>

#include "limsurf/detail/target_clones.h"
#include "limsurf/detail/vector_lanes.h"

namespace limsurf::detail {
namespace {

/// element_forward() with N doubles per register.
template <int N>
[[gnu::always_inline]] inline void forward(const double* __restrict K, std::ptrdiff_t ld_k, std::ptrdiff_t rows,
                                           std::ptrdiff_t cols, const double* __restrict P, double* __restrict out,
                                           std::ptrdiff_t ld_out) {
    // 16 rows per pass, times three columns: six sums of eight in flight.
    constexpr std::ptrdiff_t block = 16;
    const double* P0 = P;
    const double* P1 = P + cols;
    const double* P2 = P + 2 * cols;
    std::ptrdiff_t r = 0;
    for (; r + block <= rows; r += block) {
        Lanes<N> a0 = zero_lanes<N>(), a1 = zero_lanes<N>(), b0 = zero_lanes<N>(), b1 = zero_lanes<N>(),
                 c0 = zero_lanes<N>(), c1 = zero_lanes<N>();
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            Lanes<N> k0, k1;
            load(k0, K + j * ld_k + r);
            load(k1, K + j * ld_k + r + 8);
            const double p0 = P0[j], p1 = P1[j], p2 = P2[j];
            add_product(a0, k0, p0);
            add_product(a1, k1, p0);
            add_product(b0, k0, p1);
            add_product(b1, k1, p1);
            add_product(c0, k0, p2);
            add_product(c1, k1, p2);
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

/// Columns [first, first + Width) of out = Kᵀ L for W columns of L: W sums of Width doubles, one
/// row of K and W entries of L at a time.
template <int N, int Width, int W>
[[gnu::always_inline]] inline void backward_pass(const double* __restrict Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                                 std::ptrdiff_t first, std::ptrdiff_t cols, const double* __restrict L,
                                                 std::ptrdiff_t ld_l, double* __restrict out, std::ptrdiff_t ld_out) {
    // The small loops unrolled completely, so that the sums stay in registers.
    Lanes<N, Width> sum[W];
#pragma GCC unroll 3
    for (int w = 0; w < W; ++w) {
        sum[w] = zero_lanes<N, Width>();
    }
    for (std::ptrdiff_t r = 0; r < rows; ++r) {
        Lanes<N, Width> k;
        load(k, Kt + r * ld_kt + first);
#pragma GCC unroll 3
        for (int w = 0; w < W; ++w) {
            add_product(sum[w], k, L[w * ld_l + r]);
        }
    }
    double lanes[W][Width];
    for (int w = 0; w < W; ++w) {
        store(lanes[w], sum[w]);
    }
    const std::ptrdiff_t count = std::min<std::ptrdiff_t>(Width, cols - first);
    for (std::ptrdiff_t j = 0; j < count; ++j) {
        for (int w = 0; w < W; ++w) {
            out[(first + j) * ld_out + w] = lanes[w][j];
        }
    }
}

/// All columns of out, for W columns of L, in passes as wide as the registers allow: the 3 W / N
/// sums per 8 columns and a row of K must fit in the 16 registers. AVX-512: 16 columns per pass,
/// then 8. AVX2: 12 where 9–12 or more than 16 remain (a Loop or C2g0 element's 12 points in one
/// pass instead of two of 8, a quarter of them padding), else 8, and 4 for the last 1–4. SSE2: 8.
/// How the columns are grouped changes no sum.
template <int N, int W>
[[gnu::always_inline]] inline void backward_columns(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                                    std::ptrdiff_t cols, const double* L, std::ptrdiff_t ld_l,
                                                    double* out, std::ptrdiff_t ld_out) {
    std::ptrdiff_t first = 0;
    if constexpr (N == 8) {
        for (; first + 8 < cols; first += 16) {
            backward_pass<N, 16, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
        }
    }
    if constexpr (N == 4) {
        // first stays a multiple of 4, so first + 12 <= ld_kt (cols rounded up to 8) wherever 9 or more remain.
        for (std::ptrdiff_t left = cols - first; left > 4; left = cols - first) {
            if ((left > 8 && left <= 12) || left > 16) {
                backward_pass<N, 12, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
                first += 12;
            } else {
                backward_pass<N, 8, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
                first += 8;
            }
        }
        if (first < cols) {
            backward_pass<N, 4, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
        }
        return;
    }
    for (; first < cols; first += 8) {
        backward_pass<N, 8, W>(Kt, ld_kt, rows, first, cols, L, ld_l, out, ld_out);
    }
}

/// element_backward() with N doubles per register.
template <int N>
[[gnu::always_inline]] inline void backward(const double* __restrict Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                            std::ptrdiff_t cols, const double* __restrict L, std::ptrdiff_t ld_l,
                                            std::ptrdiff_t width, double* __restrict out, std::ptrdiff_t ld_out) {
    std::ptrdiff_t w = 0;
    for (; w + 3 <= width; w += 3) {  // three columns of L sharing the loads of K's rows
        backward_columns<N, 3>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    }
    if (width - w == 2) {
        backward_columns<N, 2>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    } else if (width - w == 1) {
        backward_columns<N, 1>(Kt, ld_kt, rows, cols, L + w * ld_l, ld_l, out + w, ld_out);
    }
}

// One copy of each product per instruction set (target_clones.h).
#ifdef LIMSURF_ISA_VARIANTS
LIMSURF_TARGET_AVX512F void forward_avx512f(const double* K, std::ptrdiff_t ld_k, std::ptrdiff_t rows,
                                            std::ptrdiff_t cols, const double* P, double* out, std::ptrdiff_t ld_out) {
    forward<8>(K, ld_k, rows, cols, P, out, ld_out);
}
LIMSURF_TARGET_AVX2 void forward_avx2(const double* K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols,
                                      const double* P, double* out, std::ptrdiff_t ld_out) {
    forward<4>(K, ld_k, rows, cols, P, out, ld_out);
}
LIMSURF_TARGET_AVX512F void backward_avx512f(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows,
                                             std::ptrdiff_t cols, const double* L, std::ptrdiff_t ld_l,
                                             std::ptrdiff_t width, double* out, std::ptrdiff_t ld_out) {
    backward<8>(Kt, ld_kt, rows, cols, L, ld_l, width, out, ld_out);
}
LIMSURF_TARGET_AVX2 void backward_avx2(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows, std::ptrdiff_t cols,
                                       const double* L, std::ptrdiff_t ld_l, std::ptrdiff_t width, double* out,
                                       std::ptrdiff_t ld_out) {
    backward<4>(Kt, ld_kt, rows, cols, L, ld_l, width, out, ld_out);
}
#endif

}  // namespace

void element_forward(const double* K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols, const double* P,
                     double* out, std::ptrdiff_t ld_out) noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    switch (vector_doubles()) {
    case 8:
        return forward_avx512f(K, ld_k, rows, cols, P, out, ld_out);
    case 4:
        return forward_avx2(K, ld_k, rows, cols, P, out, ld_out);
    default:
        break;
    }
#endif
    forward<2>(K, ld_k, rows, cols, P, out, ld_out);
}

void element_backward(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows, std::ptrdiff_t cols, const double* L,
                      std::ptrdiff_t ld_l, std::ptrdiff_t width, double* out, std::ptrdiff_t ld_out) noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    switch (vector_doubles()) {
    case 8:
        return backward_avx512f(Kt, ld_kt, rows, cols, L, ld_l, width, out, ld_out);
    case 4:
        return backward_avx2(Kt, ld_kt, rows, cols, L, ld_l, width, out, ld_out);
    default:
        break;
    }
#endif
    backward<2>(Kt, ld_kt, rows, cols, L, ld_l, width, out, ld_out);
}

}  // namespace limsurf::detail

namespace limsurf::detail {
namespace {

/// Four doubles (a row of a patch's control points) in N-double registers: one AVX2 register, or
/// two SSE2 ones.
template <int N>
using Quad = Lanes<(N < 4 ? N : 4), 4>;

/// Three sums of four (one per coordinate), from +0.
template <int N>
[[gnu::always_inline]] inline void zero_coordinates(Quad<N> (&sums)[3]) {
#pragma GCC unroll 3
    for (int c = 0; c < 3; ++c) {
        sums[c] = zero_lanes<(N < 4 ? N : 4), 4>();
    }
}

/// tensor_forward() with N doubles per register and Fixed samples per direction (element.n when
/// Fixed is 0). Vectorised across four lanes: the four control points of a grid row (along v),
/// then four samples of a row of the grid (along u). Every sum is in the same order for every N
/// and Fixed.
template <int N, int Fixed>
[[gnu::always_inline]] inline void tensor_forward_n(const TensorElement& element, const double* __restrict P,
                                                    int first_row, double* __restrict out, std::ptrdiff_t ld_out) {
    const std::ptrdiff_t n = Fixed > 0 ? Fixed : element.n;
    constexpr std::ptrdiff_t m = Fixed > 0 ? Fixed : max_tensor_samples;
    // The control points as a grid, per coordinate: grid[c][b] holds points (0…3, b).
    Quad<N> grid[3][4];
    for (int c = 0; c < 3; ++c) {
        for (int b = 0; b < 4; ++b) {
            double row[4];
            for (int a = 0; a < 4; ++a) {
                row[a] = P[16 * c + element.slot[a + 4 * b]];
            }
            load(grid[c][b], row);
        }
    }
    // Along v first: half[kv][c][j][a] = Σ_b N_b^(kv)(t_j) grid[c][b][a], b = 0, 1, 2, 3 (every
    // v-order: the rows from ∂u on need all three). Here and below the three coordinates go side by
    // side: three independent sums in flight, as a sum of products is bound by the addition's latency.
    double half[3][3][m][4];
    for (int kv = 0; kv < 3; ++kv) {
        for (std::ptrdiff_t j = 0; j < n; ++j) {
            const double* w = element.basis_by_node + (n * kv + j) * 4;
            Quad<N> sum[3];
            zero_coordinates<N>(sum);
#pragma GCC unroll 4
            for (int b = 0; b < 4; ++b) {
#pragma GCC unroll 3
                for (int c = 0; c < 3; ++c) {
                    add_product(sum[c], grid[c][b], w[b]);
                }
            }
#pragma GCC unroll 3
            for (int c = 0; c < 3; ++c) {
                store(half[kv][c][j], sum[c]);
            }
        }
    }
    // Then along u: row r at (t_i, t_j) = Σ_a N_a^(ku)(t_i) half[kv][c][j][a], a = 0, 1, 2, 3.
    const std::ptrdiff_t nn = n * n;
    for (int r = first_row; r < 6; ++r) {
        const double* U = element.basis + 4 * tensor_row_u[r] * n;
        for (std::ptrdiff_t j = 0; j < n; ++j) {
            const std::ptrdiff_t at = r * nn + j * n;
            std::ptrdiff_t i = 0;
            for (; i + 4 <= n; i += 4) {
                Quad<N> d[3];
                zero_coordinates<N>(d);
#pragma GCC unroll 4
                for (int a = 0; a < 4; ++a) {
                    Quad<N> u;
                    load(u, U + a * n + i);
#pragma GCC unroll 3
                    for (int c = 0; c < 3; ++c) {
                        add_product(d[c], u, half[tensor_row_v[r]][c][j][a]);
                    }
                }
#pragma GCC unroll 3
                for (int c = 0; c < 3; ++c) {
                    store(out + c * ld_out + at + i, d[c]);
                }
            }
            for (; i < n; ++i) {
                for (int c = 0; c < 3; ++c) {
                    const double* h = half[tensor_row_v[r]][c][j];
                    double d = 0.0;
                    for (int a = 0; a < 4; ++a) {
                        d += U[a * n + i] * h[a];
                    }
                    out[c * ld_out + at + i] = d;
                }
            }
        }
    }
}

/// tensor_backward() with N doubles per register and Fixed samples per direction (as above),
/// vectorised across the four control points of a grid row.
template <int N, int Fixed>
[[gnu::always_inline]] inline void tensor_backward_n(const TensorElement& element, const double* __restrict L,
                                                     std::ptrdiff_t ld_l, int first_row, int last_row,
                                                     double* __restrict out, std::ptrdiff_t ld_out) {
    const std::ptrdiff_t n = Fixed > 0 ? Fixed : element.n;
    constexpr std::ptrdiff_t m = Fixed > 0 ? Fixed : max_tensor_samples;
    const std::ptrdiff_t nn = n * n;
    // Along u first: half[kv][c][j][a] = Σ_r Σ_i N_a^(ku)(t_i) L(r n² + n j + i, c) over the rows r
    // whose v-order is kv, in increasing r, then i.
    bool have[3] = {false, false, false};
    double half[3][3][m][4];
    for (int r = first_row; r < last_row; ++r) {
        const int kv = tensor_row_v[r];
        const double* U = element.basis_by_node + 4 * n * tensor_row_u[r];
        for (std::ptrdiff_t j = 0; j < n; ++j) {
            Quad<N> sum[3];
            const double* l[3];
#pragma GCC unroll 3
            for (int c = 0; c < 3; ++c) {
                sum[c] = zero_lanes<(N < 4 ? N : 4), 4>();
                if (have[kv]) {
                    load(sum[c], half[kv][c][j]);
                }
                l[c] = L + c * ld_l + r * nn + j * n;
            }
            for (std::ptrdiff_t i = 0; i < n; ++i) {
                Quad<N> u;
                load(u, U + 4 * i);
#pragma GCC unroll 3
                for (int c = 0; c < 3; ++c) {
                    add_product(sum[c], u, l[c][i]);
                }
            }
#pragma GCC unroll 3
            for (int c = 0; c < 3; ++c) {
                store(half[kv][c][j], sum[c]);
            }
        }
        have[kv] = true;
    }
    // Then along v: out(slot(a, b), c) = Σ_kv Σ_j N_b^(kv)(t_j) half[kv][c][j][a], kv then j increasing.
    for (int b = 0; b < 4; ++b) {
        Quad<N> sum[3];
        zero_coordinates<N>(sum);
        for (int kv = 0; kv < 3; ++kv) {
            if (!have[kv]) {
                continue;
            }
            const double* V = element.basis + (4 * kv + b) * n;
            for (std::ptrdiff_t j = 0; j < n; ++j) {
#pragma GCC unroll 3
                for (int c = 0; c < 3; ++c) {
                    Quad<N> h;
                    load(h, half[kv][c][j]);
                    add_product(sum[c], h, V[j]);
                }
            }
        }
        for (int c = 0; c < 3; ++c) {
            double column[4];
            store(column, sum[c]);
            for (int a = 0; a < 4; ++a) {
                out[element.slot[a + 4 * b] * ld_out + c] = column[a];
            }
        }
    }
}

/// Both with N doubles per register: the square rule's common sizes (degrees 3–4, 5–6 and 7–8:
/// 3, 4 and 5 points) with their loops unrolled, any other size with n known only at run time.
template <int N>
[[gnu::always_inline]] inline void tensor_forward_isa(const TensorElement& element, const double* P, int first_row,
                                                      double* out, std::ptrdiff_t ld_out) {
    switch (element.n) {
    case 3:
        return tensor_forward_n<N, 3>(element, P, first_row, out, ld_out);
    case 4:
        return tensor_forward_n<N, 4>(element, P, first_row, out, ld_out);
    case 5:
        return tensor_forward_n<N, 5>(element, P, first_row, out, ld_out);
    default:
        return tensor_forward_n<N, 0>(element, P, first_row, out, ld_out);
    }
}

template <int N>
[[gnu::always_inline]] inline void tensor_backward_isa(const TensorElement& element, const double* L,
                                                       std::ptrdiff_t ld_l, int first_row, int last_row, double* out,
                                                       std::ptrdiff_t ld_out) {
    switch (element.n) {
    case 3:
        return tensor_backward_n<N, 3>(element, L, ld_l, first_row, last_row, out, ld_out);
    case 4:
        return tensor_backward_n<N, 4>(element, L, ld_l, first_row, last_row, out, ld_out);
    case 5:
        return tensor_backward_n<N, 5>(element, L, ld_l, first_row, last_row, out, ld_out);
    default:
        return tensor_backward_n<N, 0>(element, L, ld_l, first_row, last_row, out, ld_out);
    }
}

// A grid row has four points: AVX2 registers are as wide as the work, so an AVX-512 CPU runs
// the AVX2 copy too.
#ifdef LIMSURF_ISA_VARIANTS
LIMSURF_TARGET_AVX2 void tensor_forward_avx2(const TensorElement& element, const double* P, int first_row, double* out,
                                             std::ptrdiff_t ld_out) {
    tensor_forward_isa<4>(element, P, first_row, out, ld_out);
}
LIMSURF_TARGET_AVX2 void tensor_backward_avx2(const TensorElement& element, const double* L, std::ptrdiff_t ld_l,
                                              int first_row, int last_row, double* out, std::ptrdiff_t ld_out) {
    tensor_backward_isa<4>(element, L, ld_l, first_row, last_row, out, ld_out);
}
#endif

}  // namespace

void tensor_forward(const TensorElement& element, const double* P, int first_row, double* out,
                    std::ptrdiff_t ld_out) noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    if (vector_doubles() >= 4) {
        return tensor_forward_avx2(element, P, first_row, out, ld_out);
    }
#endif
    tensor_forward_isa<2>(element, P, first_row, out, ld_out);
}

void tensor_backward(const TensorElement& element, const double* L, std::ptrdiff_t ld_l, int first_row, int last_row,
                     double* out, std::ptrdiff_t ld_out) noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    if (vector_doubles() >= 4) {
        return tensor_backward_avx2(element, L, ld_l, first_row, last_row, out, ld_out);
    }
#endif
    tensor_backward_isa<2>(element, L, ld_l, first_row, last_row, out, ld_out);
}

}  // namespace limsurf::detail
