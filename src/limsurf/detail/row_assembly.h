// Sparse matrices built row by row: each row summed with a dense accumulator (Gustavson's
// algorithm, RowAccumulator) and written sorted, the rows split into contiguous ranges over threads
// and concatenated in order. Each row is one thread's sum in the order its terms are added, so the
// result has the same bits on any number of threads. Private: any layer.
//
// Why by hand: Eigen forms a product of row-major matrices through its conservative product into a
// column-major matrix and transposes it back (twice, to sort), on one thread, and a sum of products
// one term at a time, each into a fresh matrix. Used for Aᵀ M A (congruence.h), the products of the
// hierarchy's accumulated operators, and the vector-field design's sums of products.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/detail/row_accumulator.h"

namespace limsurf::detail {

/// @brief The rows × cols matrix whose row i is what @p fill_row(i, accumulator) adds to the
///   accumulator (RowAccumulator::add), columns sorted, structural zeros kept.
/// @param num_threads threads (0: hardware concurrency); a thread takes at least 1024 rows
/// @param fill_row    void(Index row, RowAccumulator&), called once per row from one thread
template <class FillRow>
SparseMatrix assemble_rows(Index rows, Index cols, int num_threads, const FillRow& fill_row) {
    const int threads = thread_count(num_threads, rows, 1024);
    struct Part {
        std::vector<Index> counts;
        HugeTable<Index> columns;
        HugeTable<double> values;
    };
    std::vector<Part> parts(static_cast<std::size_t>(threads));
    const auto first_row = [&](Index part) { return rows * part / threads; };
    run_ranges(threads, threads, [&](Index part_begin, Index part_end) {
        for (Index p = part_begin; p < part_end; ++p) {
            Part& out = parts[static_cast<std::size_t>(p)];
            RowAccumulator row_sum(cols);
            const Index begin = first_row(p), end = first_row(p + 1);
            out.counts.reserve(static_cast<std::size_t>(end - begin));
            for (Index i = begin; i < end; ++i) {
                fill_row(i, row_sum);
                out.counts.push_back(row_sum.flush(out.columns, out.values, static_cast<std::size_t>(end - begin)));
            }
        }
    });
    std::size_t total = 0;
    for (const Part& part : parts) {
        total += part.columns.size();
    }
    SparseMatrix out(rows, cols);
    out.resizeNonZeros(static_cast<Eigen::Index>(total));
    advise_huge_pages(out.innerIndexPtr(), sizeof(Index) * total);
    advise_huge_pages(out.valuePtr(), sizeof(double) * total);
    auto* outer = out.outerIndexPtr();
    outer[0] = 0;
    Index row = 0;
    std::size_t written = 0;
    for (const Part& part : parts) {
        std::copy(part.columns.begin(), part.columns.end(), out.innerIndexPtr() + written);
        std::copy(part.values.begin(), part.values.end(), out.valuePtr() + written);
        written += part.columns.size();
        for (const Index count : part.counts) {
            outer[row + 1] = outer[row] + count;
            ++row;
        }
    }
    return out;
}

/// @brief A B (A: n × m, B: m × k). Row i sums A(i, e) B(e, j) over the entries of A's row i by
///   ascending e, then B's row e by ascending j: the order of Eigen's conservative product, so the
///   same bits as Eigen's A * B, on any number of threads. Structural zeros are kept.
/// @pre A.cols() == B.rows()
inline SparseMatrix sparse_product(const SparseMatrix& A, const SparseMatrix& B, int num_threads) {
    return assemble_rows(static_cast<Index>(A.rows()), static_cast<Index>(B.cols()), num_threads,
                         [&](Index i, RowAccumulator& row) {
                             for (SparseMatrix::InnerIterator a(A, i); a; ++a) {
                                 for (SparseMatrix::InnerIterator b(B, a.index()); b; ++b) {
                                     row.add(static_cast<Index>(b.index()), a.value() * b.value());
                                 }
                             }
                         });
}

}  // namespace limsurf::detail
