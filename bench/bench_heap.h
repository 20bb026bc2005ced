// First-touch page faults are very expensive on the project's VM (~4 s per GiB of fresh
// heap) and would land on whichever contender happens to grow the heap first. So the
// benchmarks grow the heap once to LIMSURF_BENCH_PREFAULT_GIB GiB (default given by the
// caller), touch it, and keep it: glibc malloc without mmap and without trimming (glibc
// only; 0 turns this off and measures "cold", each contender paying its own page faults).
#pragma once

#include <cstddef>
#include <cstdlib>
#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace limsurf::bench {

inline void prefault_heap(double default_gib) {
#ifdef __GLIBC__
    double gib = default_gib;
    if (const char* g = std::getenv("LIMSURF_BENCH_PREFAULT_GIB")) {
        gib = std::strtod(g, nullptr);
    }
    if (!(gib > 0.0)) {
        return;
    }
    mallopt(M_MMAP_MAX, 0);         // every block from the brk heap ...
    mallopt(M_TRIM_THRESHOLD, -1);  // ... which is never given back ...
    mallopt(M_ARENA_MAX, 1);        // ... and which worker threads share (no fresh per-thread arenas)
    const auto bytes = static_cast<std::size_t>(gib * 1024.0 * 1024.0 * 1024.0);
    auto* block = static_cast<volatile char*>(std::malloc(bytes));
    if (block == nullptr) {
        return;
    }
    for (std::size_t i = 0; i < bytes; i += 4096) {
        block[i] = 1;
    }
    std::free(const_cast<char*>(block));
#else
    (void)default_gib;
#endif
}

}  // namespace limsurf::bench
