// Inner products of discrete forms (SEC §2.2, §3.2): M_k with ⟨a, b⟩ = aᵀ M_k b for k-forms.
//
// Polygonal (DEC) inner products on any polygon mesh, after Alexa & Wardetzky 2011, as the SEC
// paper uses them (docs/sec.md "Inner products"):
//   M0  diagonal vertex masses, Σ over incident faces of |a_f| / n_f (a_f the vector area);
//   M1  Σ_f S_fᵀ (B_f B_fᵀ / |a_f| + λ_f P_f) S_f, with B_f the edge midpoints relative to the
//       face centroid (rows), P_f the projector onto the kernel of E_fᵀ (E_f: the edge vectors of
//       the face flattened onto its plane) and λ_f = tr(B_f B_fᵀ) / (2 |a_f|); S_f picks the face's
//       edges with their orientation signs. d0ᵀ M1 d0 is the cotan Laplacian on triangles, and on
//       every regular polygon M_f = (inradius / edge length)·I, the circumcentric DEC Hodge star;
//   M2  diagonal 1 / |a_f| (2-forms are integrals over faces).
// All are symmetric positive definite on non-degenerate meshes, scale as s^{2(1−k)} and are exact
// for constant forms on planar meshes.
//
// Subdivision inner products (SEC Eq. 12): M_k^0 = (A_k^L)ᵀ M_k^L A_k^L with the polygonal M_k^L
// of the level-L mesh; SECsnap (Eq. 16) evaluates M_k^L on the level-L mesh with its vertices
// moved to their limit positions; lumping (§3.5) replaces M0 and M2 by diag(M 1). The paper's
// lumped M1 (Φ_1 replaced by dΦ_0) is not provided (docs/sec.md).
#pragma once

#include <string>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// The three inner-product matrices of one mesh: M0 #V×#V, M1 #E×#E, M2 #F×#F.
struct InnerProducts {
    SparseMatrix M0;
    SparseMatrix M1;
    SparseMatrix M2;

    InnerProducts() = default;
    /// Takes the three matrices over without copying them.
    InnerProducts(SparseMatrix&& m0, SparseMatrix&& m1, SparseMatrix&& m2) {
        M0.swap(m0);
        M1.swap(m1);
        M2.swap(m2);
    }
    // Eigen 3.4's SparseMatrix has no move constructor: moving InnerProducts swaps the matrices
    // instead of copying them (M1 at level 3 holds millions of non-zeros).
    InnerProducts(InnerProducts&& other) noexcept { swap(other); }
    InnerProducts& operator=(InnerProducts&& other) noexcept {
        swap(other);
        return *this;
    }
    InnerProducts(const InnerProducts&) = default;
    InnerProducts& operator=(const InnerProducts&) = default;
    ~InnerProducts() = default;

    void swap(InnerProducts& other) noexcept {
        M0.swap(other.M0);
        M1.swap(other.M1);
        M2.swap(other.M2);
    }
};

/// @brief Polygonal inner products of the mesh (@p topology, @p X) (#V × 3).
/// @throws InputError on a row-count mismatch; NumericalError naming the first face with
///   (numerically) zero area or a non-finite coordinate
[[nodiscard]] InnerProducts polygonal_inner_products(const Topology& topology, const Points& X);

/// How the inner products on the control mesh are computed (SEC §3.4).
enum class InnerProductMethod {
    Dec,      ///< polygonal inner products of the control mesh itself
    DecSnap,  ///< the same, with the control vertices moved to their limit positions
    Sec,      ///< Eq. 12: (A_k^L)ᵀ M_k^L A_k^L
    SecSnap,  ///< Eq. 16: as Sec, with the level-L vertices moved to their limit positions
};

/// True for Sec and SecSnap (inner products from level L, Eq. 12).
[[nodiscard]] constexpr bool uses_subdivision(InnerProductMethod m) noexcept {
    return m == InnerProductMethod::Sec || m == InnerProductMethod::SecSnap;
}
/// True for DecSnap and SecSnap (vertices moved to their limit positions).
[[nodiscard]] constexpr bool uses_limit_positions(InnerProductMethod m) noexcept {
    return m == InnerProductMethod::DecSnap || m == InnerProductMethod::SecSnap;
}

/// @brief "dec", "decsnap", "sec", "secsnap".
[[nodiscard]] const char* to_string(InnerProductMethod method) noexcept;
/// @throws InputError naming the accepted values
[[nodiscard]] InnerProductMethod parse_inner_product_method(const std::string& name);

/// How Sec and SecSnap are assembled; both give the same matrices up to rounding.
enum class SecAssembly {
    Auto,       ///< Patches; Hierarchy should a face's ring not be refinable on its own
    Patches,    ///< per control face from shared ring stencils (docs/sec.md "Assembly"); fast
    Hierarchy,  ///< refine the whole mesh with forms and pull back level by level (Eq. 10); the reference
};

struct InnerProductOptions {
    InnerProductMethod method = InnerProductMethod::Sec;
    int level = 3;        ///< L for Sec and SecSnap (0 <= L <= 8)
    bool lumped = false;  ///< replace M0 and M2 by diag(M 1) (SEC §3.5); M1 is kept
    int num_threads = 0;  ///< threads for Sec and SecSnap and their refinement (0: hardware concurrency)
    SecAssembly assembly = SecAssembly::Auto;
};

/// @brief The positions the inner products of @p method are evaluated at, from the positions
///   @p X (#V × 3) of @p topology (the control mesh, or level L for Sec and SecSnap): X itself, or
///   for DecSnap and SecSnap the limit positions of the vertices under @p scheme.
/// @throws as LimitBasis (the snapping methods)
[[nodiscard]] Points evaluation_positions(const Topology& topology, const Points& X, InnerProductMethod method,
                                          SchemeKind scheme, const SchemeOptions& scheme_options = {});

/// @brief The inner products on the control mesh (@p topology, @p X0) under @p scheme.
/// @throws as polygonal_inner_products, require_form_rules (Sec, SecSnap), and limit
///   evaluation (DecSnap, SecSnap); InputError when options.level is out of range; UnsupportedError
///   (Sec, SecSnap) for a face or vertex beyond max_limit_size (require_local_size);
///   UnsupportedError under SecAssembly::Patches when a face's ring cannot be refined on its own
///   (not expected; Auto then uses Hierarchy), naming the face; NumericalError naming the control face when a level-L
///   face inside it has zero area
[[nodiscard]] InnerProducts control_inner_products(const Topology& topology, const Points& X0, SchemeKind scheme,
                                                   const InnerProductOptions& options = {},
                                                   const SchemeOptions& scheme_options = {});

/// @brief (A_k^L)ᵀ M_k^L A_k^L for k = 0, 1, 2 from a hierarchy built with RefineOptions::forms
///   and positions @p XL of its level L (the core of Sec and SecSnap).
[[nodiscard]] InnerProducts pulled_back_inner_products(const Hierarchy& hierarchy, int level, const Points& XL);

/// @brief The Galerkin mass matrix of the exact limit basis, ∫ φ_i φ_j dA, by the quadrature of
///   @p sampler on the limit surface of @p X (#V × 3): the independent reference that M0 of Sec
///   converges to as L grows (SEC §3.2).
/// @throws InputError when X does not have sampler.num_vertices() rows
[[nodiscard]] SparseMatrix galerkin_mass_matrix(const LimitSampler& sampler, const Points& X);

/// @brief The diagonal of the polygonal M0: Σ |a_f| / n_f over the faces at each vertex (#V).
/// @throws as polygonal_inner_products
[[nodiscard]] Eigen::VectorXd polygonal_vertex_masses(const Topology& topology, const Points& X);

/// @brief diag(M 1) of a square matrix (mass lumping).
[[nodiscard]] SparseMatrix lumped(const SparseMatrix& M);

}  // namespace limsurf
