// Catmull–Clark refinement of a local copy of a mesh (private: refine and limit layers).
//
// The limit basis refines one-ring copies of a face (limit_basis.cpp). A copy's outer vertices
// are boundary vertices of the copy but smooth vertices of the mesh; an extraordinary vertex's own
// β and γ (iga-tuned-catmull-clark-weights Fig. 1) act in the edge rule of its edges and the face
// rule of its faces wherever it is smooth, so they must act in the copy too: the face points and
// edge points around such an outer vertex are inside the copy and read by its children's patches.
#pragma once

#include <vector>

#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/level.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf::detail {

/// refine_catmull_clark(parent, options, weights), with the own β and γ of every vertex v with
/// forced[v] acting in its edges' and faces' rules whatever its rule in @p parent.
/// Run as @p run says (carried points, threads; refine_face_split.h).
/// @pre forced is empty or has one entry per vertex of @p parent
[[nodiscard]] Level refine_catmull_clark_forced(const Topology& parent, const SchemeOptions& options,
                                                const TunedWeights& weights, const std::vector<bool>& forced,
                                                const StepRun& run = {});

}  // namespace limsurf::detail
