// Exact limit evaluation of C2g0 surfaces (private; LimitBasis wires it in). docs/c2g0_limit.md.
//
// Parameterisation (as Loop): each triangle is one ptex face, (0,0) = v0, (1,0) = v1, (0,1) = v2.
//
// Type-0 triangles (c2g0-sphere-scheme-biomembranes §3.1: the 12 vertices at distance <= 1 all of
// valence 6): the surface is one degree-7 polynomial, the box spline of symbol (1.3), read off the
// generated Bernstein–Bézier table c2g0_patch_table.inc (tools/make_c2g0_patch.py) applied to the
// 27 vertices of the triangle's 2-ring. Every other triangle (types I, II₁, II₂) lies within ring 2
// of exactly one valence-3 vertex c. Its surface is evaluated on a canonical copy K_R of the
// "3-regular complex" around c (paper Fig. 4: c and R rings of valence-6 vertices in three 60°
// sectors): K_4 refines into K_6 with the C2g0 rules (matrix B, only the children whose stencils
// lie in K_4), K_4 into K_4 (A, the stationary local subdivision matrix); a point at distance ρ
// from c (in sector coordinates, ring units) lies, after m levels with 2^m ρ in [2, 4], in a type-0
// triangle of K_6 at level m, so its weights are  bez · P · B · A^(m-1) · E  with E the copy of K_4
// in the control mesh. A^n is tabulated as 1ℓᵀ + R^n (ℓ the limit mask of c), as Stam-type
// evaluation needs (no eigendecomposition: A has zero eigenvalues in Jordan blocks).
//
// Accepted meshes: require_c2g0_topology, and any two valence-3 vertices at distance >= 4 (so every
// K_4 copy sees only valence-6 vertices besides its centre, within ring 3). Meshes whose valence-3
// vertices are closer (but not adjacent: distance 2 or 3, e.g. tetra_1) are refined once with
// refine_c2g0 and evaluated on the refined mesh (distances double), the weights mapped back by the
// subdivision matrix.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/topology.h"

namespace limsurf::detail {

/// @brief The regular C2g0 patch (degree-7 box spline) over the lattice triangle P0 = (0,0),
///   P1 = (1,0), P2 = (1,1) at (u, v) (barycentrics (1-u-v, u, v)): rows value, ∂u, ∂v, ∂uu, ∂uv,
///   ∂vv over the 27 control points in the order of c2g0_patch_offsets().
void c2g0_patch_weights(double u, double v, Eigen::Matrix<double, 6, 27>& out);

/// The lattice offsets (x, y) of the 27 control points of c2g0_patch_weights (neighbours of (0,0)
/// counter-clockwise: (1,0), (1,1), (0,1), (-1,0), (-1,-1), (0,-1)).
[[nodiscard]] std::array<std::array<int, 2>, 27> c2g0_patch_offsets();

/// @brief The exact limit basis of a C2g0 surface.
///
/// Everything is built in the constructor; evaluate() is const and thread-safe.
class C2g0Limit {
  public:
    /// @param topology closed triangle mesh, valences 3 and 6 (copied)
    /// @param evaluation Stationary (tables of A^n, O(1) per point) or Subdivision (level by level,
    ///   an independent path for the tests; refuses points closer than 2^-60 to a valence-3 vertex)
    /// @throws UnsupportedError as require_c2g0_topology, and for two valence-3 vertices at distance
    ///   2 or 3 that are still closer than 4 after one refinement (naming one of them)
    explicit C2g0Limit(const Topology& topology, LimitEvaluation evaluation = LimitEvaluation::Stationary);
    ~C2g0Limit();
    C2g0Limit(C2g0Limit&&) noexcept;
    C2g0Limit& operator=(C2g0Limit&&) noexcept;
    C2g0Limit(const C2g0Limit&) = delete;
    C2g0Limit& operator=(const C2g0Limit&) = delete;

    /// @brief Weights at (u, v) of triangle @p face (its ptex face).
    /// @param rows_needed 1, 3 or 6 (value; first; second derivatives); other rows are 0
    /// @param[out] support the control vertices the surface depends on there
    /// @param[out] rows 6 × support.size()
    /// @param[out] at_vertex true when the point is a valence-3 vertex (within 2^-60): the value
    ///   is its exact limit position, the derivatives are taken 2^-61 away along the face's edge
    /// @pre face in range, (u, v) in the triangle (LimitBasis checks and clamps)
    /// @throws NumericalError under LimitEvaluation::Subdivision at a valence-3 vertex
    void evaluate(Index face, double u, double v, int rows_needed, std::vector<Index>& support,
                  Eigen::Matrix<double, 6, Eigen::Dynamic>& rows, bool& at_vertex) const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace limsurf::detail
