// Exterior derivatives from the topology (exterior_derivative.h).
#include "limsurf/sec/exterior_derivative.h"

#include <vector>

namespace limsurf {

SparseMatrix exterior_derivative_0(const Topology& topology) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(2 * static_cast<std::size_t>(topology.num_edges()));
    for (Index e = 0; e < topology.num_edges(); ++e) {
        const auto ends = topology.edge_vertices(e);  // lower (tail) first
        entries.emplace_back(e, ends[0], -1.0);
        entries.emplace_back(e, ends[1], 1.0);
    }
    SparseMatrix d0(topology.num_edges(), topology.num_vertices());
    d0.setFromTriplets(entries.begin(), entries.end());
    return d0;
}

SparseMatrix exterior_derivative_1(const Topology& topology) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(topology.num_corners()));
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const auto edges = topology.face_edges(f);
        const auto signs = topology.face_edge_signs(f);
        for (std::size_t k = 0; k < edges.size(); ++k) {
            entries.emplace_back(f, edges[k], static_cast<double>(signs[k]));
        }
    }
    SparseMatrix d1(topology.num_faces(), topology.num_edges());
    d1.setFromTriplets(entries.begin(), entries.end());
    return d1;
}

}  // namespace limsurf
