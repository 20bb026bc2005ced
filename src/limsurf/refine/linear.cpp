// Linear refinement: the Loop split with midpoints.
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_linear(const Topology& parent) {
    return detail::refine_linear_step(parent, {});
}

Level detail::refine_linear_step(const Topology& parent, const StepRun& run) {
    detail::require_triangles(parent, "linear subdivision");
    const Index V = parent.num_vertices();
    const Index E = parent.num_edges();
    auto effective = detail::effective_sharpness(parent, BoundaryInterpolation::EdgeOnly);
    auto child = detail::split_child(parent, detail::Split::Triangles, run, [&] {
        return detail::child_sharpness(parent, effective, CreasingMethod::Uniform, V, true);
    });
    detail::SparseRowBuilder rows(V + E, V, V + 2 * E, run);
    detail::add_identity_rows(V, rows);
    detail::add_midpoint_rows(parent, rows);
    return detail::finish_step(parent, child, rows, run, detail::Split::Triangles, &effective);
}

}  // namespace limsurf
