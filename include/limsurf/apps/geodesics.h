// Geodesic distance by the heat method (Crane, Weischedel & Wardetzky 2013) with the operators of
// SEC (§2.3, §4.2) or Galerkin with the limit basis (iga, as the paper's Figs. 6 and 9 compare):
// the driver behind `limsurf geodesic` and limsurf.geodesic_distance /
// limsurf.HeatGeodesics in Python. docs/guide/geodesic.md shows it at work.
//
// The three steps, all unknowns on the control vertices (#V), with M0 and L of --method (the
// inner products' M0 and d0ᵀ M1 d0; for iga the mass and Laplace–Beltrami stiffness of the limit
// basis, fem/galerkin.h, integrated with iga_quadrature):
//   1. heat:    (M0 + t L) u = δ, δ the unit point masses at the sources; on open meshes u is the
//               average of the Neumann solution and the one with u = 0 on the boundary (Crane §3.2);
//   2. field:   X = −∇u / |∇u| and its integrated divergence b_i = ∫ ∇φ_i · X (below);
//   3. Poisson: L φ = b (one vertex pinned), then φ shifted (see "Shift" below).
// Where X is formed:
//   - dec, decsnap: per face of the control mesh (decsnap: its vertices at their limit positions),
//     b_i = Σ_f |f| ∇φ_i|_f · X_f (the cotan divergence on triangles; on polygons the gradient
//     exact for linear functions on planar polygons);
//   - iga, and sec, secsnap with HeatGradient::Limit (the default from L = 3 on): at the quadrature samples of the
//   limit
//     surface (gradient_quadrature: the rule per ptex face), ∇u the surface gradient of the limit
//     function Σ u_i Φ_i in the limit metric, b_i = Σ_s w_s X_s · ∇Φ_i(s) dA_s — the Galerkin
//     divergence of the normalised field, so that |∇φ| ≈ 1 on the limit surface; per source it
//     costs samples × support (4 samples of 16 weights per quad, 3 of 12 per triangle by default),
//     independent of the level. secsnap and sec share it (both mean the limit surface);
//   - sec, secsnap with HeatGradient::Subdivided: per face of the control mesh subdivided
//     gradient_level times (with its vertices snapped), the field there being that of the
//     subdivided heat solution A u and the divergence pulled back by Aᵀ: the SEC divergence
//     d0ᵀ M1 = (A_0^L)ᵀ d0ᵀ M1^L A_1^L of Eq. 12 applied to the level-L normalised field, with
//     per-source time ∝ the level-L faces (64× the control faces at L = 3).
// The Laplacian measures in the level-L metric, which tends to the limit's as L grows. The
// subdivided gradient at G = L normalises in that same metric, the limit gradient in the limit's:
// at L = 3 their distances are equally close to the references (within 0–25 % against DEC on the
// level-3 mesh, slightly closer to exact polyhedral geodesics for Limit), at L = 1 the mismatch
// costs Limit 2–5× (docs/guide/geodesic.md), hence HeatGradient::Automatic. Normalising on the
// control mesh (Subdivided with gradient_level 0) scales distances by the control/limit length
// ratio.
//
// Time step t = time_factor · h², h the MEAN edge length of the control mesh (Crane's choice,
// 2013 §3.2.4: t = m h², m = 1, h the mean spacing), not the paper's maximum: one long edge
// would otherwise over-smooth every distance; --time-factor (h_max/h_mean)² reproduces the
// paper's rule. Both lengths are reported.
//
// Source load: the unit point mass ∫ δ φ_i = φ_i(source): e_s for dec (hat functions); for sec and
// iga the limit stencil of s (row s of P = LimitBasis::vertex_limit_matrix), and the mass is lumped (SEC
// §3.5) in M0 + t L — with e_s or the consistent mass the coefficients of u oscillate in sign
// around the source and ∇u points the wrong way (measured; docs/guide/geodesic.md).
//
// Shift: dec and decsnap represent φ by its values at the control vertices, and φ_s = 0 (with
// several sources the mean of their values is subtracted). sec, secsnap and iga represent the limit
// function Σ φ_i Φ_i, which cannot follow the cone tip |x| of a distance at the source (the
// smooth basis rounds it); the constant is fixed instead so that the limit function at the limit
// points of the sources' 1-ring neighbours equals their chord length to the nearest source (the
// geodesic distance to O(h³)). The limit value at a source is then small but not 0 (source
// values are reported: tested below 0.3 h_mean on the bundled meshes).
// Distances between components are undefined: meshes with more than one connected component are
// refused.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/apps/laplacian_method.h"
#include "limsurf/core/types.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/inner_products.h"
#include "limsurf/sec/reference_solution.h"

namespace limsurf {

/// Where sec and secsnap normalise the heat gradient (dec and decsnap: on the control faces).
enum class HeatGradient {
    /// Subdivided when a gradient_level is given or the level L is below 3, otherwise Limit: the
    /// limit gradient is 3.5–4× cheaper per source at L = 3 and as accurate, but below L = 3 the
    /// Laplacian's level-L metric differs from the limit's enough to matter (header comment).
    Automatic,
    Limit,       ///< at quadrature samples of the limit surface (gradient_quadrature)
    Subdivided,  ///< per face of the control mesh subdivided gradient_level times
};

/// "auto", "limit", "subdivided".
[[nodiscard]] const char* to_string(HeatGradient gradient) noexcept;
/// @throws InputError naming @p name unless it is "auto", "limit" or "subdivided"
[[nodiscard]] HeatGradient parse_heat_gradient(const std::string& name);

struct HeatGeodesicsOptions {
    LaplacianMethod method = LaplacianMethod::Sec;
    int level = 3;  ///< sec, secsnap: the level L of the inner products (0..8)
    /// iga: the rule of the mass and stiffness (degree 8 with 6 tile levels, as `limsurf poisson`)
    SamplerOptions iga_quadrature{.degree = 8, .subdivide_near_extraordinary = 6, .num_threads = 0};
    HeatGradient gradient = HeatGradient::Automatic;
    /// HeatGradient::Limit and iga: the rule per ptex face (degree 2: 2 × 2 Gauss points on quads, 3 points
    /// on triangles; tile levels towards extraordinary corners). Its threads: num_threads below.
    SamplerOptions gradient_quadrature{.degree = 2, .subdivide_near_extraordinary = 0, .num_threads = 0};
    /// HeatGradient::Subdivided (and Automatic, which it then makes Subdivided): the level (0..8);
    /// −1: = level. Must stay −1 with Limit.
    int gradient_level = -1;
    double time_factor = 1.0;  ///< t = time_factor · h_mean² (> 0)
    /// t itself, overriding time_factor (> 0): the reference takes the t of the method it checks.
    std::optional<double> time_step;
    SchemeOptions scheme_options;
    int num_threads = 0;  ///< threads for the refinement and the SEC inner products (0: hardware concurrency)
};

/// One set-up of the heat method: the inner products and the factorisations of M0 + t L (and its
/// interior block on open meshes) and of L (one vertex pinned), so that each distance() costs
/// two (three on open meshes) back-substitutions and one divergence of the normalised field;
/// distances() shares the back-substitutions among many source sets.
class HeatGeodesics {
  public:
    /// @brief Prepares the heat method on the limit surface of (@p topology, @p X) (#V × 3).
    /// @throws InputError when the mesh has more than one connected component (naming a vertex of
    ///   the second), time_factor is not positive and finite, a level is out of range, X has the
    ///   wrong size, gradient_level is set with HeatGradient::Limit or with iga, iga is asked for
    ///   the subdivided gradient, a quadrature is out of LimitSampler's range; NumericalError when
    ///   a factorisation fails (degenerate faces) or the limit surface is singular at a quadrature
    ///   point; otherwise as control_inner_products (and assemble_laplace_beltrami for iga)
    HeatGeodesics(const Topology& topology, const Points& X, SchemeKind scheme,
                  const HeatGeodesicsOptions& options = {});
    HeatGeodesics(const ControlMesh& mesh, SchemeKind scheme, const HeatGeodesicsOptions& options = {});
    ~HeatGeodesics();
    HeatGeodesics(HeatGeodesics&&) noexcept;
    HeatGeodesics& operator=(HeatGeodesics&&) noexcept;

    /// @brief The distance φ (#V) from the set @p sources (control vertex indices; repeats allowed):
    ///   values at the control vertices (dec, decsnap) or control coefficients of the limit
    ///   function (sec, secsnap), shifted as the header says. Thread-safe (const).
    /// @throws InputError when @p sources is empty or names a vertex out of range (naming it);
    ///   NumericalError when the result is not finite
    [[nodiscard]] Eigen::VectorXd distance(const std::vector<Index>& sources) const;

    /// @brief distance() for several source sets at once (#V × sets; column k for source_sets[k]):
    ///   the back-substitutions take every set in one pass through each factor, which is what a
    ///   solve costs (docs/guide/geodesic.md), so per set this is several times cheaper than
    ///   distance(). Equal to distance() per column to rounding (batched triangular solves sum in
    ///   another order). No sets: #V × 0. Thread-safe (const).
    /// @throws as distance(), for the first bad set
    [[nodiscard]] Eigen::MatrixXd distances(const std::vector<std::vector<Index>>& source_sets) const;

    /// @brief The values of @p phi (#V) at @p sources as distance() measures them (control values
    ///   or limit values, see the header): within source_spread of 0 for a distance() result.
    /// @throws InputError as distance()
    [[nodiscard]] Eigen::VectorXd source_values(const Eigen::VectorXd& phi, const std::vector<Index>& sources) const;

    [[nodiscard]] Index num_vertices() const noexcept;       ///< #V of the control mesh
    [[nodiscard]] double time_step() const noexcept;         ///< t
    [[nodiscard]] double mean_edge_length() const noexcept;  ///< h_mean of the control mesh
    [[nodiscard]] double max_edge_length() const noexcept;   ///< h_max of the control mesh
    /// "control" (dec, decsnap), "limit" or "subdivided" (sec, secsnap)
    [[nodiscard]] const char* gradient() const noexcept;
    /// 0 for dec, decsnap; the level of HeatGradient::Subdivided; empty for HeatGradient::Limit
    [[nodiscard]] std::optional<int> gradient_level() const noexcept;
    /// Where the field is normalised: faces of the gradient mesh, or the limit quadrature's samples
    [[nodiscard]] Index gradient_elements() const noexcept;
    [[nodiscard]] double setup_seconds() const noexcept;          ///< inner products, operators, gradient mesh
    [[nodiscard]] double factorisation_seconds() const noexcept;  ///< the Cholesky factorisations
    [[nodiscard]] const HeatGeodesicsOptions& options() const noexcept;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// @brief The paper's reference (§4.2): the heat method with DEC on the control mesh subdivided
///   @p level times with the same time step @p t as the method checked (so that both approximate
///   the same smooth problem and the difference is the discretisation error), compared with the
///   subdivided distance A^K @p phi: l2 = ‖A^K φ − φ_K‖ in the level-K mass over ‖φ_K‖, linf =
///   max |A^K φ − φ_K| / max |φ_K|. The level-K vertex s is control vertex s (vertex points first).
/// @param max_memory the budget as ReferenceProblem::max_memory (checked before any work)
/// @throws as check_reference, Hierarchy and HeatGeodesics; InputError when phi has the wrong size
[[nodiscard]] ReferenceComparison compare_geodesics_with_reference(const Topology& topology, const Points& X,
                                                                   SchemeKind scheme, const std::vector<Index>& sources,
                                                                   const Eigen::VectorXd& phi, int level, double t,
                                                                   const SchemeOptions& scheme_options = {},
                                                                   std::optional<std::int64_t> max_memory = {});

/// Everything `limsurf geodesic` reports.
struct GeodesicResult {
    Eigen::VectorXd distance;        ///< φ (#V), see HeatGeodesics::distance
    Eigen::VectorXd limit_distance;  ///< P φ: the distance at the limit point of each control vertex
    double time_step = 0.0;
    double mean_edge_length = 0.0;
    double max_edge_length = 0.0;
    std::string gradient;               ///< HeatGeodesics::gradient
    std::optional<int> gradient_level;  ///< HeatGeodesics::gradient_level
    Eigen::VectorXd source_values;      ///< the distance at each source (HeatGeodesics::source_values)
    double setup_seconds = 0.0;
    double factorisation_seconds = 0.0;
    double solve_seconds = 0.0;  ///< the one distance() call
    std::optional<ReferenceComparison> reference;
};

struct GeodesicOptions {
    HeatGeodesicsOptions heat;
    std::optional<int> reference_level;      ///< compare with DEC on the K-times subdivided mesh
    std::optional<std::int64_t> max_memory;  ///< of the reference
};

/// @brief One distance field with its report (set-up, one solve, limit values, the reference).
/// @details A reference that cannot be had (memory budget) is refused before the main work.
/// @throws as HeatGeodesics, compare_geodesics_with_reference
[[nodiscard]] GeodesicResult geodesic_distance(const ControlMesh& mesh, SchemeKind scheme,
                                               const std::vector<Index>& sources, const GeodesicOptions& options);

}  // namespace limsurf
