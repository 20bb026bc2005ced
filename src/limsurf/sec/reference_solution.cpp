#include "limsurf/sec/reference_solution.h"

#include <cmath>

#include "limsurf/core/error.h"
#include "limsurf/core/memory.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/operators.h"

namespace limsurf {
namespace {

/// Bytes per level-K vertex of the DEC solve: inner products, Laplacian, its free block and the
/// Cholesky factor (measured 1.9–2.4 KiB on the bundled meshes at 10⁴–2·10⁵ vertices).
constexpr std::int64_t solve_bytes_per_vertex = 2560;

RefineOptions refine_options(SchemeKind scheme, const ReferenceProblem& problem) {
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = problem.level;
    refine.scheme_options = problem.scheme_options;
    refine.kept_topologies = KeptTopologies::Finest;  // the reference is solved on level K alone
    return refine;
}

}  // namespace

std::int64_t reference_peak_bytes(const Topology& topology, SchemeKind scheme, int level) {
    const std::vector<LevelSize> sizes = predict_sizes(topology, scheme, level);
    return estimated_peak_bytes(sizes, KeptTopologies::Finest) + solve_bytes_per_vertex * sizes.back().vertices;
}

void check_reference(const Topology& topology, SchemeKind scheme, const ReferenceProblem& problem) {
    LIMSURF_CHECK(problem.level >= 0 && problem.level <= 16, InputError, "the reference level must be in [0, 16], got ",
                  problem.level);
    const std::int64_t peak = reference_peak_bytes(topology, scheme, problem.level);
    LIMSURF_CHECK(!problem.max_memory || *problem.max_memory > 0, InputError,
                  "the memory budget (max_memory) must be positive, got ", problem.max_memory.value_or(0));
    const std::int64_t budget = problem.max_memory.value_or(default_memory_budget());
    LIMSURF_CHECK(peak <= budget, InputError, "the DEC reference on level ", problem.level, " (",
                  predict_sizes(topology, scheme, problem.level).back().vertices, " vertices) needs about ",
                  format_bytes(peak), ", more than the memory budget of ", format_bytes(budget),
                  problem.max_memory ? " (max_memory)" : " (3/4 of this machine's memory)",
                  ": use a lower reference level");
    // The hierarchy's own limits (faces, 32-bit indices), without refining anything.
    const LevelSize finest = predict_sizes(topology, scheme, problem.level).back();
    LIMSURF_CHECK(finest.faces <= RefineOptions{}.max_faces && finest.corners < 2147483647LL, InputError,
                  "the DEC reference on level ", problem.level, " would have ", finest.faces,
                  " faces, more than refinement allows (", RefineOptions{}.max_faces, "): use a lower reference level");
}

ReferenceComparison compare_with_reference(const Topology& topology, const Points& X, SchemeKind scheme,
                                           const ReferenceProblem& problem, const Eigen::VectorXd& u) {
    check_reference(topology, scheme, problem);
    LIMSURF_CHECK(u.size() == topology.num_vertices(), InputError, "the solution has ", u.size(),
                  " values but the mesh has ", topology.num_vertices(), " vertices");
    RefineOptions refine = refine_options(scheme, problem);
    refine.max_memory = problem.max_memory;
    const Hierarchy h(topology, refine);
    const int K = problem.level;
    const Topology& fine = h.topology(K);
    const Points XK = h.positions(K, X);
    const Operators ops(fine, polygonal_inner_products(fine, XK));
    PoissonProblem reference_problem;
    reference_problem.f = problem.f(XK);
    if (fine.has_boundary()) {
        reference_problem.boundary_values = problem.boundary_values(XK);
    }
    const Eigen::VectorXd reference = solve_poisson(fine, ops, reference_problem).u;
    Eigen::VectorXd difference = h.apply(K, u) - reference;
    const SparseMatrix& M0 = ops.inner_products().M0;
    if (fine.is_closed()) {  // solutions are defined up to a constant
        const Eigen::VectorXd mass = M0 * Eigen::VectorXd::Ones(fine.num_vertices());
        difference.array() -= mass.dot(difference) / mass.sum();
    }
    const double reference_norm2 = reference.dot(M0 * reference);
    const double reference_max = reference.cwiseAbs().maxCoeff();
    LIMSURF_CHECK(reference_norm2 > 0.0 && reference_max > 0.0, NumericalError,
                  "the reference solution is zero: relative differences are not defined");
    ReferenceComparison out;
    out.level = K;
    out.vertices = fine.num_vertices();
    out.l2 = std::sqrt(difference.dot(M0 * difference) / reference_norm2);
    out.linf = difference.cwiseAbs().maxCoeff() / reference_max;
    LIMSURF_CHECK(std::isfinite(out.l2) && std::isfinite(out.linf), NumericalError,
                  "the differences from the reference overflow a double: rescale the right-hand side");
    return out;
}

}  // namespace limsurf
