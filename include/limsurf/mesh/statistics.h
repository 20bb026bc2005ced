// Summary numbers of a control mesh: what `limsurf info` prints.
#pragma once

#include <map>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/control_mesh.h"

namespace limsurf {

/// How sharp the mesh is (see sharpness.h for the scale).
struct SharpnessSummary {
    Index num_sharp_edges = 0;             ///< edges with sharpness > 0
    Index num_infinitely_sharp_edges = 0;  ///< edges with sharpness >= infinite_sharpness
    double max_semi_sharp_edge = 0.0;      ///< largest sharpness below infinite_sharpness (0 if none)
    Index num_sharp_vertices = 0;          ///< vertices with sharpness > 0 (corners)
    Index num_infinitely_sharp_vertices = 0;
    Index num_holes = 0;
};

/// Counts and histograms of a mesh.
struct MeshStatistics {
    std::map<Index, Index> face_degrees;       ///< degree -> number of faces
    std::map<Index, Index> interior_valences;  ///< valence -> number of interior vertices
    std::map<Index, Index> boundary_valences;  ///< valence -> number of boundary vertices
    std::vector<Index> boundary_loop_lengths;  ///< vertices per boundary loop, in loop order
    Eigen::Vector3d bounding_box_min = Eigen::Vector3d::Zero();
    Eigen::Vector3d bounding_box_max = Eigen::Vector3d::Zero();
    SharpnessSummary sharpness;
};

/// @brief Histograms, boundary loops, bounding box and sharpness of @p mesh.
[[nodiscard]] MeshStatistics statistics(const ControlMesh& mesh);

}  // namespace limsurf
