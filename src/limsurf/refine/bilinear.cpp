// Bilinear refinement: the Catmull–Clark split with centroids and midpoints.
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_bilinear(const Topology& parent) {
    return detail::refine_bilinear_step(parent, {});
}

Level detail::refine_bilinear_step(const Topology& parent, const StepRun& run) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    // Sharpness is carried with uniform decay so that a later smooth scheme sees it.
    auto effective = detail::effective_sharpness(parent, BoundaryInterpolation::EdgeOnly);
    auto child = detail::split_child(parent, detail::Split::Quads, run, [&] {
        return detail::child_sharpness(parent, effective, CreasingMethod::Uniform, V + F, false);
    });
    detail::SparseRowBuilder rows(V + F + E, V, V + parent.num_corners() + 2 * E, run);
    detail::add_identity_rows(V, rows);
    for (Index f = 0; f < F; ++f) {
        const auto verts = parent.face_vertices(f);
        const double w = 1.0 / static_cast<double>(verts.size());
        for (const Index c : verts) {
            rows.add(c, w);
        }
        rows.end_row();
    }
    detail::add_midpoint_rows(parent, rows);
    return detail::finish_step(parent, child, rows, run, detail::Split::Quads, &effective);
}

}  // namespace limsurf
