// Dense symmetric element matrices gathered into one CSR matrix, row by row: the per-control-face
// ring-stencil assembly of the SEC layer (docs/sec.md), shared with the Galerkin layer (docs/fem.md
// "Assembly"). Private: sec and fem.
//
// The matrix is Σ_e R_eᵀ K_e R_e: element e has k_e global ids (its rows and columns, in local order)
// and a k_e × k_e symmetric matrix K_e, stored column-major (a column is then also a row). Each global
// row is summed from the elements that hold it, in ascending element order, so that entries (i, j)
// and (j, i) add the same numbers in the same order: the result is exactly symmetric, and the same
// bits for any thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <span>
#include <vector>

#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/detail/row_accumulator.h"

namespace limsurf::detail {

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
            const double* row = values + offsets[at(e)] + at(inc.local[p]) * ids.size();
            for (std::size_t lj = 0; lj < ids.size(); ++lj) {
                row_sum.add(ids[lj], row[lj]);
            }
        }
        block.counts.push_back(row_sum.flush(block.columns, block.values, at(end - begin)));
    }
    return block;
}

/// @brief The rows × rows matrix Σ_e R_eᵀ K_e R_e (see the file comment).
/// @param ids_of ids_of(e): element e's global ids, each below @p rows and none twice
/// @param values the element matrices, element e's k_e × k_e column-major from values + offsets[e]
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
