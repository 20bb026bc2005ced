// Loop refinement with OpenSubdiv's boundary and crease rules (docs/schemes.md).
#include <cstddef>
#include <vector>

#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/loop_weights.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

}  // namespace

Level refine_loop(const Topology& parent, const SchemeOptions& options) {
    return detail::refine_loop_step(parent, options, {});
}

Level detail::refine_loop_step(const Topology& parent, const SchemeOptions& options, const StepRun& run) {
    detail::require_triangles(parent, "Loop");
    const Index V = parent.num_vertices();
    const Index E = parent.num_edges();
    auto effective = detail::effective_sharpness(parent, options.boundary);
    auto child = detail::split_child(parent, detail::Split::Triangles, run, [&] {
        return detail::child_sharpness(parent, effective, options.creasing, V, true);
    });

    detail::SparseRowBuilder rows(V + E, V, 7 * V + 4 * E, run);

    // Vertex points: Loop's weights, β = (5/8 − (3/8 + cos(2π/n)/4)²)/n per neighbour.
    const auto smooth = [](Index, detail::VertexMask& mask) {
        const auto n = mask.edges.size();
        const double edge_weight = detail::loop_neighbour_weight(n);
        mask.vertex = 1.0 - edge_weight * static_cast<double>(n);
        for (auto& x : mask.edges) {
            x = edge_weight;
        }
    };
    detail::VertexMask mask;
    detail::VertexMaskWorkspace work;
    for (Index v = 0; v < V; ++v) {
        detail::vertex_mask(parent, effective, options.creasing, v, smooth, mask, work);
        detail::add_vertex_and_neighbours(parent, v, mask, rows);
        rows.end_row();
    }

    // Edge points: 3/8 ends + 1/8 opposite corners, or the crease midpoint.
    std::vector<double> scratch;
    for (Index e = 0; e < E; ++e) {
        const auto ends = parent.edge_vertices(e);
        const double s = effective.edge[at(e)];
        if (is_sharp(s) && detail::edge_child_is_crease(parent, effective, options.creasing, e, scratch)) {
            detail::add_edge_midpoint(parent, e, rows);
            rows.end_row();
            continue;
        }
        double vertex_weight = 0.375;
        double face_weight = 0.125;
        if (is_sharp(s)) {
            const double c = 1.0 - s;
            vertex_weight = s * 0.5 + c * vertex_weight;
            face_weight *= c;
        }
        rows.add(ends[0], vertex_weight);
        rows.add(ends[1], vertex_weight);
        for (const Index f : parent.edge_faces(e)) {
            rows.add(detail::opposite_vertex(parent, f, e), face_weight);
        }
        rows.end_row();
    }

    return detail::finish_step(parent, child, rows, run, detail::Split::Triangles, &effective);
}

}  // namespace limsurf
