// Linear refinement: the Loop split with midpoints.
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_linear(const Topology& parent) {
    return detail::refine_linear_step(parent, nullptr);
}

Level detail::refine_linear_step(const Topology& parent, CarriedPoints* carried) {
    detail::require_triangles(parent, "linear subdivision");
    const Index V = parent.num_vertices();
    const Index E = parent.num_edges();
    detail::SparseRowBuilder rows(V + E, V, V + 2 * E, carried);
    detail::add_identity_rows(V, rows);
    detail::add_midpoint_rows(parent, rows);
    const auto effective = detail::effective_sharpness(parent, BoundaryInterpolation::EdgeOnly);
    return detail::make_level(detail::tri_split_topology(
                                  parent, detail::child_sharpness(parent, effective, CreasingMethod::Uniform, V, true)),
                              rows.finish(), carried != nullptr ? Provenance{} : detail::tri_split_provenance(parent));
}

}  // namespace limsurf
