// One sparse symmetric positive-definite solver for the sec and fem layers: CHOLMOD (SuiteSparse,
// supernodal) when limsurf is built with it, Eigen's SimplicialLDLT otherwise. Both are used
// through Eigen's wrappers, on column-major copies made for the factorisation and freed after it
// (a solve reads only the factor).
//
// Factor one matrix at a time: two CHOLMOD factorisations on two threads at once (tried
// 2026-12-07 for the heat method's two factors) intermittently failed as "not positive definite"
// on matrices that factor alone. The likely cause, not confirmed: the BLAS Debian links by
// default, openblas-serial, is not safe for concurrent callers unless built with locking.
#pragma once

#include <cstdint>
#include <new>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#ifdef LIMSURF_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include "limsurf/core/error.h"
#include "limsurf/core/types.h"

namespace limsurf::detail {

class SparseCholesky {
  public:
    using ColMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;

    /// @throws NumericalError (naming @p what) when @p A has an entry that is not finite or is not
    ///   positive definite
    SparseCholesky(const SparseMatrix& A, const char* what) {
        const ColMatrix column_major(A);  // freed once factorised: the factor is all a solve reads
        if (!prepare(column_major, Pattern::of(column_major), what)) {
            return;
        }
        solver_.compute(column_major);
        check_factorised(what);
    }
    /// @brief Factorises @p A with the fill-reducing ordering and symbolic analysis of
    ///   @p same_pattern, which must have been built from a matrix of exactly A's pattern: CHOLMOD's
    ///   analysis (its METIS ordering) is a third or more of a factorisation on a mesh's Laplacian.
    ///   (Without CHOLMOD: a factorisation of its own.)
    /// @throws std::logic_error when the patterns differ; as the other constructor
    SparseCholesky(const SparseMatrix& A, const SparseCholesky& same_pattern, const char* what) {
        const ColMatrix column_major(A);
        const Pattern pattern = Pattern::of(column_major);
        if (pattern != same_pattern.pattern_) {
            throw std::logic_error("limsurf bug: SparseCholesky reused the analysis of a matrix of another pattern");
        }
        if (!prepare(column_major, pattern, what)) {
            return;
        }
#ifdef LIMSURF_HAVE_CHOLMOD
        solver_.factorize_like(same_pattern.solver_, column_major);
#else
        solver_.compute(column_major);
#endif
        check_factorised(what);
    }
    [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
        if (pattern_.rows == 0) {
            return Eigen::VectorXd(0);
        }
        Eigen::VectorXd x = solver_.solve(b);
        return x;
    }
    /// One solve per column of @p B, all in one pass through the factor.
    [[nodiscard]] Eigen::MatrixXd solve_columns(const Eigen::MatrixXd& B) const {
        if (pattern_.rows == 0) {
            return Eigen::MatrixXd(0, B.cols());
        }
        Eigen::MatrixXd X = solver_.solve(B);
        return X;
    }
    /// min |D_k| / max |D_k| over the factor's pivots (D_k = L_kk² for an LLᵀ factor; 1 for an empty
    /// matrix): at rounding level for a matrix with a (numerical) kernel.
    [[nodiscard]] double pivot_ratio() const {
        if (pattern_.rows == 0) {
            return 1.0;
        }
#ifdef LIMSURF_HAVE_CHOLMOD
        const Eigen::VectorXd d = solver_.pivots().cwiseAbs();
#else
        const Eigen::VectorXd d = solver_.vectorD().cwiseAbs();
#endif
        return d.minCoeff() / d.maxCoeff();
    }
    static const char* name() noexcept {
#ifdef LIMSURF_HAVE_CHOLMOD
        return "cholmod";
#else
        return "eigen-simplicial-ldlt";
#endif
    }

  private:
    /// What the same-pattern constructor compares, in place of the matrix (which can be a large
    /// part of a factorisation's memory and is not needed once it is factorised): the size, the
    /// number of entries and a hash (FNV-1a) of the column-major pattern.
    struct Pattern {
        Eigen::Index rows = 0;
        Eigen::Index nonzeros = 0;
        std::uint64_t hash = 0;

        static Pattern of(const ColMatrix& A) {
            std::uint64_t h = 14695981039346656037ULL;
            const auto mix = [&h](const ColMatrix::StorageIndex* first, const ColMatrix::StorageIndex* last) {
                for (; first != last; ++first) {
                    h = (h ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(*first))) * 1099511628211ULL;
                }
            };
            mix(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
            mix(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
            return {A.rows(), A.nonZeros(), h};
        }
        bool operator==(const Pattern&) const = default;
    };

    /// Records @p pattern (@p A's), checks A's entries and quiets CHOLMOD. @return false for an empty
    /// matrix (nothing to factor: CHOLMOD crashes on one)
    bool prepare(const ColMatrix& A, const Pattern& pattern, const char* what) {
        pattern_ = pattern;
        if (A.rows() == 0) {
            return false;
        }
        // An overflowed entry (a material constant or weight near the largest double) would be
        // reported by the factorisation as "not positive definite": name the cause instead.
        LIMSURF_CHECK(Eigen::Map<const Eigen::VectorXd>(A.valuePtr(), A.nonZeros()).allFinite(), NumericalError,
                      "the matrix of ", what,
                      " has an entry that is not finite: its data overflowed (a material constant, weight or "
                      "coordinate too large?)");
#ifdef LIMSURF_HAVE_CHOLMOD
        // CHOLMOD prints its warnings ("matrix not positive definite") to stdout by itself; the library
        // prints nothing: the failure is reported by the exception below.
        solver_.cholmod().print = 0;
#endif
        return true;
    }
    void check_factorised(const char* what) const {
        LIMSURF_CHECK(solver_.info() == Eigen::Success && smallest_relative_pivot() >= min_relative_pivot,
                      NumericalError, "the Cholesky factorisation of ", what,
                      " failed: the matrix is not positive definite (degenerate geometry?)");
    }

    // The simplicial LDLᵀ factorisations (CHOLMOD's for small or very sparse systems, and Eigen's) flag
    // only a zero pivot: an indefinite matrix was solved without a word. A negative pivot of rounding
    // size is not refused: singular but consistent systems (the Galerkin stiffness of the cube, whose
    // limit basis is linearly dependent) have pivots that round to either sign.
    static constexpr double min_relative_pivot = -1e-10;

    /// The smallest pivot D_k of an LDLᵀ factor over the largest |D_k|; 1 for an LLᵀ factor, whose
    /// factorisation refuses a non-positive pivot itself.
    [[nodiscard]] double smallest_relative_pivot() const {
#ifdef LIMSURF_HAVE_CHOLMOD
        return solver_.smallest_relative_pivot();
#else
        return relative_minimum(solver_.vectorD());
#endif
    }
    static double relative_minimum(const Eigen::VectorXd& d) {
        const double largest = d.cwiseAbs().maxCoeff();
        return largest > 0.0 ? d.minCoeff() / largest : 1.0;
    }

#ifdef LIMSURF_HAVE_CHOLMOD
    // Eigen's wrapper, with the factor's pivots read (Eigen keeps the factor protected).
    class Cholmod : public Eigen::CholmodDecomposition<ColMatrix, Eigen::Lower> {
      public:
        /// Factorises @p A (of @p other's pattern) from a copy of @p other's factor: its ordering and
        /// symbolic analysis are kept, its numbers recomputed.
        void factorize_like(const Cholmod& other, const ColMatrix& A) {
            this->m_cholmodFactor = cholmod_copy_factor(other.m_cholmodFactor, &this->cholmod());
            if (this->m_cholmodFactor == nullptr) {
                throw std::bad_alloc();
            }
            this->m_isInitialized = true;
            this->m_analysisIsOk = true;
            this->m_factorizationIsOk = false;
            this->factorize(A);
        }
        [[nodiscard]] double smallest_relative_pivot() const {
            const cholmod_factor* f = this->m_cholmodFactor;
            if (f == nullptr || f->is_super != 0 || f->is_ll != 0 || f->n == 0) {
                return 1.0;  // LLᵀ: CHOLMOD itself refuses a non-positive pivot
            }
            return relative_minimum(pivots());
        }
        /// The pivots D_k of the factor: the diagonal of D for LDLᵀ, L_kk² for LLᵀ (simplicial or
        /// supernodal), in the factor's (permuted) order.
        [[nodiscard]] Eigen::VectorXd pivots() const {
            const cholmod_factor* f = this->m_cholmodFactor;
            Eigen::VectorXd d(f == nullptr ? 0 : static_cast<Eigen::Index>(f->n));
            if (d.size() == 0) {
                return d;
            }
            const auto* values = static_cast<const double*>(f->x);
            if (f->is_super != 0) {
                // Supernode s holds columns super[s] .. super[s+1] − 1 as a dense column-major block of
                // pi[s+1] − pi[s] rows at px[s], its diagonal block on top.
                const auto* super = static_cast<const ColMatrix::StorageIndex*>(f->super);
                const auto* pi = static_cast<const ColMatrix::StorageIndex*>(f->pi);
                const auto* px = static_cast<const ColMatrix::StorageIndex*>(f->px);
                for (std::size_t s = 0; s < f->nsuper; ++s) {
                    const Eigen::Index rows = pi[s + 1] - pi[s];
                    for (Eigen::Index j = super[s]; j < super[s + 1]; ++j) {
                        const double l = values[px[s] + (j - super[s]) * rows + (j - super[s])];
                        d[j] = l * l;
                    }
                }
                return d;
            }
            const auto* starts = static_cast<const ColMatrix::StorageIndex*>(f->p);
            for (Eigen::Index k = 0; k < d.size(); ++k) {
                const double diagonal = values[starts[k]];  // first in each column of a simplicial factor
                d[k] = f->is_ll != 0 ? diagonal * diagonal : diagonal;
            }
            return d;
        }
    };
#endif

    Pattern pattern_;
#ifdef LIMSURF_HAVE_CHOLMOD
    Cholmod solver_;
#else
    Eigen::SimplicialLDLT<ColMatrix> solver_;
#endif
};

}  // namespace limsurf::detail
