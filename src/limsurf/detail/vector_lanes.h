// Eight doubles as one value, for hand-vectorised kernels compiled once per instruction set
// (target_clones.h): GCC/Clang vector types, lowered to the widest registers of the copy being
// compiled (one AVX-512 register, two AVX2, four SSE2), every operation lane by lane. Compiled
// without contraction (-ffp-contract=off), a kernel written in them gives the same bits in
// every copy, because no sum is reassociated and no multiply-add fused.
#pragma once

namespace limsurf::detail {

typedef double Lanes __attribute__((vector_size(8 * sizeof(double))));

/// Eight doubles from @p p, aligned or not (through a reference: a vector returned by value would
/// depend on the instruction set's calling convention).
[[gnu::always_inline]] inline void load(Lanes& v, const double* p) {
    __builtin_memcpy(&v, p, sizeof v);
}

[[gnu::always_inline]] inline void store(double* p, const Lanes& v) {
    __builtin_memcpy(p, &v, sizeof v);
}

}  // namespace limsurf::detail
