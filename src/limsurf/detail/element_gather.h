// Dense symmetric element matrices gathered into one CSR matrix, row by row: the per-control-face
// ring-stencil assembly of the SEC layer (docs/sec.md), shared with the Galerkin layer (docs/fem.md
// "Assembly"). Private: sec and fem.
//
// The matrix is Σ_e R_eᵀ K_e R_e: element e has k_e global ids (its rows and columns, in local order)
// and a k_e × k_e symmetric matrix K_e, of which the lower triangle is stored, packed column by
// column (k_e (k_e + 1) / 2 values: half the memory of the full matrix, which at 51 200 quads held
// 370 MB of SEC element matrices). Each global row is summed from the elements that hold it, in
// ascending element order and each element's columns in local order, so that entries (i, j) and
// (j, i) add the same numbers in the same order: the result is exactly symmetric, and the same bits
// for any thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <span>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/detail/row_accumulator.h"

namespace limsurf::detail {

/// The number of values of a packed k × k lower triangle.
constexpr std::size_t packed_size(std::size_t k) {
    return k * (k + 1) / 2;
}

/// Where column c of a packed k × k lower triangle starts (its diagonal entry).
constexpr std::size_t packed_column(std::size_t c, std::size_t k) {
    return c * (2 * k - c + 1) / 2;
}

/// @brief Packs the lower triangle of the k × k matrix @p full (column by column) into @p out.
/// @p full: anything with full(r, c); the caller guarantees it is symmetric where that matters.
template <class Full>
void pack_lower(const Full& full, std::size_t k, double* out) {
    for (std::size_t c = 0; c < k; ++c) {
        for (std::size_t r = c; r < k; ++r) {
            *out++ = full(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c));
        }
    }
}

/// For every global row: the (element, local index) pairs whose element rows add into it,
/// elements ascending.
struct ElementIncidence {
    std::vector<Index> offsets;  ///< #rows + 1
    std::vector<Index> element;
    std::vector<Index> local;
};

/// @p ids_of(e) gives element e's global ids (anything with size() and operator[]).
template <class IdsOf>
ElementIncidence element_incidence(Index rows, Index num_elements, const IdsOf& ids_of) {
    const auto at = [](Index i) { return static_cast<std::size_t>(i); };
    ElementIncidence inc;
    inc.offsets.assign(at(rows) + 1, 0);
    for (Index e = 0; e < num_elements; ++e) {
        const auto& ids = ids_of(e);
        for (std::size_t li = 0; li < ids.size(); ++li) {
            ++inc.offsets[at(ids[li]) + 1];
        }
    }
    for (std::size_t r = 0; r < at(rows); ++r) {
        inc.offsets[r + 1] += inc.offsets[r];
    }
    inc.element.resize(at(inc.offsets.back()));
    inc.local.resize(inc.element.size());
    std::vector<Index> cursor(inc.offsets.begin(), inc.offsets.end() - 1);
    for (Index e = 0; e < num_elements; ++e) {
        const auto& ids = ids_of(e);
        for (std::size_t li = 0; li < ids.size(); ++li) {
            const auto slot = at(cursor[at(ids[li])]++);
            inc.element[slot] = e;
            inc.local[slot] = static_cast<Index>(li);
        }
    }
    return inc;
}

/// The rows [begin, end) of a gathered matrix.
struct GatheredRows {
    Index begin = 0;
    std::vector<Index> counts;
    std::vector<Index> columns;
    std::vector<double> values;
};

/// Sums the element rows into global rows [begin, end) with a dense accumulator.
template <class IdsOf>
GatheredRows gather_element_rows(Index rows, Index begin, Index end, const ElementIncidence& inc, const IdsOf& ids_of,
                                 const double* values, const std::vector<std::size_t>& offsets) {
    const auto at = [](Index i) { return static_cast<std::size_t>(i); };
    GatheredRows block;
    block.begin = begin;
    block.counts.reserve(at(end - begin));
    RowAccumulator row_sum(rows);
    for (Index r = begin; r < end; ++r) {
        for (auto p = at(inc.offsets[at(r)]); p < at(inc.offsets[at(r) + 1]); ++p) {
            const Index e = inc.element[p];
            const auto& ids = ids_of(e);
            const std::size_t k = ids.size();
            const std::size_t li = at(inc.local[p]);
            const double* element = values + offsets[at(e)];
            for (std::size_t lj = 0; lj < li; ++lj) {  // (li, lj) below the diagonal: in column lj
                row_sum.add(ids[lj], element[packed_column(lj, k) + (li - lj)]);
            }
            const double* column = element + packed_column(li, k);  // (lj, li) from the diagonal down
            for (std::size_t lj = li; lj < k; ++lj) {
                row_sum.add(ids[lj], column[lj - li]);
            }
        }
        block.counts.push_back(row_sum.flush(block.columns, block.values, at(end - begin)));
    }
    return block;
}

/// @brief The rows × rows matrix Σ_e R_eᵀ K_e R_e (see the file comment).
/// @param ids_of ids_of(e): element e's global ids, each below @p rows and none twice
/// @param values the element matrices, element e's lower triangle packed (pack_lower) from
///   values + offsets[e], packed_size(k_e) values
template <class IdsOf>
SparseMatrix gather_elements(Index rows, Index num_elements, const IdsOf& ids_of, const double* values,
                             const std::vector<std::size_t>& offsets, int num_threads) {
    const ElementIncidence inc = element_incidence(rows, num_elements, ids_of);
    std::vector<GatheredRows> blocks;
    std::mutex blocks_mutex;
    parallel_ranges(rows, num_threads, [&](Index begin, Index end) {
        GatheredRows block = gather_element_rows(rows, begin, end, inc, ids_of, values, offsets);
        const std::lock_guard lock(blocks_mutex);
        blocks.push_back(std::move(block));
    });
    std::sort(blocks.begin(), blocks.end(),
              [](const GatheredRows& a, const GatheredRows& b) { return a.begin < b.begin; });
    SparseMatrix M(rows, rows);
    std::size_t nonzeros = 0;
    for (const GatheredRows& b : blocks) {
        nonzeros += b.values.size();
    }
    M.resizeNonZeros(static_cast<Eigen::Index>(nonzeros));
    advise_huge_pages(M.innerIndexPtr(), sizeof(Index) * nonzeros);  // before the first write
    advise_huge_pages(M.valuePtr(), sizeof(double) * nonzeros);
    std::size_t written = 0;
    Index row = 0;
    M.outerIndexPtr()[0] = 0;
    for (const GatheredRows& b : blocks) {
        std::copy(b.columns.begin(), b.columns.end(), M.innerIndexPtr() + written);
        std::copy(b.values.begin(), b.values.end(), M.valuePtr() + written);
        for (const Index count : b.counts) {
            written += static_cast<std::size_t>(count);
            M.outerIndexPtr()[++row] = static_cast<Index>(written);
        }
    }
    return M;
}

}  // namespace limsurf::detail
