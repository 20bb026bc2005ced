// Level: one refinement step as data — the child topology, the sparse matrix
// S0 that carries any per-vertex data from the parent to the child, and the
// provenance of every child vertex and face (DESIGN.md §2, docs/conventions.md
// "Refinement").
//
// Child vertex order (as OpenSubdiv Far's uniform refinement):
//   Catmull–Clark / bilinear: children of parent vertices (child v = parent v),
//     then one point per parent face (in face order), then one per parent edge
//     (in the parent's edge order).
//   Loop / linear: children of parent vertices, then one point per parent edge.
//   Doo–Sabin: one child vertex per parent face corner, in corner order.
// Child face order: the children of parent face 0, then of face 1, ...;
//   quad split: child k of face f is [v_k, e(v_k, v_k+1), face point, e(v_k-1, v_k)];
//   triangle split: child k (k = 0, 1, 2) is [v_k, e(v_k, v_k+1), e(v_k-1, v_k)],
//     then the middle triangle [e01, e12, e20];
//   Doo–Sabin: see refine_doo_sabin() (F-, E- and V-faces).
// Orientation is inherited from the parent.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"

namespace limsurf {

/// The kind of parent element a child element comes from.
enum class ParentKind : std::uint8_t { Vertex, Edge, Face };

/// Where each child vertex and face came from.
struct Provenance {
    std::vector<ParentKind> vertex_parent_kind;  ///< #V_child
    std::vector<Index> vertex_parent;            ///< #V_child: the parent vertex, edge or face
    std::vector<ParentKind> face_parent_kind;    ///< #F_child (Face for every face of the face-split schemes)
    std::vector<Index> face_parent;              ///< #F_child: the parent face (or edge/vertex, Doo–Sabin)
    /// #F_child: the corner of the parent face the child face sits at, or
    /// invalid_index (the middle triangle of a triangle split; Doo–Sabin E/V-faces).
    std::vector<Index> face_parent_corner;
};

/// One refinement step.
struct Level {
    Topology topology;      ///< the child topology, with sharpness carried to it
    SparseMatrix S0;        ///< #V_child × #V_parent; child values = S0 · parent values
    Provenance provenance;  ///< where each child vertex and face came from
    /// Form subdivision (form_subdivision.h), empty (0 × 0) unless asked for:
    /// #E_child × #E_parent and #F_child × #F_parent.
    SparseMatrix S1;
    SparseMatrix S2;

    Level() = default;
    /// Takes S0 over without copying it.
    Level(Topology child, SparseMatrix&& s0, Provenance where)
        : topology(std::move(child)), provenance(std::move(where)) {
        S0.swap(s0);
    }
    // Eigen 3.4's SparseMatrix has no move constructor: moving a Level swaps S0
    // instead of copying it (a level's S0 holds millions of non-zeros).
    Level(Level&& other) noexcept : topology(std::move(other.topology)), provenance(std::move(other.provenance)) {
        S0.swap(other.S0);
        S1.swap(other.S1);
        S2.swap(other.S2);
    }
    Level& operator=(Level&& other) noexcept {
        topology = std::move(other.topology);
        S0.swap(other.S0);
        provenance = std::move(other.provenance);
        S1.swap(other.S1);
        S2.swap(other.S2);
        return *this;
    }
    Level(const Level&) = default;
    Level& operator=(const Level&) = default;
    ~Level() = default;
};

}  // namespace limsurf
