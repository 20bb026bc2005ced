// OpenSubdiv 3.5 (Far) as a reference for limit evaluation: limit positions and
// tangents at the control vertices (PrimvarRefiner::Limit) and patch evaluation
// at ptex points (PatchTableFactory + PatchMap + PatchTable::EvaluateBasis).
//
// The options map onto Sdc exactly as the face-split peer test's make_refiner:
// BoundaryInterpolation -> VtxBoundaryInterpolation, CreasingMethod ->
// CreasingMethod, TriangleSubdivision -> TriangleSubdivision; edge and vertex
// sharpness and holes travel as TopologyDescriptor tags.
//
// Derivatives are with respect to the ptex (u, v) of docs/conventions.md. Far
// 3.5's EvaluateBasis gets two of them wrong (shared/reference/PEERS.md), and
// osd_evaluate() CORRECTS both:
//   1. patches below an n-gon's sub-face (PatchParam::NonQuadRoot(), Catmull–Clark):
//      Far scales by 2^depth although the sub-face is the ptex face one level down;
//      first derivatives are divided by 2, second by 4;
//   2. rotated Loop sub-triangles (PatchParam::IsTriangleRotated()): Far flips the
//      sign of the second derivatives (sign^3 instead of sign^2); they are negated back.
// osd_harness_test checks both corrections against central differences of Far's positions.
//
// Exactness: a point in a regular patch (B-spline / box spline, `regular`) is the
// exact limit surface; end caps (Gregory, or B-spline approximations) are not
// (their derivatives are a few percent off near extraordinary vertices). Moreover
// Far's Gregory-basis derivatives are not even the derivatives of its own Gregory
// positions (patchBasis.cpp differentiates the Bezier patch of the current (s, t) and
// skips the rational multipliers' derivatives), and at asymmetric valence-3 vertices
// the Gregory corner's tangent plane is only approximate (error shrinking with the
// isolation level). Use end-cap values as rough witnesses only.
// Two more approximations, found on OpenSubdiv's regression shapes
// (opensubdiv_shapes_limit_test): patches at the deepest isolation level are flagged regular even
// next to an irregular feature (a Loop dart at isolation 4: 4e-5 off; exact from 6), and
// PrimvarRefiner::Limit applies the smooth mask at darts and interior valence-2 vertices, which is
// not their limit (refinement converges to limsurf's value there).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::test {

/// Limit position and tangents of every control vertex (#V × 3 each), from
/// Far::PrimvarRefinerReal<double>::Limit after one uniform refinement (child v = parent v).
struct OsdVertexLimits {
    Points position;
    Points tangent1;
    Points tangent2;
};

/// @brief Limit positions and the two limit tangents of the control vertices.
/// @param scheme CatmullClark or Loop
/// @throws std::runtime_error for another scheme or when Far refuses the topology
[[nodiscard]] OsdVertexLimits osd_vertex_limits(const Topology& topology, const Points& X, SchemeKind scheme,
                                                const SchemeOptions& options);

/// End caps for the irregular patches at the isolation level.
enum class OsdEndCaps { GregoryBasis, BSplineBasis };

/// One evaluated point.
struct OsdPointEval {
    /// Rows: position, ∂u, ∂v, ∂uu, ∂uv, ∂vv (ptex parameterisation, defects corrected).
    Eigen::Matrix<double, 6, 3> value = Eigen::Matrix<double, 6, 3>::Zero();
    bool has_patch = false;         ///< false: no limit surface here (hole, None boundary); value is NaN
    bool regular = false;           ///< B-spline / box-spline patch: the exact limit surface
    bool end_cap = false;           ///< an end cap (Gregory or B-spline approximation): approximate
    bool non_quad_root = false;     ///< the patch lies in a sub-face of a non-quad (Catmull–Clark)
    bool triangle_rotated = false;  ///< a rotated Loop sub-triangle
    int depth = 0;                  ///< refinement depth of the patch (PatchParam::GetDepth())
    int patch = -1;                 ///< patch number, unique within one evaluator (for "same patch" tests)
};

/// @brief Far's adaptive patch table for one control mesh, built once; evaluates many points.
class OsdLimitEvaluator {
  public:
    /// @param isolation_level maximum adaptive isolation level (1..10)
    /// @throws std::runtime_error for a scheme other than CatmullClark or Loop, or when Far refuses the topology
    OsdLimitEvaluator(const Topology& topology, const Points& X, SchemeKind scheme, const SchemeOptions& options,
                      int isolation_level = 6, OsdEndCaps end_caps = OsdEndCaps::GregoryBasis);
    ~OsdLimitEvaluator();
    OsdLimitEvaluator(OsdLimitEvaluator&&) noexcept;
    OsdLimitEvaluator& operator=(OsdLimitEvaluator&&) noexcept;
    OsdLimitEvaluator(const OsdLimitEvaluator&) = delete;
    OsdLimitEvaluator& operator=(const OsdLimitEvaluator&) = delete;

    /// Number of ptex faces (Far::PtexIndices).
    [[nodiscard]] Index num_ptex_faces() const;
    /// @throws std::runtime_error for a ptex face out of range
    [[nodiscard]] OsdPointEval evaluate(const SurfacePoint& point) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// @brief Evaluates @p points (ptex face, u, v) with Far's patch table (see OsdLimitEvaluator).
[[nodiscard]] std::vector<OsdPointEval> osd_evaluate(const Topology& topology, const Points& X, SchemeKind scheme,
                                                     const SchemeOptions& options,
                                                     const std::vector<SurfacePoint>& points, int isolation_level = 6,
                                                     OsdEndCaps end_caps = OsdEndCaps::GregoryBasis);

}  // namespace limsurf::test
