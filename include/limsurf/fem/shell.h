// Linear Kirchhoff–Love thin shells on a curved limit surface (Cirak, Ortiz and Schröder,
// "Subdivision surfaces: a new paradigm for thin-shell finite-element analysis", IJNME 47 (2000);
// iga-with-catmull-clark §5–6 for the bases): the displacement u = Σ u_i φ_i has three components
// per control vertex, and the strain energy is
//   ½ a(u, u) = ½ ∫ [ C_m ε(u) · ε(u) + C_b κ(u) · κ(u) ] dA,
//   membrane  ε_αβ = ½ (a_α · u,β + a_β · u,α),
//   bending   κ_αβ = a₃ · (u,αβ − Γ^γ_αβ u,γ)   (the linearised change of x,αβ · a₃),
// with a_α = ∂x/∂θ^α the tangents of the limit surface, a₃ its unit normal, Γ^γ_αβ = x,αβ · a^γ,
// both strains expressed in a local orthonormal tangent frame and C = plane-stress elasticity times
// E t / (1 − ν²) (membrane) and E t³ / (12 (1 − ν²)) (bending). Rigid motions u = c + ω × x give
// zero strain exactly. On a planar surface the bending block is the plate's (plate.h).
// docs/fem.md "Shells".
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// Material and thickness of a shell (any consistent units).
struct ShellMaterial {
    double E = 1.0;          ///< Young's modulus, > 0
    double nu = 0.3;         ///< Poisson's ratio, in (−1, 0.5)
    double thickness = 0.1;  ///< t > 0
    /// E t / (1 − ν²).
    [[nodiscard]] double membrane_rigidity() const noexcept { return E * thickness / (1.0 - nu * nu); }
    /// E t³ / (12 (1 − ν²)).
    [[nodiscard]] double bending_rigidity() const noexcept {
        return E * thickness * thickness * thickness / (12.0 * (1.0 - nu * nu));
    }
};

/// Which parts of the strain energy to assemble.
enum class ShellTerms { MembraneAndBending, Membrane, Bending };

/// @brief The stiffness K of the shell on the limit surface of the sampler's control points @p X
///   (#V × 3): 3 #V × 3 #V, the unknown of component c (x, y, z) of control vertex v in row 3 v + c;
///   symmetric, positive semi-definite, with the six rigid motions in its kernel.
/// @throws InputError for a material out of range or X of the wrong size; NumericalError at a
///   degenerate quadrature point (parallel tangents), naming its ptex face
[[nodiscard]] SparseMatrix assemble_shell_stiffness(const LimitSampler& sampler, const Points& X,
                                                    const ShellMaterial& material,
                                                    ShellTerms terms = ShellTerms::MembraneAndBending);

/// A force per unit area on the surface: positions and unit normals (#P × 3 each) in, one force
/// (#P × 3) out.
using SurfaceTraction = std::function<Points(const Points& positions, const Points& normals)>;

/// @brief The load vector f_{3i+c} = ∫ t_c φ_i dA of the traction @p t, evaluated at the quadrature
///   points of the limit surface (normals: ∂u x × ∂v x normalised, outward for consistently oriented
///   closed meshes).
/// @throws InputError when t returns the wrong shape or a non-finite value (naming the point)
[[nodiscard]] Eigen::VectorXd shell_area_load(const LimitSampler& sampler, const Points& X, const SurfaceTraction& t);

/// @brief Adds the point force @p force at the surface point whose limit weights are @p at:
///   f_{3i+c} += φ_i F_c.
void add_point_load(const LimitWeights& at, const Eigen::Vector3d& force, Eigen::VectorXd& f);

/// @brief The six rigid motions of the control points (3 #V × 6, rows as the stiffness): the
///   translations along x, y, z and the rotations about axes through the centroid, scaled by the
///   control points' extent so that all six columns have comparable size. A rigid motion of the
///   control points moves the limit surface rigidly (the basis is affine invariant).
[[nodiscard]] Eigen::MatrixXd rigid_body_modes(const Points& X);

struct ShellSolution {
    Eigen::VectorXd u;           ///< 3 #V control displacements, row 3 v + c
    double residual = 0.0;       ///< ‖K u − f‖ / ‖f‖ over the unconstrained unknowns
    double energy = 0.0;         ///< fᵀ u (twice the strain energy)
    int free_rigid_motions = 0;  ///< rigid motions the constraints leave free (removed from u)
    std::string solver;
    /// u as #V × 3 rows.
    [[nodiscard]] Points displacements() const;
};

/// @brief Solves K u = f with the unknowns where @p fixed holds set to zero (3 #V flags: supports on
///   control points, exact on the limit boundary where the boundary rows carry it). Rigid motions
///   that the supports leave free are handled for a load in equilibrium with them: enough further
///   unknowns are pinned to make the system definite (chosen by a pivoted QR of those motions) and
///   the free rigid part is removed from u in the least-squares sense over the control points.
/// @throws InputError on size mismatches or when the load has a resultant along a free rigid motion
///   (naming it); NumericalError when the constrained stiffness is singular (a mechanism)
[[nodiscard]] ShellSolution solve_shell(const SparseMatrix& K, const Eigen::VectorXd& f, const Points& X,
                                        const std::vector<bool>& fixed);

/// Zero displacement components on the boundary control vertices whose position @p where selects
/// (exact on the limit boundary curve, which depends on the boundary control points only).
struct ShellSupport {
    std::function<bool(const Eigen::Vector3d&)> where;
    std::array<bool, 3> components{true, true, true};  ///< x, y, z
};

/// A force at the limit point of the control vertex nearest @p position.
struct ShellPointLoad {
    Eigen::Vector3d position;
    Eigen::Vector3d force;
};

/// A shell problem solved on a control mesh and its refinements (solve_shell_levels).
struct ShellProblem {
    ShellMaterial material;
    SchemeKind scheme = SchemeKind::CatmullClark;
    std::vector<ShellSupport> supports;
    SurfaceTraction traction;  ///< force per unit area; empty: none
    std::vector<ShellPointLoad> point_loads;
    std::vector<Eigen::Vector3d> probes;  ///< points where the displacement is reported
    SamplerOptions quadrature{6, 4, 0};
    /// The given points are points of the surface: the control points are fitted so that the limit
    /// surface passes through them at the vertices' limit points (interpolation.h). Otherwise the
    /// given points are the control points.
    bool interpolate = true;
    /// The exact surface, when known: at each level the refined points (#P × 3) are moved onto it
    /// with this projection (e.g. project_onto_zero_set) and fitted again: the geometry is refined
    /// with the mesh, as the obstacle course asks. Empty: the limit surface of level 0 is the shell
    /// at every level (h-refinement of one geometry).
    std::function<Points(const Points&)> project;
};

/// The displacement at a probe.
struct ShellProbe {
    Index vertex = invalid_index;  ///< whose limit point the probe is
    double distance = 0.0;         ///< from the requested point
    Eigen::Vector3d position, normal, displacement;
};

/// One level of solve_shell_levels.
struct ShellLevel {
    int level = 0;
    Topology topology;
    Points X;  ///< control points
    ShellSolution solution;
    std::vector<ShellProbe> probes;
    double area = 0.0;  ///< of the limit surface, by the quadrature
};

/// The most refinement levels solve_shell_levels takes (each has 4 times the faces of the one before).
inline constexpr int max_shell_levels = 6;

/// @brief Solves @p problem on the control mesh (@p topology, @p points) refined 0..@p levels times.
///   Point loads and probes sit at the limit points of control vertices (they stay put under
///   refinement): the nearest one is taken, and refused when it is farther than 1e-6 of the
///   mesh's extent from the requested point.
/// @throws InputError for levels outside 0..max_shell_levels, when a point load or probe is not at a
///   vertex limit point, when no support selects anything although one was given, or as the functions above
[[nodiscard]] std::vector<ShellLevel> solve_shell_levels(const Topology& topology, const Points& points,
                                                         const ShellProblem& problem, int levels);

}  // namespace limsurf
