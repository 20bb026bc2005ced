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
//   - vertex_face_corners(v)[i] is the corner of vertex_faces(v)[i] at v (a
//     view, VertexFaceCorners: the Topology keeps it in a byte per corner).
//
// Construction validates everything (validate.h) and throws on any error, so
// every Topology is a consistently oriented 2-manifold with boundary, without
// isolated vertices. See docs/conventions.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <utility>
#include <vector>

#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/types.h"
#include "limsurf/mesh/sharpness.h"

namespace limsurf {
class Topology;

namespace detail {
/// An input iterator over a view that is read by index (operator[]) rather than stored.
template <class View, class Value>
class IndexIterator {
  public:
    using iterator_category = std::input_iterator_tag;
    using value_type = Value;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = Value;
    IndexIterator() = default;
    IndexIterator(const View* view, std::size_t i) : view_(view), i_(i) {}
    [[nodiscard]] Value operator*() const { return (*view_)[i_]; }
    IndexIterator& operator++() {
        ++i_;
        return *this;
    }
    IndexIterator operator++(int) {
        IndexIterator before = *this;
        ++i_;
        return before;
    }
    [[nodiscard]] bool operator==(const IndexIterator& other) const noexcept { return i_ == other.i_; }

  private:
    const View* view_ = nullptr;
    std::size_t i_ = 0;
};
}  // namespace detail

/// The corners at which a vertex sits in its faces, parallel to Topology::vertex_faces(v): a view
/// into its Topology's tables (valid as long as the spans of the other accessors), read like a span
/// of Index. The Topology keeps a corner in a byte; a corner of large_corner or more (faces of 255
/// corners and more are rare) sits in a short side table, sorted by slot.
class VertexFaceCorners {
  public:
    using iterator = detail::IndexIterator<VertexFaceCorners, Index>;
    using value_type = Index;
    /// The byte that sends a lookup to the side table.
    static constexpr std::uint8_t large_corner = 255;
    [[nodiscard]] std::size_t size() const noexcept { return size_; }
    [[nodiscard]] bool empty() const noexcept { return size_ == 0; }
    /// @pre i < size()
    [[nodiscard]] Index operator[](std::size_t i) const {
        const std::uint8_t c = bytes_[i];
        return c != large_corner ? Index{c} : large(first_slot_ + i);
    }
    [[nodiscard]] Index front() const { return (*this)[0]; }
    [[nodiscard]] Index back() const { return (*this)[size_ - 1]; }
    [[nodiscard]] iterator begin() const { return {this, 0}; }
    [[nodiscard]] iterator end() const { return {this, size_}; }

  private:
    friend class Topology;
    VertexFaceCorners(const std::uint8_t* bytes, std::size_t first_slot, std::size_t size,
                      std::span<const std::pair<Index, Index>> large_corners)
        : bytes_(bytes), first_slot_(first_slot), size_(size), large_corners_(large_corners) {}
    /// The side table's corner at one-ring slot @p slot.
    [[nodiscard]] Index large(std::size_t slot) const;
    const std::uint8_t* bytes_;  // at first_slot_
    std::size_t first_slot_;
    std::size_t size_;
    std::span<const std::pair<Index, Index>> large_corners_;  // (slot, corner), by slot
};

/// The signs of a face's edges, +1 where corner k -> k+1 runs lower -> higher vertex index, else
/// -1 (Topology::face_edge_signs): read from the face's corners, like a span of std::int8_t.
class FaceEdgeSigns {
  public:
    using iterator = detail::IndexIterator<FaceEdgeSigns, std::int8_t>;
    using value_type = std::int8_t;
    /// The signs of the face with corners @p corners (counter-clockwise).
    explicit FaceEdgeSigns(std::span<const Index> corners) : corners_(corners) {}
    [[nodiscard]] std::size_t size() const noexcept { return corners_.size(); }
    [[nodiscard]] bool empty() const noexcept { return corners_.empty(); }
    /// @pre k < size()
    [[nodiscard]] std::int8_t operator[](std::size_t k) const {
        const std::size_t next = k + 1 == corners_.size() ? 0 : k + 1;
        return corners_[k] < corners_[next] ? std::int8_t{1} : std::int8_t{-1};
    }
    [[nodiscard]] iterator begin() const { return {this, 0}; }
    [[nodiscard]] iterator end() const { return {this, corners_.size()}; }

  private:
    std::span<const Index> corners_;
};

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
    [[nodiscard]] FaceEdgeSigns face_edge_signs(Index f) const { return FaceEdgeSigns(face_vertices(f)); }
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
    [[nodiscard]] std::span<const Index> edge_faces(Index e) const {
        return std::span<const Index>(edge_faces_).subspan(2 * at(e), at(edge_face_count(e)));
    }
    [[nodiscard]] bool is_boundary_edge(Index e) const { return edge_face_count(e) == 1; }
    /// The edge joining a and b, or invalid_index. O(valence).
    [[nodiscard]] Index find_edge(Index a, Index b) const;

    // --- vertices -----------------------------------------------------------
    /// Number of incident edges.
    [[nodiscard]] Index valence(Index v) const { return static_cast<Index>(vertex_edges(v).size()); }
    /// Incident faces, counter-clockwise (see the header comment).
    [[nodiscard]] std::span<const Index> vertex_faces(Index v) const;
    /// Corner of vertex_faces(v)[i] at which v sits.
    [[nodiscard]] VertexFaceCorners vertex_face_corners(Index v) const {
        const Index first = vertex_face_offsets_[at(v)];
        return {vertex_face_corners_.data() + at(first), at(first), at(vertex_face_offsets_[at(v) + 1] - first),
                large_corners_};
    }
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
    [[nodiscard]] Index face_component(Index f) const { return face_component_.empty() ? 0 : face_component_[at(f)]; }
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
    /// edge_faces_ from face_edges_ and the corners' signs (edge_vertices_ sized); the corner at which
    /// each face enters the edge into @p edge_face_corners (two slots per edge) when it is not null.
    void fill_edge_faces(detail::HugeTable<Index>* edge_face_corners);
    /// 1 on the boundary, else 2 (a Topology's edges are manifold).
    [[nodiscard]] Index edge_face_count(Index e) const { return edge_faces_[2 * at(e) + 1] == invalid_index ? 1 : 2; }
    /// Writes slot @p slot of vertex_face_corners_: a byte, or VertexFaceCorners::large_corner and an
    /// entry of large_corners_ (a byte per corner saves 3 bytes per corner against an Index;
    /// sort_large_corners() once all are written).
    void set_vertex_face_corner(std::size_t slot, Index corner) {
        constexpr std::uint8_t large_corner = VertexFaceCorners::large_corner;
        if (corner < large_corner) {
            vertex_face_corners_[slot] = static_cast<std::uint8_t>(corner);
            return;
        }
        vertex_face_corners_[slot] = large_corner;
        large_corners_.emplace_back(static_cast<Index>(slot), corner);
    }
    void sort_large_corners();
    /// Where vertex v's one-ring edges start in vertex_edges_ (v = #V: their end). Without boundary
    /// every vertex has as many edges as faces, and the faces' offsets serve.
    [[nodiscard]] Index vertex_edge_offset(Index v) const {
        return vertex_edge_offsets_.empty() ? vertex_face_offsets_[at(v)] : vertex_edge_offsets_[at(v)];
    }
    /// vertex_is_boundary_ and the one-ring offsets from each vertex's number of faces (in
    /// vertex_face_offsets_[v + 1]); sizes the one-ring tables.
    void allocate_one_rings();
    /// Walks around each vertex counter-clockwise. Returns false when a walk ends early: a vertex
    /// whose faces form several fans.
    [[nodiscard]] bool build_one_rings(const detail::HugeTable<Index>& edge_face_corners);
    void build_boundary_loops();
    void build_components();
    void apply_sharpness(const SharpnessTags& sharpness);
    /// face_edge_signs(f) at global corner @p c of face @p f.
    [[nodiscard]] std::int8_t corner_sign(Index f, Index c) const {
        return face_vertices_[at(c)] < face_vertices_[at(next_corner(f, c))] ? std::int8_t{1} : std::int8_t{-1};
    }
    /// The corner after corner @p c (a global corner index) of face @p f.
    [[nodiscard]] Index next_corner(Index f, Index c) const {
        return c + 1 == face_offsets_[at(f) + 1] ? face_offsets_[at(f)] : c + 1;
    }

    Index num_vertices_ = 0;
    detail::HugeTable<Index> face_offsets_{0};
    detail::HugeTable<Index> face_vertices_;
    detail::HugeTable<Index> face_edges_;  // (the signs follow from face_vertices_: corner_sign)

    detail::HugeTable<Index> edge_vertices_;  // 2 per edge, lower first
    // 2 per edge: the face running it lower -> higher (or its only face) first; invalid_index second
    // on the boundary. No offsets: a Topology's edges have one or two faces.
    detail::HugeTable<Index> edge_faces_;

    detail::HugeTable<Index> vertex_face_offsets_;  // #V+1
    detail::HugeTable<Index> vertex_faces_;
    detail::HugeTable<std::uint8_t> vertex_face_corners_;  // large_corner: see large_corners_
    std::vector<std::pair<Index, Index>> large_corners_;   // (slot, corner), by slot
    detail::HugeTable<Index> vertex_edge_offsets_;         // #V+1; empty without boundary (vertex_edge_offset())
    detail::HugeTable<Index> vertex_edges_;
    detail::HugeTable<std::uint8_t> vertex_is_boundary_;

    detail::HugeTable<Index> boundary_loop_offsets_{0};
    detail::HugeTable<Index> boundary_loop_vertices_;
    detail::HugeTable<Index> face_component_;  // #F; empty when there is one component
    Index num_components_ = 0;
    Index genus_ = 0;

    detail::HugeTable<double> edge_sharpness_;    // empty when all smooth
    detail::HugeTable<double> vertex_sharpness_;  // empty when all smooth
    detail::HugeTable<std::uint8_t> holes_;       // empty when no holes
};

}  // namespace limsurf
