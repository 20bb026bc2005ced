// Placeholder: filled in by the SEC-applications work (issue 16).
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
