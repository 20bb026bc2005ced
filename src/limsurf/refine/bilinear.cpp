// Bilinear refinement: the Catmull–Clark split with centroids and midpoints.
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_bilinear(const Topology& parent) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    detail::SparseRowBuilder rows(V + F + E, V, V + parent.num_corners() + 2 * E);
    for (Index v = 0; v < V; ++v) {
        rows.add(v, 1.0);
        rows.end_row();
    }
    for (Index f = 0; f < F; ++f) {
        const auto verts = parent.face_vertices(f);
        const double w = 1.0 / static_cast<double>(verts.size());
        for (const Index c : verts) {
            rows.add(c, w);
        }
        rows.end_row();
    }
    for (Index e = 0; e < E; ++e) {
        const auto ends = parent.edge_vertices(e);
        rows.add(ends[0], 0.5);
        rows.add(ends[1], 0.5);
        rows.end_row();
    }
    // Sharpness is carried with uniform decay so that a later smooth scheme sees it.
    const auto effective = detail::effective_sharpness(parent, BoundaryInterpolation::EdgeOnly);
    return detail::make_level(V + F + E, detail::quad_split_faces(parent),
                              detail::child_sharpness(parent, effective, CreasingMethod::Uniform, V + F, false),
                              rows.finish(), detail::quad_split_provenance(parent));
}

}  // namespace limsurf
