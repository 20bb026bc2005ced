// Huge pages for tables that are not HugeTables (std::vector with the default allocator, Eigen
// arrays): their 2 MiB-aligned interior is advised; head and tail stay on small pages
// (limsurf/core/huge_page_allocator.h says why and what the kernel's settings do). Private: mesh
// and refine layers.
#pragma once

#include <cstddef>

#include "limsurf/core/huge_page_allocator.h"

namespace limsurf::detail {

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
