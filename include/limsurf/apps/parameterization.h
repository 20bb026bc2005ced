// Parameterisation of a subdivision surface with boundary (SEC §4.1, Figs. 1 and 5): (u, v) per
// control vertex, so that the map of the limit surface is u(x) = Σ u_i φ_i(x) with the exact limit
// basis φ_i. The driver behind `limsurf parameterize` and limsurf.parameterize in Python.
//
// Two methods, both computed on the control mesh with the inner products of --method
// (dec, decsnap, sec, secsnap; sec/inner_products.h) or with the limit basis (iga: the Galerkin
// stiffness for L, the area form ∫ du ∧ dv of the limit surface for A, the Galerkin mass's total
// for the surface area; fem/galerkin.h):
//
//   free (spectral conformal, Mullen, Tong, Alliez, Desbrun 2008; SEC Eq. 17): U = (u; v) (2#V)
//     minimises the conformal energy E_C(U) = E_D(U) − A(U) = ½ Uᵀ L_C U under Uᵀ B U = 1 and
//     B-orthogonality to the constant maps, where
//       E_D = ½ (uᵀ L u + vᵀ L v), L = d0ᵀ M1 d0 (Eq. 3) of the chosen inner products;
//       A   = the signed area of the parameterised boundary, ½ Σ_{boundary edges i→j} (u_i v_j − u_j v_i)
//             over every boundary loop (interior to the left: counter-clockwise maps have positive
//             area). For sec and secsnap A is taken on the level-L boundary and pulled back,
//             (A^L)ᵀ A_L A^L, as SEC pulls back every quadratic form (Eq. 12): then E_D and A
//             measure the same level-L polygon, E_C(identity) = 0 on a planar mesh exactly, and
//             L_C stays positive semi-definite. (dec and decsnap: A on the control boundary.)
//       B   = Mullen's choice: diagonal, 1 at boundary vertices and 0 elsewhere (for u and v). It
//             fixes the scale by the boundary alone, so that the interior is free to be conformal
//             (B = M0 would trade interior conformality for spread) and the boundary is free
//             (natural boundary conditions up to the small λ B term).
//     The result is the generalised eigenvector L_C U = λ B U of the smallest λ after the two
//     constant solutions (λ = 0): Spectra's shift-invert Lanczos (SymGEigsShiftSolver) with a
//     sparse Cholesky factorisation of L_C − σB (σ < 0, so that it is positive definite), and the
//     constants removed from the Krylov space by a B-orthogonal projection after every solve
//     (deflation: they can never be returned). λ has multiplicity 2 (a rotation of the plane by
//     90° maps an eigenvector to another); any vector of that plane is a rotation of the same map.
//   circle (fixed boundary, Fig. 5): needs a topological disk. The boundary goes to the unit circle
//     by arc length of the LIMIT boundary curve (LimitBasis, Gauss–Legendre on every boundary
//     edge): the limit point of boundary vertex b_k maps to (cos θ_k, sin θ_k), θ_k = 2π s_k / ℓ.
//     Boundary control values are solved for so that the limit boundary interpolates these points
//     (the boundary limit stencil, e.g. (1, 4, 1)/6, is inverted); the interior minimises the
//     Dirichlet energy: L_II U_I = −L_IB U_B.
//
// Normalisation of the free result (the eigenvector is defined up to a similarity):
//   translation: the B-weighted mean (the mean of the boundary vertices' (u, v)) is 0 — the
//     deflation constraint itself;
//   scale: the parameter-domain area A(U) equals the area of the surface (Σ M0) — so (u, v) is
//     in the units of the mesh and a planar mesh maps onto itself;
//   rotation: the first vertex of boundary loop 0 lies on the positive u axis;
//   orientation: A(U) > 0 (counter-clockwise boundary), the orientation of the surface.
//
// Distortion (SEC Fig. 1's metric): at quadrature points of the limit surface (LimitSampler), the
// singular values σ1 ≥ σ2 of the differential of x ↦ (u(x), v(x)) from the tangent plane to R²;
// σ1/σ2 = 1 where the map is conformal. Reported: the area-weighted mean and the maximum of
// σ1/σ2 over the limit surface, and the number (and area fraction) of orientation-reversing points.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/apps/laplacian_method.h"
#include "limsurf/core/types.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/render/render.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/inner_products.h"
#include "limsurf/sec/reference_solution.h"

namespace limsurf {

/// What happens at the boundary.
enum class ParameterizationBoundary {
    Free,    ///< spectral conformal (Mullen et al. 2008): the boundary finds its own shape
    Circle,  ///< fixed: boundary on the unit circle by limit arc length, harmonic interior
};

/// "free", "circle".
[[nodiscard]] const char* to_string(ParameterizationBoundary boundary) noexcept;
/// @throws InputError naming the accepted values
[[nodiscard]] ParameterizationBoundary parse_parameterization_boundary(const std::string& name);

/// Quadrature of the distortion metric on the limit surface.
struct DistortionOptions {
    int degree = 6;       ///< degree of the rule per tile (quadrature/rules.h)
    int tiles = 3;        ///< tile levels towards extraordinary vertices (SamplerOptions)
    int num_threads = 0;  ///< 0: hardware concurrency (results do not depend on it)
};

struct ParameterizationOptions {
    LaplacianMethod method = LaplacianMethod::Sec;
    int level = 3;  ///< sec, secsnap: the level L of the inner products (0..8)
    /// iga: the rule of the stiffness, mass and area form (degree 8 with 6 tile levels, as `limsurf poisson`)
    SamplerOptions iga_quadrature{.degree = 8, .subdivide_near_extraordinary = 6, .num_threads = 0};
    ParameterizationBoundary boundary = ParameterizationBoundary::Free;
    SchemeOptions scheme_options;
    DistortionOptions distortion;
    /// Threads for the SEC inner products (sec, secsnap) and the iga quadrature; 0: hardware
    /// concurrency (the same result).
    int num_threads = 0;
    /// circle only: also solve with DEC on the K-times subdivided mesh and compare (SEC §4.1, Fig. 5).
    std::optional<int> reference_level;
    /// Memory budget of the reference (ReferenceProblem::max_memory); empty: the default.
    std::optional<std::int64_t> max_memory;
};

/// The quasi-conformal distortion σ1/σ2 of a map of the limit surface to the plane.
struct QuasiConformalDistortion {
    double mean = 0.0;          ///< area-weighted mean of σ1/σ2 over the limit surface (1: conformal)
    double max = 0.0;           ///< maximum over the quadrature points
    double area = 0.0;          ///< area of the limit surface (Σ of the quadrature weights)
    Index samples = 0;          ///< quadrature points
    Index flipped = 0;          ///< points where the map reverses orientation (det < 0)
    double flipped_area = 0.0;  ///< their area fraction, 0..1
    Index degenerate = 0;       ///< points where σ2 <= 1e-12 σ1 (ratio unbounded): left out of mean and max
};

/// Timings in seconds.
struct ParameterizationTimes {
    double assembly = 0.0;    ///< inner products, Laplacian, boundary terms
    double solve = 0.0;       ///< factorisation and eigen- or linear solve
    double distortion = 0.0;  ///< the metric's quadrature
    double reference = 0.0;   ///< the DEC reference on level K (0 without one)
};

struct ParameterizationResult {
    Eigen::MatrixXd uv;  ///< #V × 2, (u, v) per control vertex
    ParameterizationBoundary boundary = ParameterizationBoundary::Free;
    /// free: λ of L_C U = λ B U (after normalising U by Uᵀ B U = 1), ≥ 0 up to rounding.
    std::optional<double> eigenvalue;
    /// free: ‖(L_C − λB) U‖ / ‖L_C‖₁ ‖U‖ of the eigenvector; circle: ‖L_II U_I + L_IB U_B‖ / ‖L_IB U_B‖.
    double residual = 0.0;
    int iterations = 0;  ///< free: Lanczos restarts Spectra took
    Index boundary_vertices = 0;
    Index boundary_loops = 0;
    double boundary_length = 0.0;  ///< circle: the length of the limit boundary curve
    QuasiConformalDistortion distortion;
    std::optional<ReferenceComparison> reference;  ///< circle with reference_level
    ParameterizationTimes times;
    std::string solver;  ///< "cholmod" or "eigen-simplicial-ldlt"
};

/// @brief Parameterises the limit surface of @p mesh under @p scheme (Loop or Catmull–Clark).
/// @throws InputError for a closed mesh (no boundary), a mesh of several components, circle on a
///   mesh that is not a topological disk (naming its boundary-loop count and Euler characteristic),
///   a reference with free, a reference beyond the memory budget (before any work); NumericalError
///   when the eigen-solver does not converge or a factorisation fails (degenerate geometry); and as
///   control_inner_products (zero-area faces, named), LimitBasis
[[nodiscard]] ParameterizationResult parameterize(const ControlMesh& mesh, SchemeKind scheme,
                                                  const ParameterizationOptions& options);

/// The matrices of the spectral problem L_C U = λ B U, U = (u; v) stacked (2#V).
struct ConformalSystem {
    SparseMatrix conformal;      ///< L_C = diag(L, L) − A_s, symmetric (A(U) = ½ Uᵀ A_s U)
    SparseMatrix area;           ///< A_s, symmetric, on the boundary vertices only
    SparseMatrix boundary_mass;  ///< B = diag(1 at boundary vertices), 2#V × 2#V
    double surface_area = 0.0;   ///< Σ M0
};

/// @brief Assembles L_C, A_s and B for @p options.method / level (see the file comment).
/// @throws as parameterize()
[[nodiscard]] ConformalSystem conformal_system(const ControlMesh& mesh, SchemeKind scheme,
                                               const ParameterizationOptions& options);

/// @brief The (u, v) control values that put the limit boundary of a disk on the unit circle by
///   limit arc length (rows of non-boundary vertices are 0); also returns the limit boundary length.
/// @throws InputError when the mesh is not a topological disk
[[nodiscard]] std::pair<Eigen::MatrixXd, double> circle_boundary_values(const ControlMesh& mesh, SchemeKind scheme,
                                                                        const SchemeOptions& scheme_options = {});

/// @brief σ1/σ2 of the map u(x) = Σ uv_i φ_i(x) at the samples of @p sampler on the limit surface of X.
/// @param X  #V × 3 control points; @param uv #V × 2
/// @throws InputError on size mismatches or non-finite values
[[nodiscard]] QuasiConformalDistortion quasi_conformal_distortion(const LimitSampler& sampler, const Points& X,
                                                                  const Eigen::MatrixXd& uv, int num_threads = 0);

/// @brief The same at the samples a LimitSampler(basis, quadrature) would place, each sample's limit
///   weights computed, used and dropped (what parameterize() reports: a sampler of degree 6 with 3
///   tile levels held ~0.9 KB per sample). The same numbers as through the sampler.
/// @throws as the other overload, and InputError when X does not have #V rows
[[nodiscard]] QuasiConformalDistortion quasi_conformal_distortion(const LimitBasis& basis,
                                                                  const SamplerOptions& quadrature, const Points& X,
                                                                  const Eigen::MatrixXd& uv);

/// Options of render_uv_checkerboard().
struct CheckerboardOptions {
    RenderOptions render;  ///< view, size; colormap, range and colour bar are set by the function
    int squares = 10;      ///< checker squares across the parameter domain's larger side, 1..1000
    int resolution = 0;    ///< tessellation per ptex face; 0: automatic
};

/// @brief A picture of the limit surface textured by a checkerboard in (u, v): the texture view
///   of SEC Fig. 1. Each square is coloured by the sign of sin(π k u') sin(π k v'), with (u', v')
///   the parameter values scaled to [0, k] on the larger side; a conformal map shows squares.
/// @throws as tessellate_limit_surface, render_tessellation; InputError for uv of the wrong size
[[nodiscard]] RenderResult render_uv_checkerboard(const ControlMesh& mesh, SchemeKind scheme,
                                                  const SchemeOptions& scheme_options, const Eigen::MatrixXd& uv,
                                                  const CheckerboardOptions& options = {});

}  // namespace limsurf
