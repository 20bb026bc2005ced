#include "limsurf/core/parallel.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace limsurf {

int thread_count(int requested, Index n, Index items_per_thread) {
    const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    const int wanted = requested > 0 ? requested : hardware;
    return static_cast<int>(std::clamp<Index>(n / std::max<Index>(items_per_thread, 1), 1, wanted));
}

void run_ranges(Index n, int threads, const std::function<void(Index, Index)>& body) {
    if (threads <= 1) {
        body(0, n);
        return;
    }
    std::vector<std::thread> pool;
    std::exception_ptr failure;
    std::mutex failure_mutex;
    for (int t = 0; t < threads; ++t) {
        const Index begin = static_cast<Index>(std::int64_t{n} * t / threads);
        const Index end = static_cast<Index>(std::int64_t{n} * (t + 1) / threads);
        pool.emplace_back([&, begin, end] {
            try {
                body(begin, end);
            } catch (...) {
                const std::lock_guard lock(failure_mutex);
                if (!failure) {
                    failure = std::current_exception();
                }
            }
        });
    }
    for (std::thread& thread : pool) {
        thread.join();
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
}

void parallel_ranges(Index n, int num_threads, const std::function<void(Index, Index)>& body) {
    run_ranges(n, thread_count(num_threads, n), body);
}

}  // namespace limsurf
