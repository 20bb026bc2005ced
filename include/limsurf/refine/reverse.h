// Reverse Catmull–Clark: recovers the coarse control mesh of a mesh that is the result of
// Catmull–Clark subdivision (iga-with-catmull-clark §3, "reverse Catmull–Clark"), one or more
// levels, and says how well the recovered mesh refines back to the given one (docs/guide/reverse.md).
//
// Topology: every fine face must be a quad whose corners are, in cyclic order, an old vertex (V),
// an edge point (E), a face point (F) and an edge point (E). The classes are propagated face to face
// over each connected component, V at each corner of its first face in turn; of the consistent
// classings (on a closed mesh at least two: the coarse mesh and its dual) the one whose fit has the
// smallest residual is kept; the coarse mesh has one face per F vertex (its V neighbours, in
// order, orientation kept), one vertex per V vertex (numbered in their fine order) and one edge per E
// vertex. The recovered topology is checked by refining it again (refine_catmull_clark) and comparing
// faces and tags with the fine mesh, so anything accepted is exactly a subdivided topology.
//
// Positions: the least-squares fit min ‖S0 P − P_fine‖ (S0 of the recovered coarse topology under
// the given SchemeOptions), exact on exact input and honouring every rule (boundaries, creases,
// n-gons, triangles). reverse_rule_positions() is the paper's closed-form rule, for comparison.
#pragma once

#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// One reversed level.
struct ReverseStep {
    Index fine_vertices = 0;
    Index fine_faces = 0;
    Index coarse_vertices = 0;
    Index coarse_faces = 0;
    /// max_i ‖(S0 P)_i − P_fine,i‖ (Euclidean, over the fine vertices): 0 up to rounding when the
    /// fine mesh is exactly a refinement.
    double residual_max = 0.0;
    /// sqrt(Σ_i ‖(S0 P)_i − P_fine,i‖² / #V_fine).
    double residual_rms = 0.0;
    /// False when S0 has a (numerically) non-trivial kernel, so that several coarse meshes refine to
    /// the same fine one (e.g. a closed mesh whose vertices all have valence 3 and whose edge graph is
    /// bipartite, like the cube): the result is then the fit closest to the fine V points.
    bool unique = true;
    /// fine_vertex[v]: the fine vertex that coarse vertex v refines to (its V vertex).
    std::vector<Index> fine_vertex;
};

/// The coarse mesh and one ReverseStep per reversed level (steps[0]: the first, finest level).
struct ReverseResult {
    ControlMesh coarse;
    Index levels_reversed = 0;
    std::vector<ReverseStep> steps;
};

/// @brief Reverses Catmull–Clark subdivision up to @p max_levels times.
/// @param[in] fine        the subdivided mesh (all quads); its hints are ignored, @p options rule
/// @param[in] max_levels  the number of levels to reverse (>= 1), or -1 for as many as possible
///   (at least one: stops without error at the first level that is not reversible)
/// @param[in] options     the rules the fine mesh was refined with
/// @param[in] tolerance   with max_levels = -1, a level after the first is taken only when its
///   residual_max is at most tolerance × the bounding-box diagonal of the mesh it reverses (a mesh can
///   have a subdivided topology without being a refinement: a plain quad grid); the first level is
///   always taken when the topology allows it, its residual reported
/// @throws InputError naming the fine vertex or face (ErrorElement, for file:line) when the first
///   level is not a subdivided topology (a non-quad face, corners that cannot be classed, an edge
///   point of the wrong valence, a face point on the boundary, sharpness that no coarse tag refines
///   to); for a later level of an explicit @p max_levels the message names the level, no element.
/// @throws InputError for max_levels = 0 or < -1, or a tolerance that is negative or not finite
/// @throws NumericalError when the fit is not finite
[[nodiscard]] ReverseResult reverse_catmull_clark(const ControlMesh& fine, int max_levels = -1,
                                                  const SchemeOptions& options = {}, double tolerance = 1e-9);

/// @brief The paper's rule (§3), one level, on the coarse topology reverse_catmull_clark() found:
///   V_old = (n V_new − ΣF/n − 2ΣM/n)/(n − 3) at smooth interior vertices of valence n ≠ 3, with the
///   edge midpoints M_j = 2E_j − (F_a + F_b)/2; valence 3 from a known neighbour P_j:
///   V_old = 2M_j − P_j; boundary vertices V_old = 2V_new − (E_a + E_b)/2; corners (one face, with
///   BoundaryInterpolation::EdgeAndCorner) V_old = V_new. Exact on exact input.
/// @param[in] fine   the fine mesh
/// @param[in] coarse the coarse topology (reverse_catmull_clark(fine, 1, options).coarse.topology())
/// @param[in] fine_vertex as ReverseStep::fine_vertex
/// @return #V_coarse × 3
/// @throws UnsupportedError when the coarse topology has sharpness tags, triangles under
///   TriangleSubdivision::Smooth, BoundaryInterpolation::None, or valence-3 vertices that no chain of
///   known neighbours reaches (the cube), naming the coarse vertex
[[nodiscard]] Points reverse_rule_positions(const ControlMesh& fine, const Topology& coarse,
                                            const std::vector<Index>& fine_vertex, const SchemeOptions& options = {});

}  // namespace limsurf
