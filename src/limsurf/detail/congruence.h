// Aᵀ M A for a sparse A and M in one pass, row by row (Gustavson's algorithm, row_assembly.h), in
// parallel over the rows: the Laplace–Beltrami operator d0ᵀ M1 d0 of the SEC and Hodge layers.
// Private: any layer.
//
// Why by hand: Eigen forms it as two products, (Aᵀ M) and then (·) A, each through its conservative
// product into a fresh matrix, on one thread: 0.5 s of `limsurf poisson` on 51 200 quads at SEC
// level 3, where this takes a tenth of that.
#pragma once

#include "limsurf/core/types.h"
#include "limsurf/detail/row_accumulator.h"
#include "limsurf/detail/row_assembly.h"

namespace limsurf::detail {

/// @brief Aᵀ M A (#cols(A) square) for A (n × m) and M (n × n). Row i sums, in this order, over the
///   entries A(e, i) by ascending e, then M(e, f) by ascending f, then A(f, j) by ascending j: each
///   entry is one thread's sum in a fixed order, so the result has the same bits on any number of
///   threads. Structural zeros are kept.
/// @param num_threads threads (0: hardware concurrency)
inline SparseMatrix congruence(const SparseMatrix& A, const SparseMatrix& M, int num_threads) {
    const SparseMatrix At = A.transpose();  // row i: the entries of A's column i
    const auto m = static_cast<Index>(A.cols());
    return assemble_rows(m, m, num_threads, [&](Index i, RowAccumulator& row) {
        for (SparseMatrix::InnerIterator a(At, i); a; ++a) {
            for (SparseMatrix::InnerIterator mm(M, a.index()); mm; ++mm) {
                const double am = a.value() * mm.value();
                for (SparseMatrix::InnerIterator b(A, mm.index()); b; ++b) {
                    row.add(static_cast<Index>(b.index()), am * b.value());
                }
            }
        }
    });
}

}  // namespace limsurf::detail
