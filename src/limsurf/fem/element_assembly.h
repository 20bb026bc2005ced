// Per-control-face assembly (private to src/limsurf/fem): the samples of one ptex face form an
// element; its dense matrix over the control vertices the surface there depends on is computed in
// parallel with the other elements and gathered into one CSR matrix (docs/fem.md "Assembly").
#pragma once

#include <array>
#include <map>
#include <mutex>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf::detail {

/// Consecutive samples of one ptex face: the elements (offsets into the samples, #elements + 1).
std::vector<Index> element_offsets(const LimitSampler& sampler);

/// @brief Assembles N matrices in one pass, each Σ_elements of the dense matrices @p add_sample
///   fills: add_sample(s, local, Ke) adds sample s's contributions to Ke[0..N-1] (k × k over the
///   element's vertices), where local[j] is the element row of sampler.vertices(s)[j]; one pass,
///   so what a sample costs (its metric) is computed once for all N. Each result is symmetrised
///   exactly. @p Block unknowns per vertex (3 for displacements): Ke is (Block k) × (Block k), the
///   unknown c of local vertex j is row Block j + c, and the result's row Block v + c.
template <std::size_t N, Index Block = 1, class AddSample>
std::array<SparseMatrix, N> assemble_elements(const LimitSampler& sampler, const AddSample& add_sample) {
    const std::vector<Index> offsets = element_offsets(sampler);
    const Index num_elements = static_cast<Index>(offsets.size()) - 1;
    using Triplets = std::vector<Eigen::Triplet<double>>;
    // Keyed by the first element of each range, so that the triplets are summed in one order
    // whichever thread finishes first: the same input gives the same bits on every run.
    std::map<Index, std::array<Triplets, N>> parts;
    std::mutex gather;
    const auto at = [](Index i) { return static_cast<std::size_t>(i); };
    parallel_ranges(num_elements, sampler.options().num_threads, [&](Index begin, Index end) {
        std::array<Triplets, N> triplets;
        std::vector<Index> support;
        std::vector<Index> slot(at(sampler.num_vertices()), invalid_index);
        std::vector<Index> local;
        for (Index e = begin; e < end; ++e) {
            support.clear();
            for (Index s = offsets[at(e)]; s < offsets[at(e + 1)]; ++s) {
                for (const Index v : sampler.vertices(s)) {
                    if (slot[at(v)] == invalid_index) {
                        slot[at(v)] = static_cast<Index>(support.size());
                        support.push_back(v);
                    }
                }
            }
            const Index k = Block * static_cast<Index>(support.size());
            std::array<Eigen::MatrixXd, N> Ke;
            for (Eigen::MatrixXd& m : Ke) {
                m.setZero(k, k);
            }
            for (Index s = offsets[at(e)]; s < offsets[at(e + 1)]; ++s) {
                const auto verts = sampler.vertices(s);
                local.resize(verts.size());
                for (std::size_t j = 0; j < verts.size(); ++j) {
                    local[j] = slot[at(verts[j])];
                }
                add_sample(s, std::span<const Index>(local), Ke);
            }
            for (std::size_t m = 0; m < N; ++m) {
                for (Index a = 0; a < k; ++a) {
                    for (Index b = 0; b < k; ++b) {
                        triplets[m].emplace_back(Block * support[at(a / Block)] + a % Block,
                                                 Block * support[at(b / Block)] + b % Block, Ke[m](a, b));
                    }
                }
            }
            for (const Index v : support) {
                slot[at(v)] = invalid_index;
            }
        }
        const std::lock_guard<std::mutex> lock(gather);
        parts.emplace(begin, std::move(triplets));
    });
    std::array<SparseMatrix, N> out;
    for (std::size_t m = 0; m < N; ++m) {
        Triplets all;
        for (auto& [first, p] : parts) {
            all.insert(all.end(), p[m].begin(), p[m].end());
            Triplets().swap(p[m]);
        }
        SparseMatrix A(Block * sampler.num_vertices(), Block * sampler.num_vertices());
        A.setFromTriplets(all.begin(), all.end());
        out[m] = SparseMatrix(0.5 * (A + SparseMatrix(A.transpose())));
    }
    return out;
}

/// @brief Solves A u = b with the vertices where @p fixed holds set to @p values (their rows and
///   columns eliminated; A restricted to the free vertices must be positive definite).
/// @return u (#V) and the relative residual of the reduced system
std::pair<Eigen::VectorXd, double> solve_with_fixed_values(const SparseMatrix& A, const Eigen::VectorXd& b,
                                                           const std::vector<bool>& fixed,
                                                           const Eigen::VectorXd& values, const char* what);

}  // namespace limsurf::detail
