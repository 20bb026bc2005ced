// Per-control-face assembly (private to src/limsurf/fem): the samples of one ptex face form an
// element; its dense matrix over the control vertices the surface there depends on is computed in
// parallel with the other elements and gathered into one CSR matrix (docs/fem.md "Assembly").
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/core/types.h"
#include "limsurf/detail/element_gather.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf::detail {

/// Consecutive samples of one ptex face: the elements (offsets into the samples, #elements + 1).
std::vector<Index> element_offsets(const LimitSampler& sampler);

/// @brief Assembles N matrices in one pass, each Σ_elements of the dense matrices @p add_sample
///   fills: add_sample(s, local, Ke) adds sample s's contributions to Ke[0..N-1] (k × k over the
///   element's vertices), where local[j] is the element row of sampler.vertices(s)[j]; one pass,
///   so what a sample costs (its metric) is computed once for all N. @p Block unknowns per vertex
///   (3 for displacements): Ke is (Block k) × (Block k), the unknown c of local vertex j is row
///   Block j + c, and the result's row Block v + c. Each element matrix is symmetrised,
///   ½ (Ke + Keᵀ), and the elements are gathered row by row as the SEC layer gathers its ring
///   stencils (detail/element_gather.h): exactly symmetric, the same bits for any thread count.
template <std::size_t N, Index Block = 1, class AddSample>
std::array<SparseMatrix, N> assemble_elements(const LimitSampler& sampler, const AddSample& add_sample) {
    const std::vector<Index> offsets = element_offsets(sampler);
    const Index num_elements = static_cast<Index>(offsets.size()) - 1;
    const auto at = [](Index i) { return static_cast<std::size_t>(i); };
    // Each element's global ids (Block per support vertex, in the order Ke numbers them).
    std::vector<std::vector<Index>> ids(at(num_elements));
    std::vector<Index> slot(at(sampler.num_vertices()), invalid_index);
    std::vector<Index> support;
    for (Index e = 0; e < num_elements; ++e) {
        support.clear();
        for (Index s = offsets[at(e)]; s < offsets[at(e + 1)]; ++s) {
            for (const Index v : sampler.vertices(s)) {
                if (slot[at(v)] == invalid_index) {
                    slot[at(v)] = static_cast<Index>(support.size());
                    support.push_back(v);
                }
            }
        }
        std::vector<Index>& element = ids[at(e)];
        element.reserve(support.size() * Block);
        for (const Index v : support) {
            for (Index c = 0; c < Block; ++c) {
                element.push_back(Block * v + c);
            }
            slot[at(v)] = invalid_index;
        }
    }
    std::vector<std::size_t> value_offsets(at(num_elements) + 1, 0);
    for (std::size_t e = 0; e < ids.size(); ++e) {
        value_offsets[e + 1] = value_offsets[e] + packed_size(ids[e].size());
    }
    // Every entry is written below: left uninitialised, advised for huge pages.
    std::array<std::unique_ptr<double[]>, N> values;
    for (auto& v : values) {
        v = std::make_unique_for_overwrite<double[]>(value_offsets.back());
        advise_huge_pages(v.get(), value_offsets.back() * sizeof(double));
    }
    parallel_ranges(num_elements, sampler.options().num_threads, [&](Index begin, Index end) {
        std::vector<Index> element_slot(at(sampler.num_vertices()), invalid_index);
        std::vector<Index> local;
        std::array<Eigen::MatrixXd, N> Ke;
        for (Index e = begin; e < end; ++e) {
            const std::vector<Index>& element = ids[at(e)];
            const auto k = static_cast<Index>(element.size());
            for (Index j = 0; j < k; j += Block) {
                element_slot[at(element[at(j)] / Block)] = j / Block;
            }
            for (Eigen::MatrixXd& m : Ke) {
                m.setZero(k, k);
            }
            for (Index s = offsets[at(e)]; s < offsets[at(e + 1)]; ++s) {
                const auto verts = sampler.vertices(s);
                local.resize(verts.size());
                for (std::size_t j = 0; j < verts.size(); ++j) {
                    local[j] = element_slot[at(verts[j])];
                }
                add_sample(s, std::span<const Index>(local), Ke);
            }
            for (std::size_t m = 0; m < N; ++m) {
                const Eigen::MatrixXd& K = Ke[m];
                pack_lower([&K](Eigen::Index r, Eigen::Index c) { return 0.5 * (K(r, c) + K(c, r)); }, at(k),
                           values[m].get() + value_offsets[at(e)]);
            }
            for (Index j = 0; j < k; j += Block) {
                element_slot[at(element[at(j)] / Block)] = invalid_index;
            }
        }
    });
    const auto ids_of = [&](Index e) -> const std::vector<Index>& { return ids[at(e)]; };
    std::array<SparseMatrix, N> out;
    for (std::size_t m = 0; m < N; ++m) {
        SparseMatrix gathered = gather_elements(Block * sampler.num_vertices(), num_elements, ids_of, values[m].get(),
                                                value_offsets, sampler.options().num_threads);
        out[m].swap(gathered);  // swapped: Eigen 3.4's SparseMatrix has no move assignment
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
