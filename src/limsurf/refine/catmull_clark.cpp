// Catmull–Clark refinement with OpenSubdiv's boundary, crease and triangle rules
// (docs/schemes.md; iga-with-catmull-clark §3 for the regular stencils).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "limsurf/core/magnitude.h"
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/detail/tuned_copy.h"
#include "limsurf/refine/refine.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Sdc's CATMARK_SMOOTH_TRI_EDGE_WEIGHT: face weight of a triangle next to a smooth edge.
constexpr double smooth_triangle_edge_weight = 0.470;

/// The extraordinary vertices' own weights in the edge (β) and face (γ) rules
/// (iga-tuned-catmull-clark-weights Fig. 1); empty when every vertex has Catmull–Clark's (1, 1).
struct OwnEdgeFaceWeights {
    std::vector<double> beta;
    std::vector<double> gamma;
    [[nodiscard]] bool empty() const noexcept { return beta.empty(); }
};

/// Adds weight w times the point of face f: the centroid, or with tuned corners
/// (Σ γ_c c) / Σ γ_c, γ_c = 1 for corners without tuned weights.
void add_face_point(const Topology& parent, Index f, double w, const OwnEdgeFaceWeights& own,
                    detail::SparseRowBuilder& rows) {
    const auto verts = parent.face_vertices(f);
    bool tuned = false;
    double largest = 1.0;
    if (!own.empty()) {
        for (const Index c : verts) {
            tuned = tuned || own.gamma[at(c)] != 1.0;
            largest = std::max(largest, own.gamma[at(c)]);
        }
    }
    if (!tuned) {  // Catmull–Clark's centroid, bit for bit
        const double share = w / static_cast<double>(verts.size());
        for (const Index c : verts) {
            rows.add(c, share);
        }
        return;
    }
    // Scaled by a power of two (exactly) so that the sum cannot overflow (γ = 1e308).
    const int exponent = -magnitude_exponent(Eigen::Vector3d(largest, 0.0, 0.0));
    double sum = 0.0;
    for (const Index c : verts) {
        sum += std::ldexp(own.gamma[at(c)], exponent);
    }
    for (const Index c : verts) {
        rows.add(c, w * (std::ldexp(own.gamma[at(c)], exponent) / sum));
    }
}

/// Three weights of one rule scaled by a power of two (exactly) so that their normalising sum
/// neither overflows (weights of 1e308) nor loses them to underflow: a rule depends on ratios only.
Eigen::Vector3d scale_free(const Eigen::Vector3d& w) {
    return times_power_of_two(w, -magnitude_exponent(w));
}

/// β and γ of every vertex whose rule is the smooth one (Smooth, Dart, or the smooth part of a
/// semi-sharp blend) and whose weights are tuned; (1, 1) elsewhere. Empty for Catmull–Clark's own.
OwnEdgeFaceWeights own_edge_face_weights(const Topology& parent, const detail::EffectiveSharpness& effective,
                                         CreasingMethod creasing, const TunedWeights& weights,
                                         const std::vector<bool>& forced) {
    OwnEdgeFaceWeights own;
    if (weights.is_catmull_clark()) {
        return own;
    }
    own.beta.assign(at(parent.num_vertices()), 1.0);
    own.gamma.assign(at(parent.num_vertices()), 1.0);
    bool any = false;
    detail::VertexMask mask;
    detail::VertexMaskWorkspace work;
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto record = [&](Index u, detail::VertexMask&) {
            const VertexRuleWeights w = weights.at(u, static_cast<int>(parent.valence(u)));
            own.beta[at(u)] = w.beta;
            own.gamma[at(u)] = w.gamma;
            any = any || w.beta != 1.0 || w.gamma != 1.0;
        };
        detail::vertex_mask(parent, effective, creasing, v, record, mask, work);
        if (!forced.empty() && forced[at(v)]) {  // smooth in the mesh this copy came from
            detail::VertexMask unused;
            record(v, unused);
        }
    }
    if (!any) {
        own = {};
    }
    return own;
}

}  // namespace

Level refine_catmull_clark(const Topology& parent, const SchemeOptions& options, const TunedWeights& weights) {
    return detail::refine_catmull_clark_forced(parent, options, weights, {});
}

Level detail::refine_catmull_clark_forced(const Topology& parent, const SchemeOptions& options,
                                          const TunedWeights& weights, const std::vector<bool>& forced,
                                          const StepRun& run) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    auto effective = detail::effective_sharpness(parent, options.boundary);
    auto child = detail::split_child(parent, detail::Split::Quads, run, [&] {
        return detail::child_sharpness(parent, effective, options.creasing, V + F, false);
    });

    // Regular interior rows: 9 (vertex), 4 (face), 6 (edge) entries.
    detail::SparseRowBuilder rows(V + F + E, V, 9 * V + parent.num_corners() + 6 * E, run);

    // The paper's convention (iga-tuned-catmull-clark-weights Fig. 1): α, β, γ are an
    // extraordinary vertex's own weights in its vertex rule, in the edge rule of its edges and in the
    // face rule of its faces; neighbours, other corners and new face points weigh 1; each rule is
    // normalised to sum to 1. Catmull–Clark's own: α = n(n−2), β = γ = 1.
    const OwnEdgeFaceWeights own = own_edge_face_weights(parent, effective, options.creasing, weights, forced);

    // Vertex points: (α v + Σ neighbours + Σ new face points) / (α + 2n).
    const auto smooth = [&](Index v, detail::VertexMask& mask) {
        const auto n = mask.edges.size();
        const VertexRuleWeights given = weights.at(v, static_cast<int>(n));
        const Eigen::Vector3d w = scale_free({given.alpha, 1.0, 1.0});  // v, neighbours, face points
        const double nd = static_cast<double>(n);
        const double denominator = w[0] + nd * w[1] + nd * w[2];
        mask.vertex = w[0] / denominator;
        const double edge_weight = w[1] / denominator;
        const double face_weight = w[2] / denominator;
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
                add_face_point(parent, faces[i], mask.faces[i], own, rows);
            }
        }
        rows.end_row();
    }

    // Face points: centroids (γ-weighted at tuned corners).
    for (Index f = 0; f < F; ++f) {
        add_face_point(parent, f, 1.0, own, rows);
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
        // Smooth mask (an edge with one face is a boundary edge, always sharp):
        // (β₀ v₀ + β₁ v₁ + f₀ + f₁) / (β₀ + β₁ + 2), β = 1 unless an end is tuned.
        double vertex_weight = 0.25;
        double face_weight = 0.25;
        double end_weight[2] = {0.25, 0.25};
        const bool tuned_edge = !own.empty() && (own.beta[at(ends[0])] != 1.0 || own.beta[at(ends[1])] != 1.0);
        const bool triangle_rule =
            smooth_triangles && (parent.face_degree(faces[0]) == 3 || parent.face_degree(faces[1]) == 3);
        if (triangle_rule) {
            const double w0 = parent.face_degree(faces[0]) == 3 ? smooth_triangle_edge_weight : 0.25;
            const double w1 = parent.face_degree(faces[1]) == 3 ? smooth_triangle_edge_weight : 0.25;
            face_weight = 0.5 * (w0 + w1);
            vertex_weight = 0.5 * (1.0 - 2.0 * face_weight);
        }
        end_weight[0] = end_weight[1] = vertex_weight;
        if (tuned_edge && !triangle_rule) {
            const Eigen::Vector3d b = scale_free({own.beta[at(ends[0])], own.beta[at(ends[1])], 1.0});
            const double sum = b[0] + b[1] + 2.0 * b[2];  // two ends, two face points of weight 1
            end_weight[0] = b[0] / sum;
            end_weight[1] = b[1] / sum;
            face_weight = b[2] / sum;
        }
        if (is_sharp(s)) {
            // Crease decaying to smooth: blend with the crease mask by the edge's sharpness.
            const double c = 1.0 - s;
            end_weight[0] = s * 0.5 + c * end_weight[0];
            end_weight[1] = s * 0.5 + c * end_weight[1];
            face_weight *= c;
        }
        rows.add(ends[0], end_weight[0]);
        rows.add(ends[1], end_weight[1]);
        add_face_point(parent, faces[0], face_weight, own, rows);
        add_face_point(parent, faces[1], face_weight, own, rows);
        rows.end_row();
    }

    return detail::finish_step(parent, child, rows, run, detail::Split::Quads, &effective);
}

}  // namespace limsurf
