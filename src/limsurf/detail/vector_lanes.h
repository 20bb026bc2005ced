// A few doubles as one value, for hand-vectorised kernels compiled once per instruction set
// (target_clones.h's LIMSURF_ISA_VARIANTS): Lanes<N, Width> holds Width doubles (eight by default)
// as Width / N vectors of N doubles, the width of the copy's registers (2 for SSE2, 4 for AVX2, 8
// for AVX-512), so that every operation stays in registers. (One vector type of eight doubles for
// every copy, as before 2026-12-07, is lowered through the stack where the registers are
// narrower: on an AVX2 machine the kernels ran 20–60× slower than on AVX-512, stalled on store
// forwarding.) Every operation is lane by lane; compiled without contraction (-ffp-contract=off),
// a kernel written in them gives the same bits for every N, because no sum is reassociated and no
// multiply–add fused.
#pragma once

namespace limsurf::detail {

template <int N, int Width = 8>
struct Lanes {
    static_assert((N == 2 || N == 4 || N == 8) && Width % N == 0, "whole registers of 2, 4 or 8 doubles");
    typedef double Native __attribute__((vector_size(N * sizeof(double))));
    Native part[Width / N];
};

/// Width doubles from @p p, aligned or not: one register's worth at a time (a copy of them all at
/// once would go through the stack).
template <int N, int Width>
[[gnu::always_inline]] inline void load(Lanes<N, Width>& v, const double* p) {
#pragma GCC unroll 4
    for (int i = 0; i < Width / N; ++i) {
        __builtin_memcpy(&v.part[i], p + N * i, sizeof v.part[i]);
    }
}

template <int N, int Width>
[[gnu::always_inline]] inline void store(double* p, const Lanes<N, Width>& v) {
#pragma GCC unroll 4
    for (int i = 0; i < Width / N; ++i) {
        __builtin_memcpy(p + N * i, &v.part[i], sizeof v.part[i]);
    }
}

/// sum += row · x, lane by lane (a product, then a sum: never fused).
template <int N, int Width>
[[gnu::always_inline]] inline void add_product(Lanes<N, Width>& sum, const Lanes<N, Width>& row, double x) {
#pragma GCC unroll 4
    for (int i = 0; i < Width / N; ++i) {
        sum.part[i] += row.part[i] * x;
    }
}

/// Width zeros.
template <int N, int Width = 8>
[[gnu::always_inline]] inline Lanes<N, Width> zero_lanes() {
    Lanes<N, Width> v;
#pragma GCC unroll 4
    for (int i = 0; i < Width / N; ++i) {
        v.part[i] = typename Lanes<N, Width>::Native{};
    }
    return v;
}

}  // namespace limsurf::detail
