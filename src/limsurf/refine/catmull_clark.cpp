// Catmull–Clark refinement with OpenSubdiv's boundary, crease and triangle rules
// (docs/schemes.md; iga-with-catmull-clark §3 for the regular stencils).
#include <cstddef>
#include <vector>

#include "limsurf/core/magnitude.h"
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Sdc's CATMARK_SMOOTH_TRI_EDGE_WEIGHT: face weight of a triangle next to a smooth edge.
constexpr double smooth_triangle_edge_weight = 0.470;

/// Adds weight w times the centroid of face f.
void add_face_point(const Topology& parent, Index f, double w, detail::SparseRowBuilder& rows) {
    const auto verts = parent.face_vertices(f);
    const double share = w / static_cast<double>(verts.size());
    for (const Index c : verts) {
        rows.add(c, share);
    }
}

}  // namespace

Level refine_catmull_clark(const Topology& parent, const SchemeOptions& options, const TunedWeights& weights) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    const auto effective = detail::effective_sharpness(parent, options.boundary);

    // Regular interior rows: 9 (vertex), 4 (face), 6 (edge) entries.
    detail::SparseRowBuilder rows(V + F + E, V, 9 * V + parent.num_corners() + 6 * E);

    // Vertex points.
    const auto smooth = [&](Index v, detail::VertexMask& mask) {
        const auto n = mask.edges.size();
        // The rule depends on the weights' ratios only: scaled by a power of two (exactly) so that
        // the normalising sum neither overflows (weights of 1e308) nor loses them to underflow.
        const VertexRuleWeights given = weights.at(v, static_cast<int>(n));
        const Eigen::Vector3d scaled =
            times_power_of_two(Eigen::Vector3d(given.alpha, given.beta, given.gamma),
                               -magnitude_exponent(Eigen::Vector3d(given.alpha, given.beta, given.gamma)));
        const VertexRuleWeights w{scaled.x(), scaled.y(), scaled.z()};
        const double nd = static_cast<double>(n);
        const double denominator = w.alpha + nd * w.beta + nd * w.gamma;
        mask.vertex = w.alpha / denominator;
        const double edge_weight = w.beta / denominator;
        const double face_weight = w.gamma / denominator;
        for (auto& x : mask.edges) {
            x = edge_weight;
        }
        for (auto& x : mask.faces) {
            x = face_weight;
        }
    };
    detail::VertexMask mask;
    detail::VertexMaskWorkspace work;
    for (Index v = 0; v < V; ++v) {
        detail::vertex_mask(parent, effective, options.creasing, v, smooth, mask, work);
        detail::add_vertex_and_neighbours(parent, v, mask, rows);
        const auto faces = parent.vertex_faces(v);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            if (mask.faces[i] != 0.0) {
                add_face_point(parent, faces[i], mask.faces[i], rows);
            }
        }
        rows.end_row();
    }

    // Face points: centroids.
    for (Index f = 0; f < F; ++f) {
        add_face_point(parent, f, 1.0, rows);
        rows.end_row();
    }

    // Edge points.
    std::vector<double> scratch;
    const bool smooth_triangles = options.triangles == TriangleSubdivision::Smooth;
    for (Index e = 0; e < E; ++e) {
        const auto ends = parent.edge_vertices(e);
        const auto faces = parent.edge_faces(e);
        const double s = effective.edge[at(e)];
        if (is_sharp(s) && detail::edge_child_is_crease(parent, effective, options.creasing, e, scratch)) {
            detail::add_edge_midpoint(parent, e, rows);
            rows.end_row();
            continue;
        }
        // Smooth mask (an edge with one face is a boundary edge, always sharp).
        double vertex_weight = 0.25;
        double face_weight = 0.25;
        if (smooth_triangles && (parent.face_degree(faces[0]) == 3 || parent.face_degree(faces[1]) == 3)) {
            const double w0 = parent.face_degree(faces[0]) == 3 ? smooth_triangle_edge_weight : 0.25;
            const double w1 = parent.face_degree(faces[1]) == 3 ? smooth_triangle_edge_weight : 0.25;
            face_weight = 0.5 * (w0 + w1);
            vertex_weight = 0.5 * (1.0 - 2.0 * face_weight);
        }
        if (is_sharp(s)) {
            // Crease decaying to smooth: blend with the crease mask by the edge's sharpness.
            const double c = 1.0 - s;
            vertex_weight = s * 0.5 + c * vertex_weight;
            face_weight *= c;
        }
        rows.add(ends[0], vertex_weight);
        rows.add(ends[1], vertex_weight);
        add_face_point(parent, faces[0], face_weight, rows);
        add_face_point(parent, faces[1], face_weight, rows);
        rows.end_row();
    }

    return detail::make_level(V + F + E, detail::quad_split_faces(parent),
                              detail::child_sharpness(parent, effective, options.creasing, V + F, false), rows.finish(),
                              detail::quad_split_provenance(parent));
}

}  // namespace limsurf
