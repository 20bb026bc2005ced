// Topology: the immutable, validated connectivity of a polygon mesh.
//
// Representation (compressed rows, like OpenSubdiv's Vtr::Level):
//   - faces: any degree >= 3, corners counter-clockwise seen from outside;
//   - edges: stored once, oriented from the lower to the higher vertex index;
//     face_edges(f)[k] is the edge from corner k to corner k+1 of f, and
//     face_edge_signs(f)[k] is +1 when that traversal follows the edge's
//     orientation (lower -> higher), -1 otherwise (the d1 convention);
//   - one-rings: for vertex v, vertex_edges(v) and vertex_faces(v) are ordered
//     counter-clockwise about the outward normal. Face vertex_faces(v)[i] lies
//     between vertex_edges(v)[i] (its edge leaving v) and vertex_edges(v)[i+1]
//     (its edge entering v; index taken modulo the valence for interior
//     vertices). A boundary vertex has one more edge than faces: its first
//     edge and its last edge are boundary edges.
//   - vertex_face_corners(v)[i] is the corner of vertex_faces(v)[i] at v.
//
// Construction validates everything (validate.h) and throws on any error, so
// every Topology is a consistently oriented 2-manifold with boundary, without
// isolated vertices. See docs/conventions.md.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/types.h"
#include "limsurf/mesh/sharpness.h"

namespace limsurf {
class Topology;
namespace detail {
struct HalfEdge;
/// Refinement output only (the locally refined patches of limit/local_patch.cpp; every scheme's
/// step builds its child directly, below): a Topology built without validating faces that a
/// refinement made; validated anyway in Debug builds.
Topology refined_topology(Index num_vertices, std::span<const Index> face_offsets, std::span<const Index> face_vertices,
                          const SharpnessTags& sharpness);
/// Refinement output only: the child of the quad split (Catmull–Clark, bilinear; vertex and face
/// order of refine/level.h) built directly from @p parent's tables, without sorting half-edges or
/// walking one-rings. Every table equals that of Topology(child faces, @p child_sharpness)
/// (tests/refine/face_split/child_topology_test.cpp). @p child_sharpness names child vertices and edges.
Topology quad_split_topology(const Topology& parent, const SharpnessTags& child_sharpness);
/// As quad_split_topology, for the triangle split (Loop, linear, C2g0). @pre all faces are triangles
Topology tri_split_topology(const Topology& parent, const SharpnessTags& child_sharpness);
/// Refinement output only: whether Doo–Sabin gives parent vertex @p v a face of its own (every
/// interior vertex; a boundary vertex in 3 or more faces when @p vertex_faces_on_boundary).
bool has_doo_sabin_vertex_face(const Topology& parent, Index v, bool vertex_faces_on_boundary);
/// Refinement output only: the face list of Doo–Sabin's child (refine/doo_sabin.cpp gives the order:
/// F-faces, E-faces of interior edges, V-faces; child vertex c is parent corner c).
void doo_sabin_faces(const Topology& parent, bool vertex_faces_on_boundary, std::vector<Index>& face_offsets,
                     std::vector<Index>& face_vertices);
/// Refinement output only: Doo–Sabin's child built directly from @p parent's tables, as
/// quad_split_topology is; every table equals that of Topology(doo_sabin_faces(…)) (no sharpness).
Topology doo_sabin_topology(const Topology& parent, bool vertex_faces_on_boundary);
}  // namespace detail

class Topology {
  public:
    /// An empty topology (no vertices, no faces).
    Topology() = default;

    /// @brief Builds and validates the connectivity of a polygon mesh.
    /// @param[in] num_vertices  #V; every vertex must be used by a face
    /// @param[in] face_offsets  #F+1 offsets into face_vertices, starting at 0
    /// @param[in] face_vertices concatenated 0-based corners, counter-clockwise
    /// @param[in] sharpness     creases (on existing edges), corners, holes
    /// @throws InputError on malformed offsets, indices out of range, bad tags
    /// @throws TopologyError on non-manifold or inconsistently oriented input,
    ///   or isolated vertices; the message lists the first problems.
    Topology(Index num_vertices, std::span<const Index> face_offsets, std::span<const Index> face_vertices,
             const SharpnessTags& sharpness = {});

    /// Convenience for small meshes: one vector of corners per face.
    /// @throws as the main constructor
    [[nodiscard]] static Topology from_polygons(Index num_vertices, const std::vector<std::vector<Index>>& faces,
                                                const SharpnessTags& sharpness = {});

    // --- counts -------------------------------------------------------------
    [[nodiscard]] Index num_vertices() const noexcept { return num_vertices_; }
    [[nodiscard]] Index num_edges() const noexcept { return static_cast<Index>(edge_vertices_.size() / 2); }
    [[nodiscard]] Index num_faces() const noexcept { return static_cast<Index>(face_offsets_.size()) - 1; }
    /// Sum of face degrees (number of face corners, "face-vertices").
    [[nodiscard]] Index num_corners() const noexcept { return static_cast<Index>(face_vertices_.size()); }

    // --- faces --------------------------------------------------------------
    [[nodiscard]] Index face_degree(Index f) const { return face_offsets_[at(f) + 1] - face_offsets_[at(f)]; }
    /// Corners of face f, counter-clockwise.
    [[nodiscard]] std::span<const Index> face_vertices(Index f) const { return face_span(face_vertices_, f); }
    /// face_edges(f)[k] joins corners k and k+1 (mod degree).
    [[nodiscard]] std::span<const Index> face_edges(Index f) const { return face_span(face_edges_, f); }
    /// +1 when corner k -> k+1 runs lower -> higher vertex index, else -1.
    [[nodiscard]] std::span<const std::int8_t> face_edge_signs(Index f) const { return face_span(face_edge_signs_, f); }
    /// Offset of face f's first corner in the concatenated corner arrays.
    [[nodiscard]] Index face_offset(Index f) const { return face_offsets_[at(f)]; }
    /// #F+1 offsets (CSR row pointer of the face->vertex table).
    [[nodiscard]] std::span<const Index> face_offsets() const noexcept { return face_offsets_; }
    /// All corners, concatenated (CSR column indices of the face->vertex table).
    [[nodiscard]] std::span<const Index> all_face_vertices() const noexcept { return face_vertices_; }
    /// True when every face has degree @p degree.
    [[nodiscard]] bool all_faces_have_degree(Index degree) const noexcept;
    [[nodiscard]] bool is_hole(Index f) const { return !holes_.empty() && holes_[at(f)] != 0; }

    // --- edges --------------------------------------------------------------
    /// {lower, higher} vertex index.
    [[nodiscard]] std::array<Index, 2> edge_vertices(Index e) const {
        return {edge_vertices_[2 * at(e)], edge_vertices_[2 * at(e) + 1]};
    }
    /// The one or two faces incident to edge e (first: the face that traverses
    /// e lower -> higher when there is one).
    [[nodiscard]] std::span<const Index> edge_faces(Index e) const;
    [[nodiscard]] bool is_boundary_edge(Index e) const { return edge_faces(e).size() == 1; }
    /// The edge joining a and b, or invalid_index. O(valence).
    [[nodiscard]] Index find_edge(Index a, Index b) const;

    // --- vertices -----------------------------------------------------------
    /// Number of incident edges.
    [[nodiscard]] Index valence(Index v) const { return static_cast<Index>(vertex_edges(v).size()); }
    /// Incident faces, counter-clockwise (see the header comment).
    [[nodiscard]] std::span<const Index> vertex_faces(Index v) const;
    /// Corner of vertex_faces(v)[i] at which v sits.
    [[nodiscard]] std::span<const Index> vertex_face_corners(Index v) const;
    /// Incident edges, counter-clockwise, interleaved with vertex_faces(v).
    [[nodiscard]] std::span<const Index> vertex_edges(Index v) const;
    /// The vertex at the other end of edge e from v. @pre v is an end of e
    [[nodiscard]] Index other_vertex(Index e, Index v) const {
        const auto ends = edge_vertices(e);
        return ends[0] == v ? ends[1] : ends[0];
    }
    [[nodiscard]] bool is_boundary_vertex(Index v) const { return vertex_is_boundary_[at(v)] != 0; }

    // --- global -------------------------------------------------------------
    [[nodiscard]] bool is_closed() const noexcept { return boundary_loop_offsets_.size() == 1; }
    [[nodiscard]] bool has_boundary() const noexcept { return !is_closed(); }
    /// Number of boundary loops.
    [[nodiscard]] Index num_boundary_loops() const noexcept {
        return static_cast<Index>(boundary_loop_offsets_.size()) - 1;
    }
    /// Vertices of boundary loop i, in the order the boundary edges run
    /// (the interior lies to the left of each edge).
    [[nodiscard]] std::span<const Index> boundary_loop(Index i) const;
    /// V - E + F.
    [[nodiscard]] Index euler_characteristic() const noexcept { return num_vertices() - num_edges() + num_faces(); }
    [[nodiscard]] Index num_components() const noexcept { return num_components_; }
    /// Component of face f, in 0..num_components()-1, numbered by first face.
    [[nodiscard]] Index face_component(Index f) const { return face_component_[at(f)]; }
    /// Component of vertex v.
    [[nodiscard]] Index vertex_component(Index v) const;
    /// Genus of a connected orientable surface: (2 - chi - b) / 2; for several
    /// components, the sum over components.
    [[nodiscard]] Index genus() const noexcept { return genus_; }

    // --- sharpness ----------------------------------------------------------
    /// 0 when smooth; see sharpness.h for the scale.
    [[nodiscard]] double edge_sharpness(Index e) const {
        return edge_sharpness_.empty() ? 0.0 : edge_sharpness_[at(e)];
    }
    [[nodiscard]] double vertex_sharpness(Index v) const {
        return vertex_sharpness_.empty() ? 0.0 : vertex_sharpness_[at(v)];
    }
    /// True when any edge or vertex is sharp or any face is a hole.
    [[nodiscard]] bool has_sharpness() const noexcept {
        return !edge_sharpness_.empty() || !vertex_sharpness_.empty() || !holes_.empty();
    }
    /// The tags that rebuild this topology's sharpness (for writers).
    [[nodiscard]] SharpnessTags sharpness_tags() const;

  private:
    friend Topology detail::refined_topology(Index, std::span<const Index>, std::span<const Index>,
                                             const SharpnessTags&);
    friend Topology detail::quad_split_topology(const Topology&, const SharpnessTags&);
    friend Topology detail::tri_split_topology(const Topology&, const SharpnessTags&);
    friend Topology detail::doo_sabin_topology(const Topology&, bool);
    struct Trusted {};
    /// Builds the tables without validating: the faces come from a refinement step.
    Topology(Trusted, Index num_vertices, std::span<const Index> face_offsets, std::span<const Index> face_vertices,
             const SharpnessTags& sharpness);
    /// face_offsets_ and face_vertices_ from the caller's face list (in memory advised for huge pages).
    void copy_face_list(std::span<const Index> face_offsets, std::span<const Index> face_vertices);
    /// The tables from validated half-edges. Returns false, with the tables unusable, when some vertex's
    /// faces form several fans (a bow-tie: the one-ring walk ends before it has seen every face).
    [[nodiscard]] bool build(std::span<const detail::HalfEdge> half_edges, const SharpnessTags& sharpness);

    static std::size_t at(Index i) { return static_cast<std::size_t>(i); }
    template <class T>
    std::span<const T> face_span(const detail::HugeTable<T>& table, Index f) const {
        const auto begin = at(face_offsets_[at(f)]);
        const auto end = at(face_offsets_[at(f) + 1]);
        return std::span<const T>(table).subspan(begin, end - begin);
    }
    /// Returns, parallel to edge_faces_, the corner at which each of those faces enters the edge.
    detail::HugeTable<Index> build_edges(std::span<const detail::HalfEdge> half_edges);
    /// From face_edges_, face_edge_signs_ and the face count of each edge in edge_face_offsets_[e + 1]:
    /// the offsets and edge_faces_; the corner at which each face enters the edge into
    /// @p edge_face_corners when it is not null.
    void fill_edge_faces(detail::HugeTable<Index>* edge_face_corners);
    /// vertex_is_boundary_ and the one-ring offsets from each vertex's number of faces (in
    /// vertex_face_offsets_[v + 1]); sizes the one-ring tables.
    void allocate_one_rings();
    /// Walks around each vertex counter-clockwise. Returns false when a walk ends early: a vertex
    /// whose faces form several fans.
    [[nodiscard]] bool build_one_rings(const detail::HugeTable<Index>& edge_face_corners);
    void build_boundary_loops();
    void build_components();
    void apply_sharpness(const SharpnessTags& sharpness);
    /// The corner after corner @p c (a global corner index) of face @p f.
    [[nodiscard]] Index next_corner(Index f, Index c) const {
        return c + 1 == face_offsets_[at(f) + 1] ? face_offsets_[at(f)] : c + 1;
    }

    Index num_vertices_ = 0;
    detail::HugeTable<Index> face_offsets_{0};
    detail::HugeTable<Index> face_vertices_;
    detail::HugeTable<Index> face_edges_;
    detail::HugeTable<std::int8_t> face_edge_signs_;

    detail::HugeTable<Index> edge_vertices_;      // 2 per edge, lower first
    detail::HugeTable<Index> edge_face_offsets_;  // #E+1
    detail::HugeTable<Index> edge_faces_;

    detail::HugeTable<Index> vertex_face_offsets_;  // #V+1
    detail::HugeTable<Index> vertex_faces_;
    detail::HugeTable<Index> vertex_face_corners_;
    detail::HugeTable<Index> vertex_edge_offsets_;  // #V+1
    detail::HugeTable<Index> vertex_edges_;
    detail::HugeTable<std::uint8_t> vertex_is_boundary_;

    detail::HugeTable<Index> boundary_loop_offsets_{0};
    detail::HugeTable<Index> boundary_loop_vertices_;
    detail::HugeTable<Index> face_component_;
    Index num_components_ = 0;
    Index genus_ = 0;

    detail::HugeTable<double> edge_sharpness_;    // empty when all smooth
    detail::HugeTable<double> vertex_sharpness_;  // empty when all smooth
    detail::HugeTable<std::uint8_t> holes_;       // empty when no holes
};

}  // namespace limsurf
