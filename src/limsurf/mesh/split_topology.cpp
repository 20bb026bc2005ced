// The child topology of the quad split and the triangle split, built directly from the parent's
// tables (as OpenSubdiv's Vtr refines its levels): a child edge is half of a parent edge or an edge
// inside a parent face, a child one-ring follows the parent's, and components and genus do not
// change. Nothing is sorted and no one-ring is walked. The tables are those the general constructor
// builds from the child's face list — the same edge numbering (first appearance in the face list),
// the same one-ring starts and orders — which tests/refine/face_split/child_topology_test.cpp checks table by
// table; the derivation of each one-ring is in the comments below.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/detail/connectivity.h"
#include "limsurf/detail/huge_pages.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/mesh/validate.h"

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Numbers child edges in order of first appearance: each child edge has a key (a half of a parent
/// edge, or an edge inside a parent face) and gets the next number the first time its key is seen.
class EdgeNumbering {
  public:
    EdgeNumbering(Index num_keys, HugeTable<Index>& edge_vertices, HugeTable<Index>& edge_face_offsets)
        : edge_vertices_(edge_vertices), edge_face_offsets_(edge_face_offsets) {
        assign_huge(number_, at(num_keys), invalid_index);
        assign_huge(edge_vertices_, 2 * at(num_keys));
        assign_huge(edge_face_offsets_, at(num_keys) + 1, 0);
    }
    /// The number of the child edge with @p key joining @p a and @p b, which has @p num_faces faces.
    Index operator()(Index key, Index a, Index b, Index num_faces) {
        Index& e = number_[at(key)];
        if (e == invalid_index) {
            e = next_++;
            edge_vertices_[2 * at(e)] = std::min(a, b);
            edge_vertices_[2 * at(e) + 1] = std::max(a, b);
            edge_face_offsets_[at(e) + 1] = num_faces;
        }
        return e;
    }
    /// The number given to @p key. @pre it was seen
    [[nodiscard]] Index of(Index key) const { return number_[at(key)]; }

  private:
    HugeTable<Index> number_;
    Index next_ = 0;
    HugeTable<Index>& edge_vertices_;
    HugeTable<Index>& edge_face_offsets_;
};

/// Key of the half of parent edge @p e at its lower (@p higher_end false) or higher end.
Index half_key(Index e, bool higher_end) {
    return 2 * e + (higher_end ? 1 : 0);
}

/// For every parent edge, the corner at which each of its faces enters it, in the order of
/// edge_faces(e) (the face running it lower -> higher first); the second is invalid_index on the boundary.
HugeTable<std::array<Index, 2>> edge_corners(const Topology& parent) {
    HugeTable<std::array<Index, 2>> corners;
    assign_huge(corners, at(parent.num_edges()), {invalid_index, invalid_index});
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index first = parent.face_offset(f);
        const auto face_edges = parent.face_edges(f);
        const auto signs = parent.face_edge_signs(f);
        for (std::size_t k = 0; k < face_edges.size(); ++k) {
            const Index e = face_edges[k];
            const bool single = parent.is_boundary_edge(e);
            corners[at(e)][signs[k] > 0 || single ? 0 : 1] = first + static_cast<Index>(k);
        }
    }
    return corners;
}

/// Writes a cyclic one-ring (faces, their corners at the vertex, the edge each face leaves the
/// vertex by) starting at its face of least index: an interior vertex's walk starts at its first
/// corner in the face list, i.e. in its face of least index.
template <std::size_t N>
void write_interior_ring(const std::array<Index, N>& faces, const std::array<Index, N>& corners,
                         const std::array<Index, N>& edges, Index* out_faces, Index* out_corners, Index* out_edges) {
    const auto first = static_cast<std::size_t>(std::min_element(faces.begin(), faces.end()) - faces.begin());
    for (std::size_t i = 0; i < N; ++i) {
        const std::size_t j = (first + i) % N;
        out_faces[i] = faces[j];
        out_corners[i] = corners[j];
        out_edges[i] = edges[j];
    }
}

/// The first V child vertices are the parent vertices' children: their one-ring sizes and boundary
/// flags are the parent's. @pre @p face_counts has #V_child + 1 entries, @p boundary #V_child
void copy_parent_vertex_ring_sizes(const Topology& parent, HugeTable<Index>& face_counts,
                                   HugeTable<std::uint8_t>& boundary) {
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        face_counts[at(v) + 1] = static_cast<Index>(parent.vertex_faces(v).size());
        boundary[at(v)] = parent.is_boundary_vertex(v) ? 1 : 0;
    }
}

/// A parent vertex's child: the children at its corners, in the parent's order (the first corner
/// and the boundary start are the parent's); it is corner 0 of each; its edges are the halves at
/// it of its parent edges. Its slots are the parent vertex's (the first V child vertices, of the
/// same sizes). @p child_face(f, k) is the child of parent face f at its corner k.
template <class ChildFace>
void fill_parent_vertex_rings(const Topology& parent, const EdgeNumbering& number, const ChildFace& child_face,
                              HugeTable<Index>& faces, HugeTable<Index>& corners, HugeTable<Index>& edges) {
    Index face_slot = 0;
    Index edge_slot = 0;
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto ring_faces = parent.vertex_faces(v);
        const auto ring_corners = parent.vertex_face_corners(v);
        for (std::size_t i = 0; i < ring_faces.size(); ++i, ++face_slot) {
            faces[at(face_slot)] = child_face(ring_faces[i], ring_corners[i]);
            corners[at(face_slot)] = 0;
        }
        for (const Index e : parent.vertex_edges(v)) {
            edges[at(edge_slot++)] = number.of(half_key(e, parent.edge_vertices(e)[1] == v));
        }
    }
}

/// Child faces [first_child(f), first_child(f + 1)) lie in the component of parent face f.
template <class FirstChild>
void inherit_components(const Topology& parent, const FirstChild& first_child, HugeTable<Index>& component) {
    assign_huge(component, at(first_child(parent.num_faces())));
    for (Index f = 0; f < parent.num_faces(); ++f) {
        std::fill(component.begin() + first_child(f), component.begin() + first_child(f + 1), parent.face_component(f));
    }
}

}  // namespace

namespace {

/// Debug and sanitizer builds check what refinement produced.
void check_child(const Topology& child) {
#ifndef NDEBUG
    ValidationReport report;
    check_connectivity({child.num_vertices(), child.face_offsets(), child.all_face_vertices()}, child.sharpness_tags(),
                       SourceMap{}, report);
    LIMSURF_ASSERT(!report.has_errors(), "refinement produced an invalid topology: ", report.summary());
#else
    (void)child;
#endif
}

}  // namespace

Topology quad_split_topology(const Topology& parent, const SharpnessTags& child_sharpness) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    const Index C = parent.num_corners();
    const Index face_point = V;      // child vertex of parent face f: face_point + f
    const Index edge_point = V + F;  // child vertex of parent edge e: edge_point + e
    Topology child;
    child.num_vertices_ = V + F + E;

    // Faces: child c of parent corner c is [v_k, e_k, f, e_(k-1)] (refine/level.h). Edges, keyed:
    // halves of parent edges (2E keys), then spokes (2E + c: from the point of the edge leaving
    // corner c to its face point).
    assign_huge(child.face_offsets_, at(C) + 1);
    for (std::size_t i = 0; i < child.face_offsets_.size(); ++i) {
        child.face_offsets_[i] = static_cast<Index>(4 * i);
    }
    assign_huge(child.face_vertices_, 4 * at(C));
    assign_huge(child.face_edges_, 4 * at(C));
    assign_huge(child.face_edge_signs_, 4 * at(C));
    EdgeNumbering number(2 * E + C, child.edge_vertices_, child.edge_face_offsets_);
    for (Index f = 0; f < F; ++f) {
        const Index first = parent.face_offsets_[at(f)];
        const Index last = parent.face_offsets_[at(f) + 1] - 1;
        for (Index c = first; c <= last; ++c) {
            const Index previous = c == first ? last : c - 1;
            const Index e_next = parent.face_edges_[at(c)];
            const Index e_prev = parent.face_edges_[at(previous)];
            const std::array<Index, 4> corners{parent.face_vertices_[at(c)], edge_point + e_next, face_point + f,
                                               edge_point + e_prev};
            // Corner c runs e_next lower -> higher when its sign is +1 (then v_k is e_next's lower end);
            // the previous corner runs e_prev into v_k.
            const bool v_higher_on_next = parent.face_edge_signs_[at(c)] < 0;
            const bool v_higher_on_prev = parent.face_edge_signs_[at(previous)] > 0;
            const std::array<Index, 4> edges{
                number(half_key(e_next, v_higher_on_next), corners[0], corners[1],
                       parent.edge_face_offsets_[at(e_next) + 1] - parent.edge_face_offsets_[at(e_next)]),
                number(2 * E + c, corners[1], corners[2], 2), number(2 * E + previous, corners[2], corners[3], 2),
                number(half_key(e_prev, v_higher_on_prev), corners[3], corners[0],
                       parent.edge_face_offsets_[at(e_prev) + 1] - parent.edge_face_offsets_[at(e_prev)])};
            for (std::size_t i = 0; i < 4; ++i) {
                const auto slot = 4 * at(c) + i;
                child.face_vertices_[slot] = corners[i];
                child.face_edges_[slot] = edges[i];
                child.face_edge_signs_[slot] = corners[i] < corners[(i + 1) % 4] ? 1 : -1;
            }
        }
    }
    child.fill_edge_faces(nullptr);

    // One-ring sizes: a parent vertex's child has its faces; a face point one face per corner of its
    // face; an edge point two per face of its edge, and it is on the boundary when the edge is.
    assign_huge(child.vertex_face_offsets_, at(child.num_vertices_) + 1, 0);
    assign_huge(child.vertex_is_boundary_, at(child.num_vertices_), 0);
    copy_parent_vertex_ring_sizes(parent, child.vertex_face_offsets_, child.vertex_is_boundary_);
    for (Index f = 0; f < F; ++f) {
        child.vertex_face_offsets_[at(face_point + f) + 1] = parent.face_degree(f);
    }
    for (Index e = 0; e < E; ++e) {
        const Index faces = parent.edge_face_offsets_[at(e) + 1] - parent.edge_face_offsets_[at(e)];
        child.vertex_face_offsets_[at(edge_point + e) + 1] = 2 * faces;
        child.vertex_is_boundary_[at(edge_point + e)] = faces == 1 ? 1 : 0;
    }
    child.allocate_one_rings();

    // A parent vertex's child: child c of each parent corner c at it.
    fill_parent_vertex_rings(
        parent, number, [&](Index f, Index k) { return parent.face_offsets_[at(f)] + k; }, child.vertex_faces_,
        child.vertex_face_corners_, child.vertex_edges_);
    // A face point: the children of its face in order, at their corner 2; child k leaves it by the
    // spoke of edge k−1.
    for (Index f = 0; f < F; ++f) {
        const Index first = parent.face_offsets_[at(f)];
        const Index n = parent.face_degree(f);
        const Index slot = child.vertex_face_offsets_[at(face_point + f)];
        const Index edge_slot = child.vertex_edge_offsets_[at(face_point + f)];
        for (Index k = 0; k < n; ++k) {
            child.vertex_faces_[at(slot + k)] = first + k;
            child.vertex_face_corners_[at(slot + k)] = 2;
            child.vertex_edges_[at(edge_slot + k)] = number.of(2 * E + first + (k == 0 ? n - 1 : k - 1));
        }
    }
    // An edge point of edge e (from v_k to v_k+1 at corner c of face g; from v_k+1 to v_k at corner
    // c' of face g'): counter-clockwise, child c (at its corner 1, leaving by the spoke of c), child
    // next(c') (corner 3, leaving by the half at v_k), child c' (corner 1, spoke of c'), child next(c)
    // (corner 3, half at v_k+1). On the boundary the walk starts where the boundary half leaves it:
    // child next(c), then child c, then the closing half at v_k.
    const auto edge_corner = edge_corners(parent);
    for (Index e = 0; e < E; ++e) {
        const Index v = edge_point + e;
        Index* faces = &child.vertex_faces_[at(child.vertex_face_offsets_[at(v)])];
        Index* corners = &child.vertex_face_corners_[at(child.vertex_face_offsets_[at(v)])];
        Index* edges = &child.vertex_edges_[at(child.vertex_edge_offsets_[at(v)])];
        const auto face_slots = parent.edge_face_offsets_[at(e)];
        const Index c = edge_corner[at(e)][0];
        const Index next_c = parent.next_corner(parent.edge_faces_[at(face_slots)], c);
        const bool vk_is_lower = parent.face_edge_signs_[at(c)] > 0;
        const Index half_at_vk = number.of(half_key(e, !vk_is_lower));
        const Index half_at_vk1 = number.of(half_key(e, vk_is_lower));
        if (child.vertex_is_boundary_[at(v)] != 0) {
            faces[0] = next_c;
            corners[0] = 3;
            edges[0] = half_at_vk1;
            faces[1] = c;
            corners[1] = 1;
            edges[1] = number.of(2 * E + c);
            edges[2] = half_at_vk;
            continue;
        }
        const Index c_other = edge_corner[at(e)][1];
        const Index next_other = parent.next_corner(parent.edge_faces_[at(face_slots) + 1], c_other);
        write_interior_ring<4>({c, next_other, c_other, next_c}, {1, 3, 1, 3},
                               {number.of(2 * E + c), half_at_vk, number.of(2 * E + c_other), half_at_vk1}, faces,
                               corners, edges);
    }

    // Components and genus are the parent's; child faces come in parent face order, so the
    // components keep their numbers (by first face).
    inherit_components(
        parent, [&](Index f) { return parent.face_offsets_[at(f)]; }, child.face_component_);
    child.num_components_ = parent.num_components_;
    child.genus_ = parent.genus_;
    child.build_boundary_loops();
    child.apply_sharpness(child_sharpness);
    check_child(child);
    return child;
}

Topology tri_split_topology(const Topology& parent, const SharpnessTags& child_sharpness) {
    LIMSURF_ASSERT(parent.all_faces_have_degree(3), "the triangle split needs triangles");
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index E = parent.num_edges();
    const Index edge_point = V;  // child vertex of parent edge e: edge_point + e
    Topology child;
    child.num_vertices_ = V + E;

    // Faces: children 4f + k = [v_k, e_k, e_(k-1)] (k = 0, 1, 2), then the middle [e_0, e_1, e_2]
    // (refine/level.h). Edges, keyed: halves of parent edges (2E keys), then the inner edges of face
    // f (2E + 3f + k: between the points of e_k and e_(k-1)).
    const auto faces_count = 4 * at(F);
    assign_huge(child.face_offsets_, faces_count + 1);
    for (std::size_t i = 0; i < child.face_offsets_.size(); ++i) {
        child.face_offsets_[i] = static_cast<Index>(3 * i);
    }
    assign_huge(child.face_vertices_, 3 * faces_count);
    assign_huge(child.face_edges_, 3 * faces_count);
    assign_huge(child.face_edge_signs_, 3 * faces_count);
    EdgeNumbering number(2 * E + 3 * F, child.edge_vertices_, child.edge_face_offsets_);
    const auto faces_of = [&](Index e) {
        return parent.edge_face_offsets_[at(e) + 1] - parent.edge_face_offsets_[at(e)];
    };
    const auto inner_key = [&](Index f, Index k) { return 2 * E + 3 * f + k % 3; };
    std::size_t slot = 0;
    const auto write = [&](const std::array<Index, 3>& corners, const std::array<Index, 3>& edges) {
        for (std::size_t i = 0; i < 3; ++i, ++slot) {
            child.face_vertices_[slot] = corners[i];
            child.face_edges_[slot] = edges[i];
            child.face_edge_signs_[slot] = corners[i] < corners[(i + 1) % 3] ? 1 : -1;
        }
    };
    for (Index f = 0; f < F; ++f) {
        const Index first = 3 * f;
        std::array<Index, 3> points{};
        for (Index k = 0; k < 3; ++k) {
            points[at(k)] = edge_point + parent.face_edges_[at(first + k)];
        }
        for (Index k = 0; k < 3; ++k) {
            const Index c = first + k;
            const Index previous = first + (k + 2) % 3;
            const Index e_next = parent.face_edges_[at(c)];
            const Index e_prev = parent.face_edges_[at(previous)];
            const std::array<Index, 3> corners{parent.face_vertices_[at(c)], points[at(k)], points[at((k + 2) % 3)]};
            const bool v_higher_on_next = parent.face_edge_signs_[at(c)] < 0;
            const bool v_higher_on_prev = parent.face_edge_signs_[at(previous)] > 0;
            write(corners, {number(half_key(e_next, v_higher_on_next), corners[0], corners[1], faces_of(e_next)),
                            number(inner_key(f, k), corners[1], corners[2], 2),
                            number(half_key(e_prev, v_higher_on_prev), corners[2], corners[0], faces_of(e_prev))});
        }
        write(points,
              {number(inner_key(f, 1), points[0], points[1], 2), number(inner_key(f, 2), points[1], points[2], 2),
               number(inner_key(f, 3), points[2], points[0], 2)});
    }
    child.fill_edge_faces(nullptr);

    // One-ring sizes: a parent vertex's child has its faces; an edge point three per face of its
    // edge, and it is on the boundary when the edge is.
    assign_huge(child.vertex_face_offsets_, at(child.num_vertices_) + 1, 0);
    assign_huge(child.vertex_is_boundary_, at(child.num_vertices_), 0);
    copy_parent_vertex_ring_sizes(parent, child.vertex_face_offsets_, child.vertex_is_boundary_);
    for (Index e = 0; e < E; ++e) {
        child.vertex_face_offsets_[at(edge_point + e) + 1] = 3 * faces_of(e);
        child.vertex_is_boundary_[at(edge_point + e)] = faces_of(e) == 1 ? 1 : 0;
    }
    child.allocate_one_rings();

    // A parent vertex's child: the corner children 4f + k.
    fill_parent_vertex_rings(
        parent, number, [](Index f, Index k) { return 4 * f + k; }, child.vertex_faces_, child.vertex_face_corners_,
        child.vertex_edges_);
    // An edge point of edge e (from v_k to v_k+1 at corner k of face g; from v_k+1 to v_k at corner m
    // of face g'): counter-clockwise, g's child k (at its corner 1), g''s child m+1 (corner 2), g''s
    // middle (corner m), g''s child m (corner 1), g's child k+1 (corner 2), g's middle (corner k),
    // each left by the edge named in the call. On the boundary the walk starts at g's child k+1,
    // where the boundary half leaves it, and closes with the half at v_k.
    const auto edge_corner = edge_corners(parent);
    for (Index e = 0; e < E; ++e) {
        const Index v = edge_point + e;
        Index* faces = &child.vertex_faces_[at(child.vertex_face_offsets_[at(v)])];
        Index* corners = &child.vertex_face_corners_[at(child.vertex_face_offsets_[at(v)])];
        Index* edges = &child.vertex_edges_[at(child.vertex_edge_offsets_[at(v)])];
        const Index g = edge_corner[at(e)][0] / 3;
        const Index k = edge_corner[at(e)][0] % 3;
        const bool vk_is_lower = parent.face_edge_signs_[at(edge_corner[at(e)][0])] > 0;
        const Index half_at_vk = number.of(half_key(e, !vk_is_lower));
        const Index half_at_vk1 = number.of(half_key(e, vk_is_lower));
        if (child.vertex_is_boundary_[at(v)] != 0) {
            const std::array<Index, 3> ring_faces{4 * g + (k + 1) % 3, 4 * g + 3, 4 * g + k};
            const std::array<Index, 3> ring_corners{2, k, 1};
            const std::array<Index, 4> ring_edges{half_at_vk1, number.of(inner_key(g, k + 1)),
                                                  number.of(inner_key(g, k)), half_at_vk};
            std::copy(ring_faces.begin(), ring_faces.end(), faces);
            std::copy(ring_corners.begin(), ring_corners.end(), corners);
            std::copy(ring_edges.begin(), ring_edges.end(), edges);
            continue;
        }
        const Index h = edge_corner[at(e)][1] / 3;
        const Index m = edge_corner[at(e)][1] % 3;
        write_interior_ring<6>({4 * g + k, 4 * h + (m + 1) % 3, 4 * h + 3, 4 * h + m, 4 * g + (k + 1) % 3, 4 * g + 3},
                               {1, 2, m, 1, 2, k},
                               {number.of(inner_key(g, k)), half_at_vk, number.of(inner_key(h, m + 1)),
                                number.of(inner_key(h, m)), half_at_vk1, number.of(inner_key(g, k + 1))},
                               faces, corners, edges);
    }

    inherit_components(
        parent, [](Index f) { return 4 * f; }, child.face_component_);
    child.num_components_ = parent.num_components_;
    child.genus_ = parent.genus_;
    child.build_boundary_loops();
    child.apply_sharpness(child_sharpness);
    check_child(child);
    return child;
}

}  // namespace limsurf::detail
