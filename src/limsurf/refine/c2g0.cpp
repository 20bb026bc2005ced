// C2g0 refinement (c2g0-sphere-scheme-biomembranes §1.2, §2; scheme/c2g0.h): the triangle split
// of Loop with the rules of the three-directional box spline (each direction thrice) and the
// valence-3 rules of Fig. 3, as the stencil rows of detail/c2g0_stencils.h (shared with the limit
// evaluator). Repeated vertices of a row are merged by the row builder, as the rows of (2.2) are.
#include "limsurf/scheme/c2g0.h"

#include "limsurf/detail/c2g0_stencils.h"
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_c2g0(const Topology& parent) {
    return detail::refine_c2g0_step(parent, {});
}

Level detail::refine_c2g0_step(const Topology& parent, const StepRun& run) {
    require_c2g0_topology(parent);
    const Index V = parent.num_vertices();
    const Index E = parent.num_edges();
    auto child = detail::split_child(parent, detail::Split::Triangles, run, [] { return SharpnessTags{}; });
    detail::SparseRowBuilder rows(V + E, V, 7 * V + 10 * E, run);
    detail::C2g0Row row;
    const auto emit = [&] {
        for (const auto& [v, w] : row) {
            rows.add(v, w);
        }
        rows.end_row();
    };
    for (Index v = 0; v < V; ++v) {
        detail::c2g0_vertex_row(parent, v, row);
        emit();
    }
    for (Index e = 0; e < E; ++e) {
        const auto ends = parent.edge_vertices(e);
        detail::c2g0_edge_row(parent, ends[0], ends[1], row);
        emit();
    }

    return detail::finish_step(parent, child, rows, run, detail::Split::Triangles);
}

}  // namespace limsurf
