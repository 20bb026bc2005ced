// Splitting work over std::threads: contiguous ranges, one thread each, exceptions carried back to
// the caller. Used by every layer whose work is a loop over independent items (quadrature samples,
// point batches, faces); each item's result must not depend on the split, so results never depend
// on the thread count.
#pragma once

#include <functional>

#include "limsurf/core/types.h"

namespace limsurf {

/// @brief The number of threads to use for @p n items: @p requested (0: hardware concurrency),
///   but at most one per @p items_per_thread items (64: cheap items, where a thread costs more than
///   a few; 1: items that take long each) and at least 1.
[[nodiscard]] int thread_count(int requested, Index n, Index items_per_thread = 64);

/// @brief Runs body(begin, end) on exactly @p threads contiguous ranges of [0, n), one std::thread
///   each (in the calling thread when threads <= 1). The first exception thrown by a range is
///   rethrown after all threads have joined.
void run_ranges(Index n, int threads, const std::function<void(Index, Index)>& body);

/// @brief Runs body(begin, end) on contiguous ranges of [0, n) on up to @p num_threads
///   std::threads (0: hardware concurrency); serial when n is small. Exceptions propagate.
void parallel_ranges(Index n, int num_threads, const std::function<void(Index, Index)>& body);

}  // namespace limsurf
