// Hot loops compiled once per x86-64 instruction set (baseline SSE2, AVX2, AVX-512), the widest
// the CPU has being chosen at run time (x86-64 Linux with GCC or Clang; elsewhere each loop is
// compiled once, for the baseline). Debian builds for baseline x86-64, so this is how a hot loop
// gets wider vectors without a second build of the library.
//
// LIMSURF_TARGET_CLONES marks a plain loop over raw pointers that the compiler vectorises itself:
// GCC/Clang function multi-versioning (target_clones, an ifunc chosen when the library is loaded).
// Anything it calls out of line runs in the baseline instruction set.
//
// A kernel written in vector_lanes.h's Lanes<N> is a template on N instead, instantiated in one
// function per instruction set: LIMSURF_TARGET_AVX2 / LIMSURF_TARGET_AVX512F mark those, and
// vector_doubles() says which one to call (8, 4 or 2 doubles per register). Where
// LIMSURF_ISA_VARIANTS is not defined, only the baseline one (N = 2) exists.
#pragma once

#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define LIMSURF_TARGET_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#endif
#if __has_attribute(target) && (defined(__GNUC__) || defined(__clang__))
#define LIMSURF_ISA_VARIANTS 1
#define LIMSURF_TARGET_AVX2 __attribute__((target("avx2")))
#define LIMSURF_TARGET_AVX512F __attribute__((target("avx512f")))
#endif
#endif
#ifndef LIMSURF_TARGET_CLONES
#define LIMSURF_TARGET_CLONES
#endif

namespace limsurf::detail {

/// Doubles per vector register of the widest instruction set this CPU runs and the library has a
/// copy for: 8 (AVX-512), 4 (AVX2) or 2 (baseline SSE2). The same choice as LIMSURF_TARGET_CLONES'.
inline int vector_doubles() noexcept {
#ifdef LIMSURF_ISA_VARIANTS
    if (__builtin_cpu_supports("avx512f")) {
        return 8;
    }
    if (__builtin_cpu_supports("avx2")) {
        return 4;
    }
#endif
    return 2;
}

}  // namespace limsurf::detail
