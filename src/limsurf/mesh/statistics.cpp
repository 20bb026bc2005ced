#include "limsurf/mesh/statistics.h"

#include <algorithm>

namespace limsurf {

MeshStatistics statistics(const ControlMesh& mesh) {
    const Topology& t = mesh.topology();
    MeshStatistics stats;
    for (Index f = 0; f < t.num_faces(); ++f) {
        ++stats.face_degrees[t.face_degree(f)];
        stats.sharpness.num_holes += t.is_hole(f) ? 1 : 0;
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        ++(t.is_boundary_vertex(v) ? stats.boundary_valences : stats.interior_valences)[t.valence(v)];
        const double s = t.vertex_sharpness(v);
        stats.sharpness.num_sharp_vertices += s > 0.0 ? 1 : 0;
        stats.sharpness.num_infinitely_sharp_vertices += s >= infinite_sharpness ? 1 : 0;
    }
    for (Index e = 0; e < t.num_edges(); ++e) {
        const double s = t.edge_sharpness(e);
        stats.sharpness.num_sharp_edges += s > 0.0 ? 1 : 0;
        stats.sharpness.num_infinitely_sharp_edges += s >= infinite_sharpness ? 1 : 0;
        if (s < infinite_sharpness) {
            stats.sharpness.max_semi_sharp_edge = std::max(stats.sharpness.max_semi_sharp_edge, s);
        }
    }
    for (Index i = 0; i < t.num_boundary_loops(); ++i) {
        stats.boundary_loop_lengths.push_back(static_cast<Index>(t.boundary_loop(i).size()));
    }
    if (mesh.positions().rows() > 0) {
        stats.bounding_box_min = mesh.positions().colwise().minCoeff().transpose();
        stats.bounding_box_max = mesh.positions().colwise().maxCoeff().transpose();
    }
    return stats;
}

}  // namespace limsurf
