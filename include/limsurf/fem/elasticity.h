// Planar linear elasticity on the limit surface of a planar Catmull–Clark control mesh
// (iga-with-catmull-clark §6: the block of material with imperfections; §4 boundary and corner
// patches). The displacement u = Σ u_i φ_i has two control values per control vertex (unknown 2i + c,
// c = 0 for x, 1 for y); the domain is the limit surface itself, so regular, extraordinary, boundary
// and corner patches all carry the basis (corner vertices interpolated, as the paper's phantom points).
//
//   a(u, v) = ∫ ε(v) : σ(u) dA,   σ = 2μ ε + λ tr(ε) I,   ε = ∇ˢu,
//
// in Voigt form σ = C ε with ε = (ε_xx, ε_yy, γ_xy = 2 ε_xy) and σ = (σ_xx, σ_yy, σ_xy):
//   plane strain: C = E / ((1 + ν)(1 − 2ν)) [[1 − ν, ν, 0], [ν, 1 − ν, 0], [0, 0, (1 − 2ν)/2]];
//   plane stress: C = E / (1 − ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1 − ν)/2]].
// A pure shear (ε_xx = ε_yy = 0) gives the same σ under both; a volumetric strain does not.
//
// Periodic conditions (§6, a representative volume element): u = (Fᵐ − I) x + ũ with the fluctuation ũ
// periodic between opposite sides of the rectangle. On the limit space a side's trace is the cubic
// B-spline of its boundary control values (the corners interpolated), so ũ is periodic exactly when
// the control values of matching boundary vertices are equal: the control mesh's left and right sides
// must carry boundary vertices at the same heights, the bottom and top sides at the same abscissae
// (match_periodic_sides checks it). Under pure periodic conditions the rigid translations are the only
// kernel (a rotation's fluctuation is not periodic); they are removed by pinning ũ = 0 at the
// bottom-left corner. docs/guide/elasticity.md.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"

namespace limsurf {

/// Plane strain (ε_zz = 0: a long body, the paper's block) or plane stress (σ_zz = 0: a thin sheet).
enum class PlaneModel { Strain, Stress };

/// "strain" / "stress".
[[nodiscard]] const char* to_string(PlaneModel model) noexcept;

/// An isotropic linear elastic material.
struct ElasticMaterial {
    double E = 1.0;   ///< Young's modulus, > 0
    double nu = 0.3;  ///< Poisson's ratio, in (−1, 0.5)
};

/// @brief The 3 × 3 Voigt matrix C of @p material (σ = C ε, ε with γ_xy = 2 ε_xy).
/// @throws InputError unless E > 0 and ν ∈ (−1, 0.5), both finite
[[nodiscard]] Eigen::Matrix3d elasticity_matrix(const ElasticMaterial& material, PlaneModel model);

/// The materials of a plane body: face f of the basis's control mesh is made of
/// materials[face_material[f]] (every face of materials[0] when face_material is empty).
struct ElasticBody {
    std::vector<ElasticMaterial> materials{ElasticMaterial{}};
    std::vector<Index> face_material;  ///< #F control faces, or empty
    PlaneModel model = PlaneModel::Strain;
};

/// @brief Checks the materials and the face assignment against @p num_faces control faces.
/// @throws InputError for no material, a material out of range (naming its index), a face_material
///   of the wrong length or naming a material that does not exist (naming the face)
void check_elastic_body(const ElasticBody& body, Index num_faces);

/// @brief The stiffness K (2#V × 2#V, symmetric, positive semi-definite with the rigid motions as
///   its kernel) on the limit surface of the planar control points @p X (#V × 3, z = 0), per
///   control face with @p basis's ptex faces (the pattern of the SEC layer), in parallel.
/// @pre @p sampler was built on @p basis
/// @throws InputError as check_elastic_body, for X of the wrong shape or off the plane z = 0;
///   NumericalError at a quadrature point where the map is degenerate or folds (det J ≤ 0 against
///   the orientation of the rest), naming its ptex face
[[nodiscard]] SparseMatrix assemble_elasticity(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                                               const ElasticBody& body);

/// A vector field on the plane: rows of positions (#P × 3) in, rows of (f_x, f_y) (#P × 2) out.
using PlaneVectorFunction = std::function<Eigen::MatrixX2d(const Points&)>;
/// A boundary load: positions (#P × 3) and outward unit normals (#P × 2) in, tractions (#P × 2) out.
using TractionFunction = std::function<Eigen::MatrixX2d(const Points&, const Eigen::MatrixX2d&)>;

/// @brief The load vector of a body force b (force per area): f_{2i+c} = ∫ b_c φ_i dA.
/// @throws InputError when @p force returns the wrong shape or a value that is not finite
[[nodiscard]] Eigen::VectorXd elasticity_body_load(const LimitSampler& sampler, const Points& X,
                                                   const PlaneVectorFunction& force);

/// @brief The load vector of a traction t on the whole limit boundary: f_{2i+c} = ∫_Γ t_c φ_i ds,
///   with Gauss points on the boundary sides of the ptex faces (@p rule's degree and tile levels).
///   A traction that should act on part of the boundary returns 0 elsewhere.
/// @throws InputError as elasticity_body_load; UnsupportedError for triangle ptex faces
[[nodiscard]] Eigen::VectorXd elasticity_traction_load(const LimitBasis& basis, const Points& X,
                                                       const SamplerOptions& rule, const TractionFunction& traction);

/// The four sides of a rectangular cell and their matching boundary vertices.
struct PeriodicCell {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< the rectangle [x0, x1] × [y0, y1]
    /// (image, source): ũ_image = ũ_source; image on the right or top side (or a corner other than
    /// the bottom-left one), source its partner on the left or bottom side, followed to the
    /// bottom-left corner for the corners. u_image − u_source = (Fᵐ − I)(x_image − x_source).
    std::vector<std::pair<Index, Index>> pairs;
    Index pinned = invalid_index;  ///< the bottom-left corner vertex, where ũ = 0
};

/// @brief Finds the periodic cell of a planar control mesh: every boundary vertex on a side of the
///   bounding rectangle, the four corners sharp control vertices (valence-2 boundary vertices or tagged
///   corners, so that the limit boundary is the rectangle), and the boundary vertices of opposite
///   sides at the same heights (left/right) and abscissae (bottom/top) within @p tolerance times the
///   rectangle's size.
/// @throws InputError naming the vertex that lies off the sides or has no partner on the opposite side,
///   or the corner that is missing or not sharp; for a closed mesh
[[nodiscard]] PeriodicCell match_periodic_sides(const Topology& topology, const Points& X, double tolerance = 1e-9);

/// Conditions on the displacement's control values.
struct ElasticConstraints {
    /// Essential conditions: unknown 2i + c is fixed to values(2i + c) where fixed[2i + c] (a boundary
    /// vertex's control value sets the limit boundary there: exact for data the basis reproduces,
    /// linear displacements say). Empty: none.
    std::vector<bool> fixed;
    Eigen::VectorXd values;
    /// The fixed unknowns take the macroscopic displacement (Fᵐ − I) x_i instead of values (the affine
    /// condition of homogenisation; values may then be empty).
    bool fixed_follow_macro = false;
    /// Periodic conditions on this cell.
    std::optional<PeriodicCell> periodic;
    /// The macroscopic displacement gradient H = Fᵐ − I (periodic cells, fixed_follow_macro).
    Eigen::Matrix2d macro_gradient = Eigen::Matrix2d::Zero();
};

struct ElasticitySolution {
    Eigen::VectorXd u;            ///< 2#V control values (u_x, u_y of vertex i at 2i, 2i + 1); periodic: the total u
    Eigen::VectorXd fluctuation;  ///< periodic: ũ = u − (Fᵐ − I) X; else empty
    double residual = 0.0;        ///< ‖K_r x − b_r‖ / ‖b_r‖ of the reduced system
    double energy = 0.0;          ///< a(u, u) = ∫ σ : ε dA (twice the strain energy)
    std::string solver;
};

/// @brief Minimises ½ a(u, u) − fᵀu under @p constraints: the fixed unknowns eliminated, periodic
///   images expressed through their sources (u_image = u_source + (Fᵐ − I)(x_image − x_source)), the
///   pinned corner's fluctuation zero.
/// @throws InputError for sizes that do not match, fixed values not finite, no constraint at all (the
///   rigid motions would be free), a periodic cell with fixed unknowns too (not supported);
///   NumericalError when the reduced stiffness is not positive definite (a mechanism: too few
///   constraints) or the solution is not finite
[[nodiscard]] ElasticitySolution solve_elasticity(const SparseMatrix& K, const Eigen::VectorXd& load, const Points& X,
                                                  const ElasticConstraints& constraints);

/// @brief solve_elasticity for several macroscopic displacement gradients at once (periodic or fixed
///   conditions alike): one factorisation of the reduced stiffness, one solution per gradient, each
///   with @p constraints' cell and fixed unknowns and that gradient (the effective stiffness takes the
///   three unit strains).
/// @throws as solve_elasticity
[[nodiscard]] std::vector<ElasticitySolution> solve_elasticity(const SparseMatrix& K, const Eigen::VectorXd& load,
                                                               const Points& X, const ElasticConstraints& constraints,
                                                               const std::vector<Eigen::Matrix2d>& macro_gradients);

/// Strain and stress at one point of the limit surface.
struct PlaneStressState {
    Eigen::Vector2d displacement = Eigen::Vector2d::Zero();
    Eigen::Vector3d strain = Eigen::Vector3d::Zero();  ///< ε_xx, ε_yy, γ_xy = 2 ε_xy
    Eigen::Vector3d stress = Eigen::Vector3d::Zero();  ///< σ_xx, σ_yy, σ_xy
    double stress_zz = 0.0;                            ///< plane strain: ν (σ_xx + σ_yy); plane stress: 0
    double von_mises = 0.0;                            ///< of the full 3-D stress (σ_zz included)
    Index material = 0;
};

/// @brief The state of @p u at the surface points @p points (each inside a ptex face of @p basis):
///   strains through the map's first derivatives, stresses by the face's material; evaluated on
///   @p num_threads threads (0: hardware concurrency; each point's state does not depend on it).
/// @throws InputError for sizes that do not match; NumericalError at a degenerate point
[[nodiscard]] std::vector<PlaneStressState> elasticity_state(const LimitBasis& basis, const Points& X,
                                                             const ElasticBody& body, const Eigen::VectorXd& u,
                                                             const std::vector<SurfacePoint>& points,
                                                             int num_threads = 0);

/// Averages over the body by the quadrature of a sampler.
struct ElasticAverages {
    double area = 0.0;                                 ///< ∫ dA
    Eigen::Vector3d stress = Eigen::Vector3d::Zero();  ///< ∫ σ dA / area (σ_xx, σ_yy, σ_xy)
    Eigen::Vector3d strain = Eigen::Vector3d::Zero();  ///< ∫ ε dA / area (ε_xx, ε_yy, γ_xy)
    double energy = 0.0;                               ///< ∫ σ : ε dA
    std::vector<double> material_area;                 ///< per material of the body
};

/// @brief The volume averages of stress and strain of @p u (the homogenised stress of a cell is
///   ∫ σ dΩ divided by the area by the same quadrature).
[[nodiscard]] ElasticAverages elasticity_averages(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                                                  const ElasticBody& body, const Eigen::VectorXd& u);

}  // namespace limsurf
