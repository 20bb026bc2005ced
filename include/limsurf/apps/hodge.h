// Helmholtz–Hodge decomposition of discrete 1-forms (SEC §2.3, §4.3, Fig. 8) in the inner products of
// any method (dec, decsnap, sec, secsnap): w = dα + δβ + h, the three parts mutually orthogonal in M1,
// and a basis of the harmonic 1-forms, of dimension b1 = 2g + b − 1 (2g on closed surfaces). The driver
// behind `limsurf hodge` and limsurf.hodge_decomposition / harmonic_basis (docs/guide/hodge.md).
//
//   exact      dα,          α from the Poisson problem d0ᵀ M1 d0 α = d0ᵀ M1 w (one vertex pinned: the
//                           constant nullspace), by sparse Cholesky;
//   harmonic   h = w's M1-projection on an M1-orthonormal basis H of the harmonic 1-forms, built once
//              from b1 tree–cotree cohomology generators, each less its exact part: d1 h = 0 and
//              d0ᵀ M1 h = 0;
//   co-exact   δβ = w − dα − h = M1⁻¹ d1ᵀ γ, M1-orthogonal to every closed form. M1⁻¹ is dense (for
//              every method here: the polygonal M1 is not diagonal either), so δβ is not solved for;
//              γ solves d1ᵀ γ = M1 δβ through d1 d1ᵀ (sparse Cholesky, one face pinned on closed
//              surfaces, where d1ᵀ 1 = 0), with one step of iterative refinement. (Until 2026-12-07:
//              the saddle-point system [[M1, d1ᵀ], [d1, 0]] by sparse LU, 4–21× slower.)
// Orthogonality follows from d1 d0 = 0 alone: ⟨dα, δβ⟩ = αᵀ (d1 d0)ᵀ γ = 0, ⟨dα, h⟩ = αᵀ d0ᵀ M1 h = 0,
// ⟨δβ, h⟩ = γᵀ d1 h = 0 — up to the solves' residuals, which iterative refinement brings to rounding.
//
// Boundaries: α is free on the boundary (natural, Neumann conditions): dα carries all the flux through
// the boundary, and δβ and h are tangent to it in the weak sense (d0ᵀ M1 (δβ + h) = 0 at boundary
// vertices too); γ is free at every face. The harmonic space then has dimension b1 = 1 − χ (2g + b − 1
// for b boundary loops): the 1-cohomology, as on closed surfaces.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/inner_products.h"

namespace limsurf {

/// The three parts of a 1-form (each #E) and their potentials.
struct HodgeParts {
    Eigen::VectorXd exact;     ///< dα = d0 α
    Eigen::VectorXd coexact;   ///< δβ = M1⁻¹ d1ᵀ γ
    Eigen::VectorXd harmonic;  ///< h = w − dα − δβ
    Eigen::VectorXd alpha;     ///< #V, M0-unweighted: the pinned vertex 0 has α = 0 before the mean is removed
    Eigen::VectorXd gamma;     ///< #F (closed surfaces: mean 0)
};

/// Factorises once for one mesh and inner products; then each decompose() is a few back-substitutions.
class HodgeDecomposer {
  public:
    /// @details Factorises the Laplacians d0ᵀ M1 d0 and d1 d1ᵀ, and builds an M1-orthonormal basis of the
    ///   b1 harmonic 1-forms from tree–cotree cohomology generators (docs/guide/hodge.md).
    /// @throws InputError when the matrices do not fit the topology, the mesh is not connected (naming
    ///   the component count) or a face meets one edge twice; NumericalError when a factorisation fails
    ///   (degenerate geometry)
    /// @param num_threads threads for assembling d0ᵀ M1 d0 (0: hardware concurrency; the result does
    ///   not depend on it)
    HodgeDecomposer(const Topology& topology, InnerProducts inner_products, int num_threads = 0);
    ~HodgeDecomposer();
    HodgeDecomposer(HodgeDecomposer&&) noexcept;
    HodgeDecomposer& operator=(HodgeDecomposer&&) noexcept;

    /// @throws InputError when w has the wrong size or a non-finite value
    [[nodiscard]] HodgeParts decompose(const Eigen::VectorXd& w) const;
    [[nodiscard]] const InnerProducts& inner_products() const noexcept;
    [[nodiscard]] const SparseMatrix& d0() const noexcept;
    [[nodiscard]] const SparseMatrix& d1() const noexcept;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// An M1-orthonormal basis of the harmonic 1-forms.
struct HarmonicBasis {
    Eigen::MatrixXd forms;  ///< #E × dimension, formsᵀ M1 forms = I
    int dimension = 0;      ///< found by the rank of projected random forms (below)
    int expected = 0;       ///< b1 = 1 − χ from the Euler characteristic (2g on closed surfaces)
    /// The eigenvalues of the M1-Gram matrix of (dimension + extra) projected random forms, descending:
    /// `dimension` of them are O(b1/#E) of the inputs' squared norms, the rest rounding.
    Eigen::VectorXd gram_eigenvalues;
    double gap = 0.0;  ///< smallest kept eigenvalue / largest dropped one (∞ as 1e300 when none dropped)
};

/// @brief The harmonic basis: projects b1 + 4 random 1-forms (seeded, std::mt19937_64) onto the harmonic
///   space (w − dα − δβ), orthonormalises them in M1 through the eigen-decomposition of their Gram matrix,
///   and counts the eigenvalues above 1e-12 × the mean squared M1-norm of the random forms as the dimension — an
///   independent determination that is then compared with b1 from the Euler characteristic.
[[nodiscard]] HarmonicBasis harmonic_basis(const HodgeDecomposer& decomposer, std::uint64_t seed = 1);

struct HodgeOptions {
    InnerProductOptions inner_products;  ///< dec, decsnap, sec, secsnap and L
    SchemeOptions scheme_options;
    bool basis = true;  ///< also compute the harmonic basis (dimension, gap)
    /// Also decompose A_1^K w with DEC on the K-times subdivided mesh and compare the parts (K >= 1).
    std::optional<int> reference_level;
};

/// A part's difference from the reference: ‖A_1^K part − part_K‖ / ‖part_K‖ (level-K DEC M1), and for the
/// whole field ‖A_1^K w − w_K‖ is 0 (the reference decomposes the subdivided input itself).
struct HodgeReference {
    int level = 0;
    Index edges = 0;
    double exact = 0.0;
    double coexact = 0.0;
    double harmonic = 0.0;
    /// ‖A(dα + δβ + h)_method − (parts)_K‖ summed as a vector field: the relative L2 error of the parts
    /// stacked, sqrt(Σ‖Δpart‖²) / sqrt(Σ‖part_K‖²).
    double total = 0.0;
};

struct HodgeResult {
    HodgeParts parts;
    double norm = 0.0;  ///< ‖w‖ in M1
    double exact_norm = 0.0, coexact_norm = 0.0, harmonic_norm = 0.0;
    /// |⟨a, b⟩| / ‖w‖² in M1 (relative to the input: a part that vanishes up to rounding, the harmonic part
    /// on a sphere, has no meaningful direction).
    double exact_coexact = 0.0, exact_harmonic = 0.0, coexact_harmonic = 0.0;
    double sum_residual = 0.0;           ///< max |dα + δβ + h − w| / max |w|
    double curl_of_exact = 0.0;          ///< max |d1 dα| / max |d1 w| (or absolute when d1 w = 0): 0 exactly
    double divergence_of_coexact = 0.0;  ///< ‖d0ᵀ M1 δβ‖ / ‖d0ᵀ M1 w‖ (or ‖M1 w‖)
    double harmonic_curl = 0.0;          ///< ‖d1 h‖ / ‖d1 w‖
    double harmonic_divergence = 0.0;    ///< ‖d0ᵀ M1 h‖ / ‖d0ᵀ M1 w‖
    int genus = 0;
    Index boundary_loops = 0;
    std::optional<HarmonicBasis> basis;
    std::optional<HodgeReference> reference;
    std::string solver;
};

/// @brief Decomposes the 1-form @p w (#E) of (@p topology, @p X0) in the inner products of options.
/// @throws InputError for a wrong size, a non-finite value, a disconnected mesh; as control_inner_products
///   and HodgeDecomposer; the reference as Hierarchy (memory)
[[nodiscard]] HodgeResult hodge_decomposition(const Topology& topology, const Points& X0, SchemeKind scheme,
                                              const Eigen::VectorXd& w, const HodgeOptions& options);

/// @brief A random 1-form: independent uniform values in [−1, 1] times the control edge lengths (a
///   field of vectors of about unit size), seeded (std::mt19937_64).
[[nodiscard]] Eigen::VectorXd random_one_form(const Topology& topology, const Points& X, std::uint64_t seed);

}  // namespace limsurf
