// Plane elasticity on a planar Catmull–Clark control mesh and its refinements, with the numbers of
// computational homogenisation (iga-with-catmull-clark §6): the homogenised stress of a periodic cell
// under a macroscopic deformation gradient Fᵐ, the effective stiffness by the three unit macroscopic
// strains, and the analytic bounds (Voigt, Reuss, Hashin–Shtrikman) it must respect. The driver behind
// `limsurf elasticity` and limsurf.elasticity in Python, so both give the same numbers.
// docs/guide/elasticity.md.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/fem/elasticity.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/render/tessellation.h"

namespace limsurf {

/// A side of the bounding rectangle of a planar mesh.
enum class RectangleSide { Left, Right, Bottom, Top };
/// "left", "right", "bottom", "top".
[[nodiscard]] const char* to_string(RectangleSide side) noexcept;
/// @throws InputError naming the accepted names
[[nodiscard]] RectangleSide parse_rectangle_side(const std::string& name);

/// How the body is held.
enum class ElasticBoundary {
    /// u = (Fᵐ − I) x + ũ, ũ periodic between opposite sides (match_periodic_sides), pinned at the
    /// bottom-left corner.
    Periodic,
    /// u = (Fᵐ − I) x on the whole boundary (the affine "Taylor" condition of homogenisation: its
    /// effective stiffness bounds the periodic one from above).
    Affine,
    /// The sides in ElasticityStudyOptions::clamped held at u = 0, tractions on others, body force.
    Loaded
};
/// "periodic", "affine", "loaded".
[[nodiscard]] const char* to_string(ElasticBoundary boundary) noexcept;

/// A uniform traction on one side of the bounding rectangle (the limit boundary within 1e-9 of it).
struct SideTraction {
    RectangleSide side = RectangleSide::Right;
    Eigen::Vector2d traction = Eigen::Vector2d::Zero();  ///< force per length
};

struct ElasticityStudyOptions {
    ElasticBody body;  ///< materials; face_material over the control mesh's faces (refinement keeps them)
    ElasticBoundary boundary = ElasticBoundary::Periodic;
    /// Fᵐ (Periodic, Affine): the seed's example shears along x = y.
    Eigen::Matrix2d macro_deformation = (Eigen::Matrix2d() << 1.0, 0.05, 0.05, 1.0).finished();
    std::vector<RectangleSide> clamped;                    ///< Loaded: sides with u = 0
    std::vector<SideTraction> tractions;                   ///< Loaded
    Eigen::Vector2d body_force = Eigen::Vector2d::Zero();  ///< force per area, all boundaries
    int levels = 0;  ///< also solve on the control mesh refined 1..levels times (0..6)
    SamplerOptions quadrature{6, 24,
                              0};     ///< degree per tile, tile levels (deep, so that the patch test holds to rounding)
    bool effective_stiffness = true;  ///< Periodic, Affine: three more solves per level
    /// Tag every edge between faces of different materials as an infinitely sharp crease before the
    /// analysis (crease_material_interfaces): the displacement may then kink across the interface, as
    /// the exact one does, instead of being C¹ there; the interface becomes the cubic B-spline of its
    /// control vertices. Without it the stress oscillates along interfaces and C* converges slowly.
    bool crease_interfaces = false;
};

/// One level of solve_elasticity_levels.
struct ElasticityLevel {
    int level = 0;
    Topology topology;
    Points X;                          ///< control points (S0 applied `level` times)
    std::vector<Index> face_material;  ///< per face of this level (the parent's material)
    ElasticitySolution solution;
    ElasticAverages averages;  ///< averages.stress: the homogenised stress
    /// Periodic, Affine with effective_stiffness: C* (3 × 3, Voigt as elasticity_matrix), column j the
    /// homogenised stress under the unit macroscopic strain e_j (γ_xy = 1 for j = 2).
    std::optional<Eigen::Matrix3d> effective_stiffness;
    double seconds = 0.0;  ///< wall time of this level (assembly, solves, averages)
};

/// Analytic bounds on the effective stiffness of a two-material body (area fractions by quadrature).
struct StiffnessBounds {
    Eigen::Matrix3d voigt;  ///< Σ f_k C_k: C* ≤ voigt as quadratic forms
    Eigen::Matrix3d reuss;  ///< (Σ f_k C_k⁻¹)⁻¹: C* ≥ reuss
    /// Hashin–Shtrikman bounds on the in-plane bulk modulus κ* = (C*_11 + C*_12)/2 (two well-ordered
    /// phases; valid for any cell geometry): the 2-D (plane strain) form κ_HS = κ_1 + f_2 / (1/(κ_2 − κ_1)
    /// + f_1/(κ_1 + μ_1)) with phase 1 the stiffer (upper) or the softer (lower); κ = λ + μ in plane
    /// strain, and the plane stress moduli λ* = 2λμ/(λ + 2μ) in plane stress. Empty unless there are
    /// exactly two materials, well ordered (κ and μ larger in the same one).
    std::optional<std::array<double, 2>> bulk_hashin_shtrikman;
    std::optional<std::array<double, 2>> shear_hashin_shtrikman;  ///< the same for μ (isotropic cells)
};

struct ElasticityStudy {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< bounding rectangle
    std::optional<PeriodicCell> cell;       ///< Periodic: the control mesh's cell
    std::vector<ElasticityLevel> levels;
    std::optional<StiffnessBounds> bounds;  ///< with two or more materials, for the finest level's fractions
    std::vector<std::string> warnings;
};

/// @brief Solves the body on the planar control mesh (@p topology, @p X, z = 0) refined 0..options.levels
///   times (Catmull–Clark with the default rules; faces keep their material), with the homogenised
///   stress and, optionally, the effective stiffness on each level.
/// @throws InputError for levels outside 0..6, a non-planar or closed mesh, a body that does not match
///   the mesh, sides that do not match (Periodic), a Loaded body with no clamped side; NumericalError
///   as solve_elasticity
[[nodiscard]] ElasticityStudy solve_elasticity_levels(const Topology& topology, const Points& X,
                                                      const ElasticityStudyOptions& options);

/// @brief @p topology with every edge between faces of different materials (@p face_material, #F)
///   tagged infinitely sharp, the topology's own tags kept; the number of edges tagged in @p count.
/// @throws InputError when face_material does not have one entry per face
[[nodiscard]] Topology crease_material_interfaces(const Topology& topology, const std::vector<Index>& face_material,
                                                  Index* count = nullptr);

/// @brief Voigt, Reuss and (two materials) Hashin–Shtrikman bounds for @p body with the area fractions
///   @p material_area (as ElasticAverages::material_area).
[[nodiscard]] StiffnessBounds stiffness_bounds(const ElasticBody& body, const std::vector<double>& material_area);

/// Fields on the limit surface of one level, for VTK output and pictures.
struct ElasticityFields {
    LimitTessellation tessellation;  ///< each ptex face's own grid, so stresses may jump between materials
    Eigen::MatrixX2d displacement;   ///< #P
    Eigen::MatrixXd strain;          ///< #P × 3 (ε_xx, ε_yy, γ_xy)
    Eigen::MatrixXd stress;          ///< #P × 3 (σ_xx, σ_yy, σ_xy)
    Eigen::VectorXd von_mises;       ///< #P
    Eigen::VectorXi material;        ///< #P
};

/// @brief The displacement, strain and stress of @p level at the points of a tessellation with
///   @p resolution segments per ptex face side, evaluated on @p num_threads threads (0: hardware
///   concurrency; the fields do not depend on it).
[[nodiscard]] ElasticityFields elasticity_fields(const ElasticityLevel& level, const ElasticBody& body, int resolution,
                                                 int num_threads = 0);

}  // namespace limsurf
