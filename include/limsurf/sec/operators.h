// The discrete differential operators of SEC Table 1 and the Poisson solve (SEC §2.3, §3.3).
//
// Operators takes the topology and any set of inner products (inner_products.h: DEC, DECsnap,
// SEC, SECsnap, lumped or not), so an application switches method by one argument. Operators
// whose formula holds an inverse inner product (Hodge–Laplacians, dual divergence and Laplacian)
// are applied through a sparse Cholesky factorisation computed on first use, never formed.
//
// Weak (integrated) forms, with 0-forms as vertex values, 1-forms as edge integrals:
//   primal: gradient d0, curl d1, divergence d0ᵀ M1, Laplace–Beltrami d0ᵀ M1 d0 (positive
//           semi-definite: it discretises −Δ), Hodge–Laplace M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1;
//   dual:   gradient d1ᵀ, curl d0ᵀ, divergence −d1 M1⁻¹, Laplace–Beltrami −d1 M1⁻¹ d1ᵀ,
//           Hodge–Laplace M1⁻¹ d1ᵀ M2 d1 M1⁻¹ + d0 M0⁻¹ d0ᵀ.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/sec/inner_products.h"

namespace limsurf {

class Operators {
  public:
    /// @param num_threads threads for assembling laplacian() (0: hardware concurrency; the result
    ///   does not depend on it)
    /// @throws InputError when the matrices' sizes do not match the topology
    Operators(const Topology& topology, InnerProducts inner_products, int num_threads = 0);
    ~Operators();
    Operators(Operators&&) noexcept;
    Operators& operator=(Operators&&) noexcept;

    [[nodiscard]] const InnerProducts& inner_products() const noexcept { return m_; }
    [[nodiscard]] const SparseMatrix& d0() const noexcept { return d0_; }
    [[nodiscard]] const SparseMatrix& d1() const noexcept { return d1_; }

    // --- primal forms -------------------------------------------------------------------------
    [[nodiscard]] const SparseMatrix& gradient() const noexcept { return d0_; }
    [[nodiscard]] const SparseMatrix& curl() const noexcept { return d1_; }
    /// d0ᵀ M1 (#V × #E).
    [[nodiscard]] SparseMatrix divergence() const;
    /// d0ᵀ M1 d0 (#V × #V), symmetric positive semi-definite, constants in its kernel; assembled row
    /// by row in one pass (each entry summed over the edges e at its row's vertex, then M1's row e).
    [[nodiscard]] SparseMatrix laplacian() const;
    /// (M1 d0 M0⁻¹ d0ᵀ M1 + d1ᵀ M2 d1) w for a 1-form w (#E).
    [[nodiscard]] Eigen::VectorXd hodge_laplacian_1(const Eigen::VectorXd& w) const;

    // --- dual forms ---------------------------------------------------------------------------
    [[nodiscard]] SparseMatrix dual_gradient() const { return SparseMatrix(d1_.transpose()); }
    [[nodiscard]] SparseMatrix dual_curl() const { return SparseMatrix(d0_.transpose()); }
    /// −d1 M1⁻¹ w for a dual 1-form w (#E) → #F.
    [[nodiscard]] Eigen::VectorXd dual_divergence(const Eigen::VectorXd& w) const;
    /// −d1 M1⁻¹ d1ᵀ u for a dual 0-form u (#F) → #F.
    [[nodiscard]] Eigen::VectorXd dual_laplacian(const Eigen::VectorXd& u) const;
    /// (M1⁻¹ d1ᵀ M2 d1 M1⁻¹ + d0 M0⁻¹ d0ᵀ) w for a dual 1-form w (#E).
    [[nodiscard]] Eigen::VectorXd dual_hodge_laplacian_1(const Eigen::VectorXd& w) const;

    /// M_k⁻¹ b (k = 0, 1, 2), by a cached sparse Cholesky factorisation. @throws NumericalError
    ///   when M_k is not positive definite
    [[nodiscard]] Eigen::VectorXd solve_inner_product(int k, const Eigen::VectorXd& b) const;

  private:
    struct Factors;
    SparseMatrix d0_, d1_;
    InnerProducts m_;
    std::unique_ptr<Factors> factors_;
    int num_threads_ = 0;
};

/// A Poisson problem −Δu = f on the surface: f as values at the vertices (integrated with M0),
/// and on open meshes Dirichlet values at the boundary vertices.
struct PoissonProblem {
    Eigen::VectorXd f;  ///< #V pointwise right-hand side (used when load is empty: b = M0 f)
    /// #V integrated right-hand side b_i = ∫ f φ_i dA, e.g. from load_vector(); takes precedence
    /// over f (which then only serves as values for reports).
    std::optional<Eigen::VectorXd> load;
    /// #V values of which only the boundary vertices' are used (required on open meshes).
    std::optional<Eigen::VectorXd> boundary_values;
};

struct PoissonSolution {
    Eigen::VectorXd u;          ///< #V; on closed meshes with M0-weighted mean 0
    double residual = 0.0;      ///< ‖L u − b‖ / ‖b‖ over the free vertices (b = M0 f, projected)
    double mean_removed = 0.0;  ///< closed meshes: the M0-mean subtracted from f (compatibility)
    std::string solver;         ///< "cholmod" or "eigen-simplicial-ldlt"
};

/// @brief Solves L u = M0 f (L = laplacian()). Closed meshes: f is made compatible by removing
///   its M0-weighted mean, the constant nullspace is fixed by pinning one vertex and the result is
///   shifted to mean 0. Open meshes: boundary vertices take problem.boundary_values.
/// @throws InputError on size mismatches or missing boundary values on an open mesh;
///   NumericalError when the factorisation fails or the solution is not finite
[[nodiscard]] PoissonSolution solve_poisson(const Topology& topology, const Operators& operators,
                                            const PoissonProblem& problem);

/// @brief The load vector b_i = ∫ f φ_i dA of a function given at points, consistent with the
///   inner products of @p options: DEC and DECsnap use M0 f at the control (or limit) positions;
///   SEC and SECsnap integrate at level L, b = (A_0^L)ᵀ lumped(M_0^L) f(X^L), which represents f
///   to O(h_L²) instead of the O(h_0²) of sampling it at the control vertices (SEC Eq. 11 applied to
///   the right-hand side). SEC and SECsnap are assembled as M0 is (options.assembly): per control
///   face from its ring stencil, with no level-L mesh of the whole surface, wherever the ring
///   stencils apply (Loop and Catmull–Clark meshes with form rules); else, and for
///   SecAssembly::Hierarchy, through the whole hierarchy. The two agree up to rounding.
/// @param f called with positions (n × 3) where f is needed, returns one value per row; it may be
///   called several times (blocks of points) and must be a function of the point alone
/// @throws as control_inner_products; InputError when f returns the wrong size or a non-finite
///   value, or @p X0 does not have #V rows; NumericalError when the load overflows a double
[[nodiscard]] Eigen::VectorXd load_vector(const Topology& topology, const Points& X0, SchemeKind scheme,
                                          const InnerProductOptions& options,
                                          const std::function<Eigen::VectorXd(const Points&)>& f,
                                          const SchemeOptions& scheme_options = {});

/// The sparse Cholesky back end in use: "cholmod" when limsurf was built with SuiteSparse.
[[nodiscard]] const char* sparse_cholesky_name() noexcept;

}  // namespace limsurf
