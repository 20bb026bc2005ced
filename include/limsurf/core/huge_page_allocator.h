// Transparent huge pages for large tables (docs/io.md "Huge pages").
//
// A million-face level is a few hundred MB of tables written once, right after they are sized.
// Each 4 KiB page costs a page fault on its first touch — measured ~10 µs on the project's VM,
// ~60 % of refining 100k faces by two levels (docs/BENCHMARKS.md "Uniform refinement"). Marked for
// transparent huge pages before that first touch, a table faults in 2 MiB at a time: 512 times
// fewer faults. Only whole, 2 MiB-aligned huge pages can be mapped, so a table in ordinary
// malloc'ed memory keeps its unaligned head and tail (up to 2 MiB each) on small pages;
// HugePageAllocator places a large table at a 2 MiB boundary and rounds its size up to one, so all
// of it can. Linux's THP settings decide: with "always" the kernel maps huge pages anyway, with
// "madvise" (Debian's and Ubuntu's default) only for marked memory, with "never" not at all. The
// advice never changes a result.
//
// Implementation detail of the mesh and refine layers, in a public header because Topology's
// tables are vectors with this allocator.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace limsurf::detail {

/// Size and alignment of a transparent huge page on x86-64 and (4 KiB-page) AArch64 Linux.
inline constexpr std::size_t huge_page_bytes = std::size_t{2} << 20U;
/// Tables smaller than this are left alone: few faults, and rounding them up to whole huge pages
/// would waste more than it saves.
inline constexpr std::size_t huge_page_minimum_bytes = std::size_t{4} << 20U;

/// @brief Marks the 2 MiB-aligned interior of [@p data, @p data + @p bytes) for transparent huge
///   pages (madvise(MADV_HUGEPAGE)); call it before the memory is first written. Advice only: it
///   does nothing below huge_page_minimum_bytes, off Linux, or when the kernel refuses.
inline void advise_huge_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (data == nullptr || bytes < huge_page_minimum_bytes) {
        return;
    }
    const auto begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (begin + huge_page_bytes - 1) & ~(huge_page_bytes - 1);
    const std::uintptr_t last = (begin + bytes) & ~(huge_page_bytes - 1);
    if (first < last) {
        void* const start = reinterpret_cast<void*>(first);  // NOLINT(performance-no-int-to-ptr)
        (void)madvise(start, last - first, MADV_HUGEPAGE);
    }
#endif
}

#if defined(__linux__) && defined(MADV_HUGEPAGE)
/// @brief @p bytes (a multiple of huge_page_bytes) of fresh, zeroed memory mapped on its own at a
///   2 MiB boundary and advised for huge pages. Its own mapping, not malloc's: freeing it returns it
///   to the system at once, and malloc's heap and thresholds stay as they were.
/// @throws std::bad_alloc when the system has no such mapping to give
inline void* map_huge_pages(std::size_t bytes) {
    // Map one huge page more than asked, then give back the unaligned head and the rest of the tail.
    void* const raw =
        mmap(nullptr, bytes + huge_page_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (raw == MAP_FAILED) {
        throw std::bad_alloc();
    }
    const auto begin = reinterpret_cast<std::uintptr_t>(raw);
    const std::uintptr_t aligned = (begin + huge_page_bytes - 1) & ~(huge_page_bytes - 1);
    const std::size_t head = aligned - begin;
    auto* const memory = static_cast<char*>(raw) + head;
    if (head > 0) {
        (void)munmap(raw, head);
    }
    if (huge_page_bytes - head > 0) {
        (void)munmap(memory + bytes, huge_page_bytes - head);
    }
    (void)madvise(memory, bytes, MADV_HUGEPAGE);
    return memory;
}

/// @brief Gives back what map_huge_pages(@p bytes) returned.
inline void unmap_huge_pages(void* memory, std::size_t bytes) noexcept {
    (void)munmap(memory, bytes);
}
#endif

/// A std::allocator that gives allocations of huge_page_minimum_bytes and more whole huge pages:
/// a mapping of their own (map_huge_pages), 2 MiB-aligned, their size rounded up to a multiple of
/// 2 MiB (at most 2 MiB more resident memory per table), advised for huge pages before anything is
/// written. Smaller allocations, and every allocation off Linux, are std::allocator's. Stateless:
/// all instances are equal.
template <class T>
class HugePageAllocator {
  public:
    using value_type = T;

    HugePageAllocator() noexcept = default;
    template <class U>
    explicit(false) HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}

    /// @throws std::bad_alloc when the memory cannot be had
    [[nodiscard]] T* allocate(std::size_t n) {
        if (!is_huge(n)) {
            return std::allocator<T>().allocate(n);
        }
        return static_cast<T*>(map_huge_pages(rounded_bytes(n)));
    }

    void deallocate(T* memory, std::size_t n) noexcept {
        if (!is_huge(n)) {
            std::allocator<T>().deallocate(memory, n);
            return;
        }
        unmap_huge_pages(memory, rounded_bytes(n));
    }

    template <class U>
    friend bool operator==(const HugePageAllocator& /*a*/, const HugePageAllocator<U>& /*b*/) noexcept {
        return true;
    }

  private:
    /// Whether @p n elements take the huge-page path (decided by the size alone, so that
    /// deallocate(p, n) takes the path allocate(n) took).
    static bool is_huge([[maybe_unused]] std::size_t n) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        return n >= huge_page_minimum_bytes / sizeof(T) && n <= SIZE_MAX / 4 / sizeof(T) &&
               alignof(T) <= huge_page_bytes;
#else
        return false;
#endif
    }
    static std::size_t rounded_bytes(std::size_t n) noexcept {
        return (n * sizeof(T) + huge_page_bytes - 1) / huge_page_bytes * huge_page_bytes;
    }
};

/// A table that takes whole huge pages once it is large (HugePageAllocator).
template <class T>
using HugeTable = std::vector<T, HugePageAllocator<T>>;

}  // namespace limsurf::detail
