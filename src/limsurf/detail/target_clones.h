// LIMSURF_TARGET_CLONES: marks a function to be compiled once per x86-64 instruction set (baseline
// SSE2, AVX2, AVX-512), the widest the CPU has being chosen when the library is loaded (GCC/Clang
// function multi-versioning through an ifunc, x86-64 Linux only; elsewhere it expands to nothing
// and the function is compiled once). Debian builds for baseline x86-64, so this is how a hot loop
// gets wider vectors without a second build of the library. The function must be a plain loop
// over raw pointers: anything it calls out of line runs in the baseline instruction set.
#pragma once

#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define LIMSURF_TARGET_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#endif
#endif
#ifndef LIMSURF_TARGET_CLONES
#define LIMSURF_TARGET_CLONES
#endif
