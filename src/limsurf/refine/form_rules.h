// Private machinery of form subdivision (form_subdivision.h): directed coarse edges, the fan of
// faces around a vertex in the labels of docs/sec.md ("Form subdivision"), and the assembler that
// turns rules written on directed coarse edges into rows of S1 and S2.
//
// A 1-form rule is written for a fine edge in a stated local direction, with weights on directed
// coarse edges p→q. A coarse edge is stored lower → higher, so p→q carries the sign of that walk;
// the fine edge likewise carries the sign of its local direction against its stored one.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// A coarse edge walked in a given direction: sign +1 when the walk runs lower → higher.
struct DirectedEdge {
    Index edge = invalid_index;
    double sign = 1.0;
    [[nodiscard]] DirectedEdge reversed() const { return {edge, -sign}; }
};

/// Edge @p position (mod degree) of face @p f, walked counter-clockwise.
[[nodiscard]] inline DirectedEdge face_edge(const Topology& t, Index f, Index position) {
    const Index n = t.face_degree(f);
    const auto k = static_cast<std::size_t>(((position % n) + n) % n);
    return {t.face_edges(f)[k], static_cast<double>(t.face_edge_signs(f)[k])};
}

/// The position in face @p g of edge @p e. @pre e is an edge of g
[[nodiscard]] Index edge_position(const Topology& t, Index g, Index e);

/// The face across edge e from face f, or invalid_index on the boundary.
[[nodiscard]] Index face_across(const Topology& t, Index f, Index e);

/// The faces around vertex v in the labels of docs/sec.md: fan face f_i lies between spokes
/// x_i = v→u_i and x_{i+1}; an interior vertex has k spokes (indices mod k), a boundary vertex
/// k + 1 with x_0 and x_k on the boundary.
class VertexFan {
  public:
    VertexFan(const Topology& t, Index v);
    [[nodiscard]] Index num_faces() const noexcept { return k_; }
    [[nodiscard]] bool is_boundary() const noexcept { return boundary_; }
    /// Fan index wrapped mod k (interior vertices).
    [[nodiscard]] Index wrap(Index i) const noexcept { return ((i % k_) + k_) % k_; }
    [[nodiscard]] Index face(Index i) const { return faces_[static_cast<std::size_t>(i)]; }
    /// The corner of face(i) at which v sits.
    [[nodiscard]] Index corner(Index i) const { return corners_[static_cast<std::size_t>(i)]; }
    /// Edge @p offset of fan face i counted from v's corner (0: x_i, last: x_{i+1} reversed).
    [[nodiscard]] DirectedEdge edge_of_face(Index i, Index offset) const {
        return face_edge(t_, face(i), corner(i) + offset);
    }
    /// Spoke x_i = v→u_i; i in [0, k) for interior vertices (wrapped), [0, k] on the boundary.
    [[nodiscard]] DirectedEdge spoke(Index i) const;

  private:
    const Topology& t_;
    std::span<const Index> faces_;
    VertexFaceCorners corners_;
    Index k_ = 0;
    bool boundary_ = false;
};

/// One row of S1 or S2 under construction: weights on directed coarse edges (or on faces).
class FormRow {
  public:
    void clear() { entries_.clear(); }
    void add(DirectedEdge e, double w) { entries_.push_back({e.edge, e.sign * w}); }
    /// Adds w to each edge of face f walked counter-clockwise (the circulation Ω_f).
    void add_circulation(const Topology& t, Index f, double w);
    /// For S2 rows: weight on coarse face f.
    void add_face(Index f, double w) { entries_.push_back({f, w}); }
    struct Entry {
        Index col;
        double weight;
    };
    [[nodiscard]] const std::vector<Entry>& entries() const noexcept { return entries_; }

  private:
    std::vector<Entry> entries_;
};

/// The rows of one sparse matrix, set once each in any order: each row is appended where it comes
/// and finish() copies the rows, in order, into the row-major arrays. (Triplets through
/// setFromTriplets cost a column-major copy and a second pass: most of the form operators' time
/// at 300 k faces.)
class RowStore {
  public:
    RowStore(Index rows, Index cols, std::size_t entries_hint);
    /// Sets row @p r to @p entries: sorted by column, each column once, no zeros.
    void set_row(Index r, std::span<const FormRow::Entry> entries);
    /// @throws std::logic_error when a row was set twice or never (a bug in the rules), naming the
    ///   row as a child @p what
    [[nodiscard]] SparseMatrix finish(const char* what);

  private:
    Index rows_, cols_;
    std::vector<FormRow::Entry> entries_;
    std::vector<std::size_t> first_;       ///< per row: where its entries start in entries_
    std::vector<Index> count_;             ///< per row: how many
    std::vector<std::uint8_t> times_set_;  ///< per row: 1 when set exactly once
};

/// Collects the rows of S1 and S2 (in any order) and builds the matrices.
class FormAssembler {
  public:
    FormAssembler(const Topology& parent, const Topology& child);
    /// The row of fine edge @p fine.edge; fine.sign: +1 when the rule's local direction is the
    /// edge's stored one. Each fine edge must be set exactly once.
    void set_edge_row(DirectedEdge fine, const FormRow& row);
    void set_face_row(Index fine_face, const FormRow& row);
    /// @throws std::logic_error when a fine edge or face got no row or two (a bug in the rules)
    [[nodiscard]] SparseMatrix finish_s1();
    [[nodiscard]] SparseMatrix finish_s2();

  private:
    RowStore s1_, s2_;
    std::vector<FormRow::Entry> merged_;  ///< the row being merged (reused)
    std::vector<FormRow::Entry> sums_;    ///< its sums per column (reused)
};

/// The even child of spoke i of @p fan (the fine edge v → edge point), in that direction, read
/// off the child face of the fan face at v (child face 4f + corner for both splits).
[[nodiscard]] DirectedEdge even_child(const Topology& child, const VertexFan& fan, Index i);

/// The two children v → edge point of the boundary edges at a boundary vertex (spokes 0 and k),
/// the same for Loop and Catmull–Clark: the cubic B-spline curve's 1-form rule
/// 3/8 (v→w) − 1/8 (v→w'), or ½ (v→w) at a one-face corner kept fixed (EdgeAndCorner).
void boundary_edge_children(const Topology& child, const VertexFan& fan, BoundaryInterpolation boundary, FormRow& row,
                            FormAssembler& out);

}  // namespace limsurf::detail
