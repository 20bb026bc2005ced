// core/huge_page_allocator.h: large tables start on a 2 MiB boundary and are advised for
// transparent huge pages (the kernel marks their mapping eligible), small ones are
// std::allocator's, and a HugeTable behaves as a vector through growth, copies and moves.
#include <cstdint>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/huge_page_allocator.h"

namespace limsurf::detail {
namespace {

std::uintptr_t address(const void* p) {
    return reinterpret_cast<std::uintptr_t>(p);
}

/// The kernel's transparent-huge-page mode ("always", "madvise", "never"), empty when unknown.
std::string thp_mode() {
    std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string word;
    while (file >> word) {
        if (word.size() > 2 && word.front() == '[' && word.back() == ']') {
            return word.substr(1, word.size() - 2);
        }
    }
    return {};
}

/// The "THPeligible:" value of the mapping of /proc/self/smaps that holds @p p (-1 when absent).
int thp_eligible(const void* p) {
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t begin = 0;
        std::uintptr_t end = 0;
        char dash = 0;
        std::istringstream header(line);
        if (header >> std::hex >> begin >> dash >> end && dash == '-' && line.find(':') > line.find(' ')) {
            inside = begin <= address(p) && address(p) < end;
            continue;
        }
        if (inside && line.rfind("THPeligible:", 0) == 0) {
            return std::stoi(line.substr(12));
        }
    }
    return -1;
}

TEST(HugePageAllocator, LargeTablesStartOnAHugePageBoundary) {
    HugeTable<std::int32_t> table(std::size_t{3} << 20U, 7);  // 12 MiB
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    EXPECT_EQ(address(table.data()) % huge_page_bytes, 0U);
#endif
    EXPECT_EQ(std::accumulate(table.begin(), table.end(), std::int64_t{0}), std::int64_t{7} * (3 << 20));
}

TEST(HugePageAllocator, LargeTablesAreEligibleForHugePages) {
#if !defined(__linux__) || !defined(MADV_HUGEPAGE)
    GTEST_SKIP() << "transparent huge pages are Linux's";
#else
    const std::string mode = thp_mode();
    if (mode != "always" && mode != "madvise") {
        GTEST_SKIP() << "transparent huge pages are '" << mode << "' on this machine (not always or madvise)";
    }
    HugeTable<double> table(std::size_t{1} << 20U, 1.0);  // 8 MiB
    const int eligible = thp_eligible(table.data());
    if (eligible < 0) {
        GTEST_SKIP() << "this kernel's /proc/self/smaps has no THPeligible field";
    }
    EXPECT_EQ(eligible, 1);
    if (mode == "madvise") {
        // The control: an ordinary table of 64 MiB (above glibc's largest mmap threshold, so a
        // mapping of its own) is not advised, and not eligible.
        const std::vector<double> ordinary(std::size_t{8} << 20U, 1.0);
        EXPECT_EQ(thp_eligible(ordinary.data()), 0);
    }
#endif
}

TEST(HugePageAllocator, SmallTablesAreOrdinaryAllocations) {
    // Whatever their address, they work; and the size alone decides the path, so freeing after
    // shrinking (capacity kept) and after growing across the threshold are both sound.
    HugeTable<std::int32_t> table(100, 1);
    for (int i = 0; i < (2 << 20); ++i) {
        table.push_back(i);  // grows from small to large allocations
    }
    EXPECT_EQ(table.size(), 100U + (2U << 20U));
    EXPECT_EQ(table[100 + 12345], 12345);
    table.resize(10);
    table.shrink_to_fit();  // large back to small
    EXPECT_EQ(table.size(), 10U);
}

TEST(HugePageAllocator, TablesCopyAndMoveAsVectors) {
    HugeTable<std::int32_t> a(std::size_t{2} << 20U);
    std::iota(a.begin(), a.end(), 0);
    HugeTable<std::int32_t> b = a;
    EXPECT_EQ(a, b);
    HugeTable<std::int32_t> c = std::move(a);
    EXPECT_EQ(b, c);
    EXPECT_EQ(HugePageAllocator<int>(), HugePageAllocator<double>());
}

}  // namespace
}  // namespace limsurf::detail
