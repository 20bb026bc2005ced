// The reference a Poisson solution is compared with in SEC §3.4 (Figs. 3, 6): the same problem
// solved with DEC on the control mesh subdivided K times, where DEC has converged far beyond the
// method under test; the subdivided solution A^K u is compared with it vertex by vertex.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// How close a solution on the control mesh is to the reference.
struct ReferenceComparison {
    int level = 0;       ///< K
    Index vertices = 0;  ///< of the level-K mesh
    double l2 = 0.0;     ///< ‖A^K u − u_K‖ in the level-K mass, relative to ‖u_K‖
    double linf = 0.0;   ///< max |A^K u − u_K| relative to max |u_K|
};

/// The problem and where to solve the reference.
struct ReferenceProblem {
    int level = 5;  ///< K >= 0
    /// The right-hand side at the rows of a #V_K × 3 position matrix (one value per row).
    std::function<Eigen::VectorXd(const Points&)> f;
    /// Dirichlet values likewise, used on open meshes (boundary vertices only).
    std::function<Eigen::VectorXd(const Points&)> boundary_values;
    SchemeOptions scheme_options;
    /// Refuse (before any work) when the estimate of reference_peak_bytes exceeds this; empty: the
    /// default budget (3/4 of the machine's memory, core/memory.h).
    std::optional<std::int64_t> max_memory = std::nullopt;
};

/// @brief Estimated peak memory (bytes) of compare_with_reference(): the hierarchy to level K (of whose
///   topologies it keeps the base and level K: KeptTopologies::Finest)
///   and the DEC solve there (about 2 KiB per level-K vertex with its Cholesky factor).
[[nodiscard]] std::int64_t reference_peak_bytes(const Topology& topology, SchemeKind scheme, int level);

/// @brief Refuses a reference that would exceed the memory budget or the hierarchy's limits:
///   call it before solving the problem under test, so that a reference that cannot be had is
///   refused at once, not after the main solve.
/// @throws InputError naming the level, the estimate and the budget
void check_reference(const Topology& topology, SchemeKind scheme, const ReferenceProblem& problem);

/// @brief Solves the problem with DEC on the level-K mesh and compares @p u (#V, a solution on the
///   control mesh) with it; on closed meshes both are taken with M0-mean zero.
/// @throws as check_reference, Hierarchy, solve_poisson; InputError when u has the wrong size
[[nodiscard]] ReferenceComparison compare_with_reference(const Topology& topology, const Points& X, SchemeKind scheme,
                                                         const ReferenceProblem& problem, const Eigen::VectorXd& u);

}  // namespace limsurf
