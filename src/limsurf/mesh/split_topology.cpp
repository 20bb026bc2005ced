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
    /// @pre every key names one child edge (the child has @p num_keys edges)
    EdgeNumbering(Index num_keys, HugeTable<Index>& edge_vertices) : edge_vertices_(edge_vertices) {
        assign_huge(number_, at(num_keys), invalid_index);
        assign_huge(edge_vertices_, 2 * at(num_keys));
    }
    /// The number of the child edge with @p key joining @p a and @p b.
    Index operator()(Index key, Index a, Index b) {
        Index& e = number_[at(key)];
        if (e == invalid_index) {
            e = next_++;
            edge_vertices_[2 * at(e)] = std::min(a, b);
            edge_vertices_[2 * at(e) + 1] = std::max(a, b);
        }
        return e;
    }

  private:
    HugeTable<Index> number_;
    Index next_ = 0;
    HugeTable<Index>& edge_vertices_;
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
                         const std::array<Index, N>& edges, Index* out_faces, std::uint8_t* out_corners,
                         Index* out_edges) {
    const auto first = static_cast<std::size_t>(std::min_element(faces.begin(), faces.end()) - faces.begin());
    for (std::size_t i = 0; i < N; ++i) {
        const std::size_t j = (first + i) % N;
        out_faces[i] = faces[j];
        out_corners[i] = static_cast<std::uint8_t>(corners[j]);  // < 4 in the splits
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
/// it of its parent edges: each child's first side (the half of the parent edge leaving the corner),
/// and on the boundary the last child's last side (the half of the edge entering it). Its slots are
/// the parent vertex's (the first V child vertices, of the same sizes). @p child_face(f, k) is the
/// child of parent face f at its corner k; @p child has its faces and their edges.
template <class ChildFace>
void fill_parent_vertex_rings(const Topology& parent, const Topology& child, const ChildFace& child_face,
                              HugeTable<Index>& faces, HugeTable<std::uint8_t>& corners, HugeTable<Index>& edges) {
    Index face_slot = 0;
    Index edge_slot = 0;
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto ring_faces = parent.vertex_faces(v);
        const auto ring_corners = parent.vertex_face_corners(v);
        for (std::size_t i = 0; i < ring_faces.size(); ++i, ++face_slot) {
            const Index g = child_face(ring_faces[i], ring_corners[i]);
            faces[at(face_slot)] = g;
            corners[at(face_slot)] = 0;
            edges[at(edge_slot++)] = child.face_edges(g).front();
        }
        if (parent.is_boundary_vertex(v)) {
            edges[at(edge_slot++)] = child.face_edges(faces[at(face_slot - 1)]).back();
        }
    }
}

/// Child faces [first_child(f), first_child(f + 1)) lie in the component of parent face f (no table
/// for one component, as the parent's).
template <class FirstChild>
void inherit_components(const Topology& parent, const FirstChild& first_child, HugeTable<Index>& component) {
    if (parent.num_components() == 1) {
        return;
    }
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
    {  // the numbering's table goes before the one-rings' are made
        EdgeNumbering number(2 * E + C, child.edge_vertices_);
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
                const bool v_higher_on_next = parent.corner_sign(f, c) < 0;
                const bool v_higher_on_prev = parent.corner_sign(f, previous) > 0;
                const std::array<Index, 4> edges{number(half_key(e_next, v_higher_on_next), corners[0], corners[1]),
                                                 number(2 * E + c, corners[1], corners[2]),
                                                 number(2 * E + previous, corners[2], corners[3]),
                                                 number(half_key(e_prev, v_higher_on_prev), corners[3], corners[0])};
                for (std::size_t i = 0; i < 4; ++i) {
                    const auto slot = 4 * at(c) + i;
                    child.face_vertices_[slot] = corners[i];
                    child.face_edges_[slot] = edges[i];
                }
            }
        }
    }
    child.fill_edge_faces(nullptr);
    // Child c's sides: 0 the half at v_k of the parent edge leaving corner c, 1 the spoke of c (key
    // 2E + c), 2 the spoke of c's previous corner, 3 the half at v_k of the edge entering it.
    const auto side = [&](Index c, std::size_t i) { return child.face_edges_[4 * at(c) + i]; };

    // One-ring sizes: a parent vertex's child has its faces; a face point one face per corner of its
    // face; an edge point two per face of its edge, and it is on the boundary when the edge is.
    assign_huge(child.vertex_face_offsets_, at(child.num_vertices_) + 1, 0);
    assign_huge(child.vertex_is_boundary_, at(child.num_vertices_), 0);
    copy_parent_vertex_ring_sizes(parent, child.vertex_face_offsets_, child.vertex_is_boundary_);
    for (Index f = 0; f < F; ++f) {
        child.vertex_face_offsets_[at(face_point + f) + 1] = parent.face_degree(f);
    }
    for (Index e = 0; e < E; ++e) {
        const Index faces = parent.edge_face_count(e);
        child.vertex_face_offsets_[at(edge_point + e) + 1] = 2 * faces;
        child.vertex_is_boundary_[at(edge_point + e)] = faces == 1 ? 1 : 0;
    }
    child.allocate_one_rings();

    // A parent vertex's child: child c of each parent corner c at it.
    fill_parent_vertex_rings(
        parent, child, [&](Index f, Index k) { return parent.face_offsets_[at(f)] + k; }, child.vertex_faces_,
        child.vertex_face_corners_, child.vertex_edges_);
    // A face point: the children of its face in order, at their corner 2; child k leaves it by the
    // spoke of edge k−1.
    for (Index f = 0; f < F; ++f) {
        const Index first = parent.face_offsets_[at(f)];
        const Index n = parent.face_degree(f);
        const Index slot = child.vertex_face_offsets_[at(face_point + f)];
        const Index edge_slot = child.vertex_edge_offset(face_point + f);
        for (Index k = 0; k < n; ++k) {
            child.vertex_faces_[at(slot + k)] = first + k;
            child.vertex_face_corners_[at(slot + k)] = 2;
            child.vertex_edges_[at(edge_slot + k)] = side(first + k, 2);
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
        std::uint8_t* corners = &child.vertex_face_corners_[at(child.vertex_face_offsets_[at(v)])];
        Index* edges = &child.vertex_edges_[at(child.vertex_edge_offset(v))];
        const auto face_slots = 2 * e;
        const Index c = edge_corner[at(e)][0];
        const Index next_c = parent.next_corner(parent.edge_faces_[at(face_slots)], c);
        const Index half_at_vk = side(c, 0);
        const Index half_at_vk1 = side(next_c, 3);
        if (child.vertex_is_boundary_[at(v)] != 0) {
            faces[0] = next_c;
            corners[0] = 3;
            edges[0] = half_at_vk1;
            faces[1] = c;
            corners[1] = 1;
            edges[1] = side(c, 1);
            edges[2] = half_at_vk;
            continue;
        }
        const Index c_other = edge_corner[at(e)][1];
        const Index next_other = parent.next_corner(parent.edge_faces_[at(face_slots) + 1], c_other);
        write_interior_ring<4>({c, next_other, c_other, next_c}, {1, 3, 1, 3},
                               {side(c, 1), half_at_vk, side(c_other, 1), half_at_vk1}, faces, corners, edges);
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
    const auto faces_of = [&](Index e) { return parent.edge_face_count(e); };
    const auto inner_key = [&](Index f, Index k) { return 2 * E + 3 * f + k % 3; };
    {  // the numbering's table goes before the one-rings' are made
        EdgeNumbering number(2 * E + 3 * F, child.edge_vertices_);
        std::size_t slot = 0;
        const auto write = [&](const std::array<Index, 3>& corners, const std::array<Index, 3>& edges) {
            for (std::size_t i = 0; i < 3; ++i, ++slot) {
                child.face_vertices_[slot] = corners[i];
                child.face_edges_[slot] = edges[i];
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
                const std::array<Index, 3> corners{parent.face_vertices_[at(c)], points[at(k)],
                                                   points[at((k + 2) % 3)]};
                const bool v_higher_on_next = parent.corner_sign(f, c) < 0;
                const bool v_higher_on_prev = parent.corner_sign(f, previous) > 0;
                write(corners, {number(half_key(e_next, v_higher_on_next), corners[0], corners[1]),
                                number(inner_key(f, k), corners[1], corners[2]),
                                number(half_key(e_prev, v_higher_on_prev), corners[2], corners[0])});
            }
            write(points, {number(inner_key(f, 1), points[0], points[1]), number(inner_key(f, 2), points[1], points[2]),
                           number(inner_key(f, 3), points[2], points[0])});
        }
    }
    child.fill_edge_faces(nullptr);
    // Child 4f + k's sides: 0 the half at v_k of the parent edge leaving corner k, 1 the inner edge
    // of f keyed k, 2 the half at v_k of the edge entering it.
    const auto side = [&](Index f, Index k, std::size_t i) { return child.face_edges_[3 * at(4 * f + k % 3) + i]; };

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
        parent, child, [](Index f, Index k) { return 4 * f + k; }, child.vertex_faces_, child.vertex_face_corners_,
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
        std::uint8_t* corners = &child.vertex_face_corners_[at(child.vertex_face_offsets_[at(v)])];
        Index* edges = &child.vertex_edges_[at(child.vertex_edge_offset(v))];
        const Index g = edge_corner[at(e)][0] / 3;
        const Index k = edge_corner[at(e)][0] % 3;
        const Index half_at_vk = side(g, k, 0);
        const Index half_at_vk1 = side(g, k + 1, 2);
        if (child.vertex_is_boundary_[at(v)] != 0) {
            const std::array<Index, 3> ring_faces{4 * g + (k + 1) % 3, 4 * g + 3, 4 * g + k};
            const std::array<Index, 3> ring_corners{2, k, 1};
            const std::array<Index, 4> ring_edges{half_at_vk1, side(g, k + 1, 1), side(g, k, 1), half_at_vk};
            std::copy(ring_faces.begin(), ring_faces.end(), faces);
            for (std::size_t i = 0; i < ring_corners.size(); ++i) {
                corners[i] = static_cast<std::uint8_t>(ring_corners[i]);
            }
            std::copy(ring_edges.begin(), ring_edges.end(), edges);
            continue;
        }
        const Index h = edge_corner[at(e)][1] / 3;
        const Index m = edge_corner[at(e)][1] % 3;
        write_interior_ring<6>(
            {4 * g + k, 4 * h + (m + 1) % 3, 4 * h + 3, 4 * h + m, 4 * g + (k + 1) % 3, 4 * g + 3}, {1, 2, m, 1, 2, k},
            {side(g, k, 1), half_at_vk, side(h, m + 1, 1), side(h, m, 1), half_at_vk1, side(g, k + 1, 1)}, faces,
            corners, edges);
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

// --- Doo–Sabin ------------------------------------------------------------------------------------
//
// Child vertex c is parent corner c (of face f at vertex v, f's corner i). The child faces are the
// F-face of each parent face, the E-face of each interior parent edge e ([f_b, f_a, g_a, g_b]: f =
// edge_faces(e)[0] runs e from its lower end a to b, g back) and the V-face of each parent vertex
// that has one (has_doo_sabin_vertex_face; the children at v in vertex_faces(v) order). In order of
// first appearance the child edges are: the F-face sides (side c runs from c to the next corner of
// its face: number c), then the two new sides of each E-face (the j-th E-face's at a: C + 2j, at b:
// C + 2j + 1; each shared with the V-face of its end when there is one), then the closing side of
// each V-face of a boundary vertex (from its last child to its first: C + 2J + its rank).
//
// Child vertex c has up to four faces, in counter-clockwise order (each next face shares the
// previous one's edge entering c): its F-face f, the E-face of e_in (f's edge entering v), the V-face
// of v, the E-face of e_out (f's edge leaving v). Each leaves c by: F: side c; E(e_in): side c_prev
// (f's previous corner); V: the side at v of E(e_in), or its closing side; E(e_out): the side at v of
// E(e_out). A missing face (a boundary edge, a vertex without V-face) makes c a boundary vertex.

bool has_doo_sabin_vertex_face(const Topology& parent, Index v, bool vertex_faces_on_boundary) {
    return !parent.is_boundary_vertex(v) || (vertex_faces_on_boundary && parent.vertex_faces(v).size() >= 3);
}

namespace {

/// Numbers of the E- and V-faces and closing sides, per parent edge and vertex (invalid_index where
/// there is none).
struct DooSabinNumbers {
    HugeTable<Index> edge_face;     ///< per parent edge: its E-face's rank j
    HugeTable<Index> vertex_face;   ///< per parent vertex: its V-face's rank
    HugeTable<Index> closing_side;  ///< per parent vertex: the rank of its V-face's closing side
    Index num_edge_faces = 0;
    Index num_vertex_faces = 0;
    Index num_closing_sides = 0;
};

DooSabinNumbers number_doo_sabin_faces(const Topology& parent, bool vertex_faces_on_boundary) {
    DooSabinNumbers n;
    assign_huge(n.edge_face, at(parent.num_edges()), invalid_index);
    for (Index e = 0; e < parent.num_edges(); ++e) {
        if (!parent.is_boundary_edge(e)) {
            n.edge_face[at(e)] = n.num_edge_faces++;
        }
    }
    assign_huge(n.vertex_face, at(parent.num_vertices()), invalid_index);
    assign_huge(n.closing_side, at(parent.num_vertices()), invalid_index);
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (has_doo_sabin_vertex_face(parent, v, vertex_faces_on_boundary)) {
            n.vertex_face[at(v)] = n.num_vertex_faces++;
            if (parent.is_boundary_vertex(v)) {
                n.closing_side[at(v)] = n.num_closing_sides++;
            }
        }
    }
    return n;
}

/// The corner after corner @p c of face @p f (global corner indices).
Index next_corner_of(const Topology& t, Index f, Index c) {
    const Index first = t.face_offset(f);
    return first + (c - first + 1) % t.face_degree(f);
}

/// The E-face of interior parent edge @p e, [f_b, f_a, g_a, g_b], from edge_corners(parent).
std::array<Index, 4> edge_face_of(const Topology& parent, const HugeTable<std::array<Index, 2>>& edge_corner, Index e) {
    const Index fa = edge_corner[at(e)][0];
    const Index gb = edge_corner[at(e)][1];
    return {next_corner_of(parent, parent.edge_faces(e)[0], fa), fa,
            next_corner_of(parent, parent.edge_faces(e)[1], gb), gb};
}

/// The child's face list from the numbers (the order above).
template <class Table>
void write_doo_sabin_faces(const Topology& parent, const DooSabinNumbers& n, Table& offsets, Table& vertices) {
    const Index F = parent.num_faces();
    const auto num_faces = at(F + n.num_edge_faces + n.num_vertex_faces);
    reserve_huge(offsets, num_faces + 1);
    offsets.assign(1, 0);
    std::size_t vertex_face_corners = 0;
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        vertex_face_corners += n.vertex_face[at(v)] != invalid_index ? parent.vertex_faces(v).size() : 0;
    }
    reserve_huge(vertices, at(parent.num_corners()) + 4 * at(n.num_edge_faces) + vertex_face_corners);
    vertices.clear();
    for (Index c = 0; c < parent.num_corners(); ++c) {
        vertices.push_back(c);
    }
    offsets.insert(offsets.end(), parent.face_offsets().begin() + 1, parent.face_offsets().end());
    const auto edge_corner = edge_corners(parent);
    for (Index e = 0; e < parent.num_edges(); ++e) {
        if (n.edge_face[at(e)] == invalid_index) {
            continue;
        }
        const auto face = edge_face_of(parent, edge_corner, e);
        vertices.insert(vertices.end(), face.begin(), face.end());
        offsets.push_back(static_cast<Index>(vertices.size()));
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (n.vertex_face[at(v)] == invalid_index) {
            continue;
        }
        const auto ring_faces = parent.vertex_faces(v);
        const auto ring_corners = parent.vertex_face_corners(v);
        for (std::size_t p = 0; p < ring_faces.size(); ++p) {
            vertices.push_back(parent.face_offset(ring_faces[p]) + ring_corners[p]);
        }
        offsets.push_back(static_cast<Index>(vertices.size()));
    }
}

}  // namespace

void doo_sabin_faces(const Topology& parent, bool vertex_faces_on_boundary, std::vector<Index>& face_offsets,
                     std::vector<Index>& face_vertices) {
    write_doo_sabin_faces(parent, number_doo_sabin_faces(parent, vertex_faces_on_boundary), face_offsets,
                          face_vertices);
}

Topology doo_sabin_topology(const Topology& parent, bool vertex_faces_on_boundary) {
    const DooSabinNumbers n = number_doo_sabin_faces(parent, vertex_faces_on_boundary);
    const Index C = parent.num_corners();
    Topology child;
    child.num_vertices_ = C;
    write_doo_sabin_faces(parent, n, child.face_offsets_, child.face_vertices_);

    // The side of E(e) at parent vertex v (a or b), and the parent's corner c at v's previous one.
    const auto side_at = [&](Index e, Index v) {
        return C + 2 * n.edge_face[at(e)] + (parent.edge_vertices(e)[1] == v ? 1 : 0);
    };
    const auto closing_side = [&](Index v) { return C + 2 * n.num_edge_faces + n.closing_side[at(v)]; };
    const auto previous_corner = [&](Index f, Index c) {
        return c == parent.face_offsets_[at(f)] ? parent.face_offsets_[at(f) + 1] - 1 : c - 1;
    };

    // Edges: their ends.
    const auto num_edges = at(C + 2 * n.num_edge_faces + n.num_closing_sides);
    assign_huge(child.edge_vertices_, 2 * num_edges);
    const auto set_edge = [&](Index e, Index a, Index b) {
        child.edge_vertices_[2 * at(e)] = std::min(a, b);
        child.edge_vertices_[2 * at(e) + 1] = std::max(a, b);
    };
    for (Index f = 0; f < parent.num_faces(); ++f) {
        for (Index c = parent.face_offsets_[at(f)]; c < parent.face_offsets_[at(f) + 1]; ++c) {
            set_edge(c, c, parent.next_corner(f, c));
        }
    }
    const auto edge_corner = edge_corners(parent);
    for (Index e = 0; e < parent.num_edges(); ++e) {
        if (n.edge_face[at(e)] == invalid_index) {
            continue;
        }
        const auto [fb, fa, ga, gb] = edge_face_of(parent, edge_corner, e);
        const auto ends = parent.edge_vertices(e);
        set_edge(side_at(e, ends[0]), fa, ga);
        set_edge(side_at(e, ends[1]), gb, fb);
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (n.closing_side[at(v)] != invalid_index) {
            const auto ring_faces = parent.vertex_faces(v);
            const auto ring_corners = parent.vertex_face_corners(v);
            set_edge(closing_side(v), parent.face_offset(ring_faces.back()) + ring_corners.back(),
                     parent.face_offset(ring_faces.front()) + ring_corners.front());
        }
    }

    // Face edges, side by side with the face list.
    assign_huge(child.face_edges_, child.face_vertices_.size());
    std::size_t slot = 0;
    for (Index c = 0; c < C; ++c, ++slot) {
        child.face_edges_[slot] = c;
    }
    for (Index e = 0; e < parent.num_edges(); ++e) {
        if (n.edge_face[at(e)] == invalid_index) {
            continue;
        }
        const auto ends = parent.edge_vertices(e);
        const auto face = edge_face_of(parent, edge_corner, e);  // [f_b, f_a, g_a, g_b]
        for (const Index side : {face[1], side_at(e, ends[0]), face[3], side_at(e, ends[1])}) {
            child.face_edges_[slot++] = side;
        }
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        if (n.vertex_face[at(v)] == invalid_index) {
            continue;
        }
        const auto ring_edges = parent.vertex_edges(v);
        const auto k = parent.vertex_faces(v).size();
        for (std::size_t p = 0; p < k; ++p) {
            // Faces p and p + 1 share vertex_edges(v)[p + 1] (p's edge entering v).
            const bool closing = p + 1 == k && parent.is_boundary_vertex(v);
            child.face_edges_[slot++] = closing ? closing_side(v) : side_at(ring_edges[(p + 1) % ring_edges.size()], v);
        }
    }
    child.fill_edge_faces(nullptr);

    // One-rings: per child vertex, the four candidate faces in counter-clockwise order, the corner of
    // c in each and the side each leaves c by; a boundary vertex's walk starts at the face after the
    // gap and closes with the side entering its last face.
    const Index F = parent.num_faces();
    HugeTable<Index> ring_position;  // per parent corner: its index in its vertex's one-ring
    assign_huge(ring_position, at(C));
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const auto ring_faces = parent.vertex_faces(v);
        const auto ring_corners = parent.vertex_face_corners(v);
        for (std::size_t p = 0; p < ring_faces.size(); ++p) {
            ring_position[at(parent.face_offset(ring_faces[p]) + ring_corners[p])] = static_cast<Index>(p);
        }
    }
    struct Candidate {
        Index face = invalid_index;  ///< invalid_index: missing
        Index corner = 0;
        Index leaving = 0;   ///< the side it leaves c by
        Index entering = 0;  ///< the side it enters c by
    };
    const auto candidates = [&](Index f, Index c) {
        const Index v = parent.face_vertices_[at(c)];
        const Index c_prev = previous_corner(f, c);
        const Index e_out = parent.face_edges_[at(c)];
        const Index e_in = parent.face_edges_[at(c_prev)];
        // Corner of c in E(e): [f_b, f_a, g_a, g_b]; f is edge_faces(e)[0] when it runs e lower -> higher.
        const auto edge_face_corner = [&](Index e) {
            const bool first = parent.corner_sign(f, e == e_out ? c : c_prev) > 0;
            const bool at_lower = parent.edge_vertices(e)[0] == v;
            return first ? (at_lower ? Index{1} : Index{0}) : (at_lower ? Index{2} : Index{3});
        };
        std::array<Candidate, 4> ring{};
        ring[0] = {f, c - parent.face_offset(f), c, c_prev};
        if (n.edge_face[at(e_in)] != invalid_index) {
            ring[1] = {F + n.edge_face[at(e_in)], edge_face_corner(e_in), c_prev, side_at(e_in, v)};
        }
        if (n.vertex_face[at(v)] != invalid_index) {
            const bool last = ring_position[at(c)] + 1 == static_cast<Index>(parent.vertex_faces(v).size());
            const bool first = ring_position[at(c)] == 0;
            const bool boundary = parent.is_boundary_vertex(v);
            ring[2] = {F + n.num_edge_faces + n.vertex_face[at(v)], ring_position[at(c)],
                       boundary && last ? closing_side(v) : side_at(e_in, v),
                       boundary && first ? closing_side(v) : side_at(e_out, v)};
        }
        if (n.edge_face[at(e_out)] != invalid_index) {
            ring[3] = {F + n.edge_face[at(e_out)], edge_face_corner(e_out), side_at(e_out, v), c};
        }
        return ring;
    };

    assign_huge(child.vertex_face_offsets_, at(C) + 1, 0);
    assign_huge(child.vertex_is_boundary_, at(C), 0);
    // Its F-face, the E-faces of its face's two edges at it when interior, its vertex's V-face.
    for (Index f = 0; f < F; ++f) {
        for (Index c = parent.face_offsets_[at(f)]; c < parent.face_offsets_[at(f) + 1]; ++c) {
            const Index v = parent.face_vertices_[at(c)];
            const Index present = 1 + (parent.is_boundary_edge(parent.face_edges_[at(previous_corner(f, c))]) ? 0 : 1) +
                                  (n.vertex_face[at(v)] != invalid_index ? 1 : 0) +
                                  (parent.is_boundary_edge(parent.face_edges_[at(c)]) ? 0 : 1);
            child.vertex_face_offsets_[at(c) + 1] = present;
            child.vertex_is_boundary_[at(c)] = present < 4 ? 1 : 0;
        }
    }
    child.allocate_one_rings();
    for (Index f = 0; f < F; ++f) {
        for (Index c = parent.face_offsets_[at(f)]; c < parent.face_offsets_[at(f) + 1]; ++c) {
            const auto ring = candidates(f, c);
            std::size_t start = 0;  // interior: the F-face, c's first corner in the face list
            if (child.vertex_is_boundary_[at(c)] != 0) {
                // the present face whose predecessor (the face sharing its leaving side) is missing
                while (ring[start].face == invalid_index || ring[(start + 3) % 4].face != invalid_index) {
                    ++start;
                }
            }
            Index face_slot = child.vertex_face_offsets_[at(c)];
            Index edge_slot = child.vertex_edge_offset(c);
            for (std::size_t i = 0; i < 4 && ring[(start + i) % 4].face != invalid_index; ++i) {
                const Candidate& x = ring[(start + i) % 4];
                child.vertex_faces_[at(face_slot)] = x.face;
                child.set_vertex_face_corner(at(face_slot++), x.corner);
                child.vertex_edges_[at(edge_slot++)] = x.leaving;
                if (face_slot == child.vertex_face_offsets_[at(c) + 1] && child.vertex_is_boundary_[at(c)] != 0) {
                    child.vertex_edges_[at(edge_slot++)] = x.entering;  // the closing boundary side
                }
            }
        }
    }

    child.sort_large_corners();
    child.build_boundary_loops();
    child.build_components();
    child.apply_sharpness({});
    check_child(child);
    return child;
}

}  // namespace limsurf::detail
