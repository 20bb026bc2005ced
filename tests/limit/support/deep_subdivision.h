// Deep subdivision as a reference for limit evaluation: refine the whole mesh
// `levels` times with limsurf's own refinement engine (refine/refine.h), follow a
// ptex point down the child faces, and evaluate the regular patch (bicubic
// B-spline, quartic box spline) of the face that contains it at the last level.
//
// The control points of that patch are gathered here by walking the one-rings of
// the refined topology (no code shared with the library's evaluator); the basis
// functions come from limit/patch_basis.h. Derivatives are taken back to the ptex
// (u, v) of docs/conventions.md by the chain rule through the affine maps of the
// child faces (a factor 2 per level for first derivatives, 4 for second, and the
// rotation / shear of each child's frame).
//
// Exact wherever it applies: the last-level face must be a regular interior patch
// (Catmull–Clark: a quad whose 4 corners are interior, smooth and of valence 4, with
// quads all around and no sharpness, holes or corners in its one-ring; Loop: a
// triangle with 3 interior valence-6 corners and no sharpness in its one-ring).
// Points at distance >= 2^-levels (in ptex units) from extraordinary vertices and
// features satisfy this.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::test {

/// @brief A mesh refined `levels` times, ready to evaluate many points.
class DeepSubdivision {
  public:
    /// @param scheme CatmullClark or Loop (Loop: triangles only)
    /// @param levels number of uniform refinements, 1..8 (Catmull–Clark meshes with
    ///   non-quad faces need >= 1 to reach their ptex sub-faces)
    /// @throws std::runtime_error for another scheme, levels out of range, or X of the wrong size
    DeepSubdivision(const Topology& topology, const Points& X, SchemeKind scheme, const SchemeOptions& options,
                    int levels);

    /// Number of ptex faces (as Far::PtexIndices).
    [[nodiscard]] Index num_ptex_faces() const { return static_cast<Index>(ptex_face_.size()); }
    /// Ptex face p lies in control face ptex_control_face(p), sub-face ptex_corner(p) (-1: the whole face).
    [[nodiscard]] Index ptex_control_face(Index p) const { return ptex_face_.at(static_cast<std::size_t>(p)); }
    [[nodiscard]] Index ptex_corner(Index p) const { return ptex_corner_.at(static_cast<std::size_t>(p)); }

    /// @brief Position, ∂u, ∂v, ∂uu, ∂uv, ∂vv (rows) at @p point, ptex parameterisation.
    /// @throws std::runtime_error when the ptex face is out of range, (u, v) is outside the
    ///   domain, or the last-level face containing the point is not a regular interior patch
    [[nodiscard]] Eigen::Matrix<double, 6, 3> evaluate(const SurfacePoint& point) const;

    /// True when evaluate(point) applies (the last-level face is a regular interior patch).
    [[nodiscard]] bool is_regular_at(const SurfacePoint& point) const;

  private:
    struct Located {
        Index face = invalid_index;  // face of the last level
        double s = 0.0, t = 0.0;     // local coordinates in it
        Eigen::Matrix2d K;           // d(s, t) / d(u, v)
    };
    [[nodiscard]] Located locate(const SurfacePoint& point) const;

    SchemeKind scheme_;
    int levels_;
    std::vector<Index> ptex_face_;
    std::vector<Index> ptex_corner_;
    /// children_[l][child_offset_[l][f] + k]: child k of face f of level l (quad split: k = corner;
    /// triangle split: k = corner 0..2, 3 = the middle triangle).
    std::vector<std::vector<Index>> child_offset_;
    std::vector<std::vector<Index>> children_;
    Topology finest_;
    Points finest_points_;
};

/// @brief Deep-subdivision limit at one point: DeepSubdivision(...).evaluate(point).
[[nodiscard]] Eigen::Matrix<double, 6, 3> deep_subdivision_limit(const Topology& topology, const Points& X,
                                                                 SchemeKind scheme, const SchemeOptions& options,
                                                                 const SurfacePoint& point, int levels);

}  // namespace limsurf::test
