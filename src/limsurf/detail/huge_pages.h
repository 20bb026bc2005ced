// Transparent huge pages for the large tables of a mesh level (private: mesh and refine layers).
//
// A million-face level is a few hundred MB of tables written once, right after they are sized.
// Each 4 KiB page costs a page fault on its first touch — measured ~10 µs on the project's VM,
// ~60 % of refining 100k faces by two levels (docs/BENCHMARKS.md "Uniform refinement"). Marked for
// transparent huge pages before that first touch, a table faults in 2 MiB at a time: 512 times
// fewer faults. Linux's THP settings decide: with "always" the kernel does this anyway, with
// "madvise" (this VM, Ubuntu) only for marked memory, with "never" not at all; the advice never
// changes a result.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace limsurf::detail {

/// Tables smaller than this are left alone: few faults, and little of them 2 MiB-aligned.
inline constexpr std::size_t huge_page_minimum_bytes = std::size_t{4} << 20U;

/// @brief Marks the 2 MiB-aligned interior of [@p data, @p data + @p bytes) for transparent huge
///   pages (madvise(MADV_HUGEPAGE)); call it before the memory is first written. Advice only: it
///   does nothing below huge_page_minimum_bytes, off Linux, or when the kernel refuses.
inline void advise_huge_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (data == nullptr || bytes < huge_page_minimum_bytes) {
        return;
    }
    constexpr std::uintptr_t huge = std::uintptr_t{2} << 20U;
    const auto begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (begin + huge - 1) & ~(huge - 1);
    const std::uintptr_t last = (begin + bytes) & ~(huge - 1);
    if (first < last) {
        void* const start = reinterpret_cast<void*>(first);  // NOLINT(performance-no-int-to-ptr)
        (void)madvise(start, last - first, MADV_HUGEPAGE);
    }
#endif
}

/// @brief Gives @p table room for @p n elements in fresh memory advised for huge pages, keeping its
///   elements, so that the resize() or assign() that follows is the first touch. Does nothing when
///   the table already has the room or the room is small.
template <class Vector>
void reserve_huge(Vector& table, std::size_t n) {
    using T = typename Vector::value_type;
    if (table.capacity() >= n || n * sizeof(T) < huge_page_minimum_bytes) {
        return;
    }
    Vector fresh;
    fresh.reserve(n);
    advise_huge_pages(fresh.data(), n * sizeof(T));
    fresh.assign(table.begin(), table.end());
    table.swap(fresh);
}

/// @brief @p table becomes @p n copies of @p value, in fresh memory advised for huge pages when it
///   is large (reserve_huge; the assignment is the first touch). @pre the table's old elements are
///   not needed.
template <class Vector>
void assign_huge(Vector& table, std::size_t n, const typename Vector::value_type& value = {}) {
    reserve_huge(table, n);
    table.assign(n, value);
}

}  // namespace limsurf::detail
