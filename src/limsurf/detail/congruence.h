// Aᵀ M A for a sparse A and M in one pass, row by row (Gustavson's algorithm, RowAccumulator), in
// parallel over the rows: the Laplace–Beltrami operator d0ᵀ M1 d0 of the SEC and Hodge layers.
// Private: any layer.
//
// Why by hand: Eigen forms it as two products, (Aᵀ M) and then (·) A, each through its conservative
// product into a fresh matrix, on one thread: 0.5 s of `limsurf poisson` on 51 200 quads at SEC
// level 3, where this takes a tenth of that.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/detail/row_accumulator.h"

namespace limsurf::detail {

/// @brief Aᵀ M A (#cols(A) square) for A (n × m) and M (n × n). Row i sums, in this order, over the
///   entries A(e, i) by ascending e, then M(e, f) by ascending f, then A(f, j) by ascending j: each
///   entry is one thread's sum in a fixed order, so the result has the same bits on any number of
///   threads. Structural zeros are kept.
/// @param num_threads threads (0: hardware concurrency)
inline SparseMatrix congruence(const SparseMatrix& A, const SparseMatrix& M, int num_threads) {
    const SparseMatrix At = A.transpose();  // row i: the entries of A's column i
    const auto m = static_cast<Index>(A.cols());
    const int threads = thread_count(num_threads, m, 1024);
    struct Part {
        std::vector<Index> counts;
        HugeTable<Index> columns;
        HugeTable<double> values;
    };
    std::vector<Part> parts(static_cast<std::size_t>(threads));
    const auto first_row = [&](Index part) { return m * part / threads; };
    run_ranges(threads, threads, [&](Index part_begin, Index part_end) {
        for (Index p = part_begin; p < part_end; ++p) {
            Part& out = parts[static_cast<std::size_t>(p)];
            RowAccumulator row_sum(m);
            const Index begin = first_row(p), end = first_row(p + 1);
            out.counts.reserve(static_cast<std::size_t>(end - begin));
            for (Index i = begin; i < end; ++i) {
                for (SparseMatrix::InnerIterator a(At, i); a; ++a) {
                    for (SparseMatrix::InnerIterator mm(M, a.index()); mm; ++mm) {
                        const double am = a.value() * mm.value();
                        for (SparseMatrix::InnerIterator b(A, mm.index()); b; ++b) {
                            row_sum.add(static_cast<Index>(b.index()), am * b.value());
                        }
                    }
                }
                out.counts.push_back(row_sum.flush(out.columns, out.values, static_cast<std::size_t>(end - begin)));
            }
        }
    });
    std::size_t total = 0;
    for (const Part& part : parts) {
        total += part.columns.size();
    }
    SparseMatrix out(m, m);
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

}  // namespace limsurf::detail
