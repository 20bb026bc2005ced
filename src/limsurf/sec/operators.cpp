// Operators of SEC Table 1 and the Poisson solve (operators.h).
#include "limsurf/sec/operators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/detail/congruence.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/exterior_derivative.h"
#include "limsurf/sec/patch_inner_products.h"

namespace limsurf {

/// Cholesky factors of M0, M1, M2, built on first use (thread-safe).
struct Operators::Factors {
    std::mutex mutex;
    std::array<std::unique_ptr<detail::SparseCholesky>, 3> of;
};

Operators::Operators(const Topology& topology, InnerProducts inner_products, int num_threads)
    : d0_(exterior_derivative_0(topology)), d1_(exterior_derivative_1(topology)), m_(std::move(inner_products)),
      factors_(std::make_unique<Factors>()), num_threads_(num_threads) {
    const std::array<Index, 3> sizes{topology.num_vertices(), topology.num_edges(), topology.num_faces()};
    const std::array<const SparseMatrix*, 3> ms{&m_.M0, &m_.M1, &m_.M2};
    for (std::size_t k = 0; k < 3; ++k) {
        LIMSURF_CHECK(ms[k]->rows() == sizes[k] && ms[k]->cols() == sizes[k], InputError, "M", k, " is ", ms[k]->rows(),
                      " × ", ms[k]->cols(), " but the mesh has ", sizes[k],
                      k == 0   ? " vertices"
                      : k == 1 ? " edges"
                               : " faces");
    }
}

Operators::~Operators() = default;
Operators::Operators(Operators&&) noexcept = default;
Operators& Operators::operator=(Operators&&) noexcept = default;

SparseMatrix Operators::divergence() const {
    return SparseMatrix(SparseMatrix(d0_.transpose()) * m_.M1);
}

SparseMatrix Operators::laplacian() const {
    return detail::congruence(d0_, m_.M1, num_threads_);
}

Eigen::VectorXd Operators::solve_inner_product(int k, const Eigen::VectorXd& b) const {
    LIMSURF_CHECK(k >= 0 && k <= 2, InputError, "form degree must be 0, 1 or 2, got ", k);
    const std::array<const SparseMatrix*, 3> ms{&m_.M0, &m_.M1, &m_.M2};
    LIMSURF_CHECK(b.size() == ms[static_cast<std::size_t>(k)]->rows(), InputError, "a ", k, "-form needs ",
                  ms[static_cast<std::size_t>(k)]->rows(), " values, got ", b.size());
    const detail::SparseCholesky* factor = nullptr;
    {
        const std::lock_guard<std::mutex> lock(factors_->mutex);
        auto& slot = factors_->of[static_cast<std::size_t>(k)];
        if (!slot) {
            const char* names[] = {"M0", "M1", "M2"};
            slot = std::make_unique<detail::SparseCholesky>(*ms[static_cast<std::size_t>(k)],
                                                            names[static_cast<std::size_t>(k)]);
        }
        factor = slot.get();
    }
    return factor->solve(b);
}

Eigen::VectorXd Operators::hodge_laplacian_1(const Eigen::VectorXd& w) const {
    const Eigen::VectorXd M1w = m_.M1 * w;
    const Eigen::VectorXd exact = m_.M1 * (d0_ * solve_inner_product(0, d0_.transpose() * M1w));
    return exact + d1_.transpose() * (m_.M2 * (d1_ * w));
}

Eigen::VectorXd Operators::dual_divergence(const Eigen::VectorXd& w) const {
    return -(d1_ * solve_inner_product(1, w));
}

Eigen::VectorXd Operators::dual_laplacian(const Eigen::VectorXd& u) const {
    return dual_divergence(d1_.transpose() * u);
}

Eigen::VectorXd Operators::dual_hodge_laplacian_1(const Eigen::VectorXd& w) const {
    const Eigen::VectorXd v = solve_inner_product(1, w);
    const Eigen::VectorXd curl_part = solve_inner_product(1, d1_.transpose() * (m_.M2 * (d1_ * v)));
    return curl_part + d0_ * solve_inner_product(0, d0_.transpose() * w);
}

namespace {

/// True when Sec's ring stencils can assemble on @p topology: the conditions under which
/// control_inner_products assembles its M0 from them (form rules, bounded local size).
bool ring_stencils_apply(const Topology& topology, SchemeKind scheme, const SchemeOptions& scheme_options) {
    try {
        detail::require_ring_stencils(topology, scheme, scheme_options);
    } catch (const UnsupportedError&) {
        return false;  // the whole-mesh path below takes every scheme and mesh
    }
    return true;
}

/// The load of Sec and SecSnap through the whole hierarchy: f at every level-L vertex, times its
/// polygonal mass, carried back by S0ᵀ step by step (A_0^L is never formed).
Eigen::VectorXd hierarchy_load_vector(const Topology& topology, const Points& X0, SchemeKind scheme,
                                      const InnerProductOptions& options,
                                      const std::function<Eigen::VectorXd(const Points&)>& f,
                                      const SchemeOptions& scheme_options) {
    const int level = uses_subdivision(options.method) ? options.level : 0;
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = level;
    refine.scheme_options = scheme_options;
    refine.num_threads = options.num_threads;
    refine.kept_topologies = KeptTopologies::Finest;  // the load is assembled on level L alone
    const Hierarchy h(topology, refine, X0);
    const Points XL =
        evaluation_positions(h.topology(level), h.positions(level), options.method, scheme, scheme_options);
    const Eigen::VectorXd values = f(XL);
    LIMSURF_CHECK(values.size() == XL.rows() && values.allFinite(), InputError,
                  "the right-hand side must give one finite value per point (", XL.rows(), ")");
    Eigen::VectorXd load = polygonal_vertex_masses(h.topology(level), XL).cwiseProduct(values);
    for (int l = level; l >= 1; --l) {
        load = h.step(l).S0.transpose() * load;
    }
    return load;
}

}  // namespace

Eigen::VectorXd load_vector(const Topology& topology, const Points& X0, SchemeKind scheme,
                            const InnerProductOptions& options, const std::function<Eigen::VectorXd(const Points&)>& f,
                            const SchemeOptions& scheme_options) {
    LIMSURF_CHECK(X0.rows() == topology.num_vertices(), InputError, "positions have ", X0.rows(),
                  " rows but the mesh has ", topology.num_vertices(), " vertices");
    std::optional<Eigen::VectorXd> load;
    if (uses_subdivision(options.method) && options.level >= 1 && options.assembly != SecAssembly::Hierarchy &&
        ring_stencils_apply(topology, scheme, scheme_options)) {
        load = detail::patch_load_vector(topology, X0, scheme, scheme_options, options.level,
                                         uses_limit_positions(options.method), options.num_threads,
                                         options.assembly == SecAssembly::Patches, f);
    }
    if (!load) {
        load = hierarchy_load_vector(topology, X0, scheme, options, f, scheme_options);
    }
    LIMSURF_CHECK(load->allFinite(), NumericalError,
                  "the load vector (the right-hand side integrated over the surface) ",
                  "overflows a double; rescale the right-hand side");
    return std::move(*load);
}

const char* sparse_cholesky_name() noexcept {
    return detail::SparseCholesky::name();
}

namespace {

/// The rows/columns of @p A kept by @p keep (a principal submatrix).
SparseMatrix principal_submatrix(const SparseMatrix& A, const std::vector<Index>& keep) {
    std::vector<Index> position(static_cast<std::size_t>(A.rows()), invalid_index);
    for (std::size_t i = 0; i < keep.size(); ++i) {
        position[static_cast<std::size_t>(keep[i])] = static_cast<Index>(i);
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t i = 0; i < keep.size(); ++i) {
        for (SparseMatrix::InnerIterator it(A, keep[i]); it; ++it) {
            const Index j = position[static_cast<std::size_t>(it.col())];
            if (j != invalid_index) {
                entries.emplace_back(static_cast<Index>(i), j, it.value());
            }
        }
    }
    SparseMatrix sub(static_cast<Index>(keep.size()), static_cast<Index>(keep.size()));
    sub.setFromTriplets(entries.begin(), entries.end());
    return sub;
}

}  // namespace

PoissonSolution solve_poisson(const Topology& topology, const Operators& operators, const PoissonProblem& problem) {
    const Index V = topology.num_vertices();
    LIMSURF_CHECK(problem.f.size() == V, InputError, "the right-hand side has ", problem.f.size(),
                  " values but the mesh has ", V, " vertices");
    LIMSURF_CHECK(problem.f.allFinite(), InputError, "the right-hand side has a non-finite value");
    const SparseMatrix& M0 = operators.inner_products().M0;
    const SparseMatrix L = operators.laplacian();
    LIMSURF_CHECK(!problem.load || problem.load->size() == V, InputError, "the load vector has ",
                  problem.load ? problem.load->size() : 0, " values but the mesh has ", V, " vertices");
    LIMSURF_CHECK(!problem.load || problem.load->allFinite(), InputError, "the load vector has a non-finite value");
    const bool open = !topology.is_closed();
    LIMSURF_CHECK(!open || (problem.boundary_values && problem.boundary_values->size() == V), InputError,
                  "an open mesh needs Dirichlet values at its boundary vertices (", V, " values)");
    // The problem is linear in its data: solve it for data scaled to order one by a power of two
    // (exactly), so that M0 f, the norms and the residual neither overflow nor underflow, and scale
    // the solution back at the end.
    const Eigen::VectorXd& data = problem.load ? *problem.load : problem.f;
    const int e = std::max(magnitude_exponent(data), open ? magnitude_exponent(*problem.boundary_values) : 0);
    Eigen::VectorXd b = times_power_of_two(data, -e);
    if (!problem.load) {
        b = M0 * b;
    }
    PoissonSolution out;
    out.solver = sparse_cholesky_name();
    Eigen::VectorXd u = Eigen::VectorXd::Zero(V);
    std::vector<Index> free;
    if (topology.is_closed()) {
        LIMSURF_CHECK(topology.num_components() == 1, UnsupportedError,
                      "the Poisson solve on a closed mesh needs one connected component, got ",
                      topology.num_components());
        // Compatibility: ∫ f = 0 on a closed surface; remove the M0-mean of f.
        const Eigen::VectorXd mass = M0 * Eigen::VectorXd::Ones(V);
        const double mean = b.sum() / mass.sum();
        b -= mean * mass;
        out.mean_removed = std::ldexp(mean, e);
        for (Index v = 1; v < V; ++v) {  // pin vertex 0: b ⊥ 1, so row 0 then holds as well
            free.push_back(v);
        }
    } else {
        LIMSURF_CHECK(problem.boundary_values->allFinite(), InputError, "a boundary value is not finite");
        for (Index v = 0; v < V; ++v) {
            if (topology.is_boundary_vertex(v)) {
                u(v) = std::ldexp((*problem.boundary_values)(v), -e);
            } else {
                free.push_back(v);
            }
        }
    }
    // Move the known values to the right-hand side, then solve on the free vertices.
    const Eigen::VectorXd rhs_full = b - L * u;
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(free.size()));
    for (std::size_t i = 0; i < free.size(); ++i) {
        rhs(static_cast<Eigen::Index>(i)) = rhs_full(free[i]);
    }
    const SparseMatrix L_free = principal_submatrix(L, free);
    const detail::SparseCholesky cholesky(L_free, "the Laplacian");
    const Eigen::VectorXd x = cholesky.solve(rhs);
    for (std::size_t i = 0; i < free.size(); ++i) {
        u(free[i]) = x(static_cast<Eigen::Index>(i));
    }
    LIMSURF_CHECK(u.allFinite(), NumericalError, "the Poisson solution is not finite");
    // The residual of the whole system (closed: every row, the pinned one included).
    Eigen::VectorXd r = L * u - b;
    double scale = b.norm();
    if (!topology.is_closed()) {
        for (Index v = 0; v < V; ++v) {
            if (topology.is_boundary_vertex(v)) {
                r(v) = 0.0;
            }
        }
        scale = rhs.norm();
    }
    out.residual = scale > 0.0 ? r.norm() / scale : r.norm();
    if (topology.is_closed()) {
        const Eigen::VectorXd mass = M0 * Eigen::VectorXd::Ones(V);
        u.array() -= mass.dot(u) / mass.sum();
    }
    out.u = times_power_of_two(u, e);
    LIMSURF_CHECK(out.u.allFinite(), NumericalError, "the Poisson solution overflows a double (the data reach about 2^",
                  e, "): rescale the right-hand side or the boundary values");
    LIMSURF_CHECK(std::isfinite(out.residual), NumericalError, "the residual of the Poisson solve is not finite");
    return out;
}

}  // namespace limsurf
