#include "limsurf/apps/shell.h"

#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/limit/interpolation.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {
namespace {

/// @p first + @p second (either may be empty).
SurfaceTraction sum_of(SurfaceTraction first, SurfaceTraction second) {
    if (!first || !second) {
        return first ? first : second;
    }
    return [first = std::move(first), second = std::move(second)](const Points& P, const Points& N) {
        Points t = first(P, N);
        const Points more = second(P, N);
        LIMSURF_CHECK(more.rows() == t.rows(), InputError, "shell load: the traction returned ", more.rows(),
                      " rows for ", t.rows(), " points");
        t += more;
        return t;
    };
}

/// The vertex supports as supports by position: the level-0 points on the intended surface (those
/// solve_shell_levels selects by) of the listed vertices.
ShellSupport support_at_vertices(const Topology& topology, const Points& where, const ShellVertexSupport& support,
                                 std::size_t number) {
    std::vector<Eigen::Vector3d> selected;
    for (const Index v : support.vertices) {
        LIMSURF_CHECK(v >= 0 && v < topology.num_vertices(), InputError, "shell: vertex support ", number,
                      ": vertex ", v, " is out of range (the mesh has ", topology.num_vertices(), " vertices)");
        LIMSURF_CHECK(topology.is_boundary_vertex(v), InputError, "shell: vertex support ", number, ": vertex ", v,
                      " is not a boundary vertex (supports act on boundary control vertices only)");
        selected.push_back(where.row(v).transpose());
    }
    ShellSupport out;
    out.components = support.components;
    out.where = [selected = std::move(selected)](const Eigen::Vector3d& x) {
        for (const Eigen::Vector3d& y : selected) {
            if (x == y) {
                return true;
            }
        }
        return false;
    };
    return out;
}

}  // namespace

SurfaceTraction gravity_and_pressure(double gravity, double pressure) {
    if (gravity == 0.0 && pressure == 0.0) {
        return {};
    }
    // Self-weight along −z and a pressure along the normal (positive: outwards for an outward-oriented
    // surface, as an internal pressure).
    return [gravity, pressure](const Points&, const Points& N) {
        Points t = pressure * N;
        t.col(2).array() -= gravity;
        return t;
    };
}

ShellProblem shell_problem(const Topology& topology, const Points& points, const ShellStudyOptions& options) {
    ShellProblem problem;
    problem.material = options.material;
    problem.scheme = options.scheme;
    problem.quadrature = options.quadrature;
    problem.interpolate = options.interpolate || static_cast<bool>(options.surface);
    if (options.surface) {
        const SurfaceFunction F = options.surface;
        problem.project = [F](const Points& P) { return project_onto_zero_set(F, P); };
    }
    problem.supports = options.supports;
    if (!options.vertex_supports.empty()) {
        LIMSURF_CHECK(options.levels == 0, InputError,
                      "shell: supports given by vertex index hold on the given mesh only (levels = 0); select "
                      "vertices by position to support refined meshes");
        LIMSURF_CHECK(points.rows() == topology.num_vertices(), InputError, "shell: ", points.rows(), " points for ",
                      topology.num_vertices(), " vertices");
        const Points where = problem.project ? problem.project(points) : points;
        for (std::size_t k = 0; k < options.vertex_supports.size(); ++k) {
            problem.supports.push_back(support_at_vertices(topology, where, options.vertex_supports[k], k + 1));
        }
    }
    problem.point_loads = options.point_loads;
    problem.probes = options.probes;
    problem.traction = sum_of(gravity_and_pressure(options.gravity, options.pressure), options.traction);
    LIMSURF_CHECK(problem.traction || !problem.point_loads.empty(), InputError,
                  "shell: no load (give gravity, pressure, a traction or point loads)");
    return problem;
}

ShellVertexLimits shell_vertex_limits(const ShellLevel& level, SchemeKind scheme) {
    const LimitBasis basis(level.topology, scheme);
    const SparseMatrix P = basis.vertex_limit_matrix();
    return ShellVertexLimits{P * level.X, P * level.solution.displacements()};
}

}  // namespace limsurf
