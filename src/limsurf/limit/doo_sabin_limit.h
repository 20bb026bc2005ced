// Exact limit evaluation of Doo–Sabin surfaces (private; LimitBasis wires it in).
//
// Parameterisation (the ptex faces of Catmull–Clark, docs/doo_sabin_limit.md):
//   a quad is one ptex face with (0,0)=v0, (1,0)=v1, (1,1)=v2, (0,1)=v3; a face of
//   degree n != 4 has n consecutive ptex faces, sub-face k with (0,0)=v_k,
//   (1,0)=side of edge (v_k, v_k+1), (1,1)=face centre, (0,1)=side of edge (v_k-1, v_k).
//   Region (f, k) — quadrant k of a quad (child k of the Catmull–Clark split: (0,0) at
//   corner k, (1,0) towards corner k+1, half size) or sub-face k — is the surface patch
//   of the level-1 Doo–Sabin vertex c = child of (face f, corner k). c has valence 4 and
//   four faces, the domain corners are the limit points of their centres:
//     (0,0) V-face of v_k, (1,0) E-face of edge (v_k, v_k+1), (1,1) F-face of f,
//     (0,1) E-face of edge (v_k-1, v_k).
//   When the four faces are quads the patch is the biquadratic B-spline of their 3 × 3
//   vertices (c in the middle); a corner whose face is an n-gon (n = valence of v_k at
//   (0,0), n = degree of f at (1,1)) is extraordinary and evaluated exactly through the
//   stationary local subdivision matrix (docs/limit_evaluation.md).
//
// Limits of this first version: only ptex faces whose control face has all its
// vertices interior have a limit surface here (the interior rule; the surface next to
// the boundary is not evaluated); sharpness tags (creases, corners, holes) are refused,
// as refine_doo_sabin refuses them.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// @brief The exact limit basis of a Doo–Sabin surface (classic weights).
///
/// The local patches are built on first use and cached; evaluate() is thread-safe.
class DooSabinLimit {
  public:
    /// @param topology control topology (copied)
    /// @param options  boundary rule (it does not change the evaluated, interior patches)
    /// @param evaluation Stationary (tables, O(1) per point) or Subdivision (level by
    ///   level, an independent path for the tests; points closer than 2^-40 are refused)
    /// @throws UnsupportedError when the topology has creases, corners or holes
    explicit DooSabinLimit(const Topology& topology, const SchemeOptions& options = {},
                           LimitEvaluation evaluation = LimitEvaluation::Stationary);
    ~DooSabinLimit();
    DooSabinLimit(DooSabinLimit&&) noexcept;
    DooSabinLimit& operator=(DooSabinLimit&&) noexcept;
    DooSabinLimit(const DooSabinLimit&) = delete;
    DooSabinLimit& operator=(const DooSabinLimit&) = delete;

    [[nodiscard]] Index num_ptex_faces() const noexcept;
    /// @throws InputError for p out of range
    [[nodiscard]] PtexFace ptex_face(Index p) const;
    /// First ptex face of control face @p f (its sub-faces follow consecutively).
    [[nodiscard]] Index first_ptex_face(Index f) const;
    /// True when every vertex of the ptex face's control face is interior.
    [[nodiscard]] bool has_limit_surface(Index p) const;

    /// @brief Weights of the limit surface at (u, v) of ptex face @p ptex_face.
    /// @param[out] support the control vertices the surface depends on there
    /// @param[out] rows    6 × support.size(): value, ∂u, ∂v, ∂uu, ∂uv, ∂vv in ptex (u, v);
    ///   the value row sums to 1, the others to 0
    /// @pre (u, v) in the unit square (a tolerance of 1e-12 is clamped)
    /// @throws InputError for a ptex face out of range, a point outside the square or a
    ///   face without a limit surface
    void evaluate(Index ptex_face, double u, double v, std::vector<Index>& support,
                  Eigen::Matrix<double, 6, Eigen::Dynamic>& rows) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace limsurf::detail
