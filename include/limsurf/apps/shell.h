// Linear Kirchhoff–Love shells on a control mesh and its refinements (fem/shell.h) with the loads
// and supports of docs/guide/shell.md: self-weight, pressure along the normal, point forces,
// supports selected by position (or by vertex), probes, the exact surface as the zero set of a
// function. The driver behind `limsurf shell` and limsurf.shell in Python, so both give the same
// numbers.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/fem/shell.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// Zero displacement components at listed control vertices of the given mesh (boundary vertices
/// only, as ShellSupport). Indices do not carry to refined meshes: levels = 0 only.
struct ShellVertexSupport {
    std::vector<Index> vertices;
    std::array<bool, 3> components{true, true, true};  ///< x, y, z
};

struct ShellStudyOptions {
    ShellMaterial material;
    SchemeKind scheme = SchemeKind::CatmullClark;  ///< Catmull–Clark or Loop, default rules
    int levels = 0;                                ///< also solve on the mesh refined 1..levels times
    double gravity = 0.0;                          ///< self-weight: force per unit area along −z
    double pressure = 0.0;                         ///< force per unit area along the limit normal
    /// A further force per unit area (positions and unit normals in, #P × 3 forces out); empty: none.
    SurfaceTraction traction;
    std::vector<ShellPointLoad> point_loads;
    std::vector<ShellSupport> supports;
    std::vector<ShellVertexSupport> vertex_supports;
    std::vector<Eigen::Vector3d> probes;
    /// The given points are points of the surface: fit the control points (ShellProblem::interpolate).
    bool interpolate = false;
    /// The exact surface as the zero set F = 0 of this function (#P × 3 in, #P values out): at every
    /// level the points are projected onto it (project_onto_zero_set) and fitted again; implies
    /// interpolate. Empty: the limit surface of level 0 is the shell at every level.
    SurfaceFunction surface;
    SamplerOptions quadrature{6, 4, 0};
};

/// @brief The traction of a self-weight @p gravity along −z and a @p pressure along the normal
///   (positive: outwards for an outward-oriented surface, as an internal pressure); empty when both are 0.
[[nodiscard]] SurfaceTraction gravity_and_pressure(double gravity, double pressure);

/// @brief The ShellProblem of @p options (solve it with solve_shell_levels(topology, points, problem,
///   options.levels)): gravity, pressure and the traction as one traction, the
///   surface as a projection, vertex supports as supports of the level-0 points (@p topology, @p points).
/// @throws InputError when there is no load, or for a vertex support with levels > 0, an index out of
///   range or of an interior vertex
[[nodiscard]] ShellProblem shell_problem(const Topology& topology, const Points& points,
                                         const ShellStudyOptions& options);

/// The displacement of a level where its control vertices' limit points are.
struct ShellVertexLimits {
    Points positions;      ///< #V × 3 limit points of the control vertices
    Points displacements;  ///< #V × 3 limit displacement there
};

/// @brief The limit points of @p level's control vertices under @p scheme and the displacement there.
[[nodiscard]] ShellVertexLimits shell_vertex_limits(const ShellLevel& level, SchemeKind scheme);

}  // namespace limsurf
