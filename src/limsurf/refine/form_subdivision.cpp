// Form subdivision: shared machinery, checks and dispatch (the rules are in loop_forms.cpp and
// catmull_clark_forms.cpp).
#include "limsurf/refine/form_subdivision.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/detail/huge_pages.h"
#include "limsurf/refine/form_rules.h"
#include "limsurf/refine/refine.h"

namespace limsurf {
namespace detail {

FormSubdivision loop_form_subdivision(const Topology& parent, const Topology& child, const SchemeOptions& options);
FormSubdivision catmull_clark_form_subdivision(const Topology& parent, const Topology& child,
                                               const SchemeOptions& options);

Index edge_position(const Topology& t, Index g, Index e) {
    const auto edges = t.face_edges(g);
    for (std::size_t k = 0; k < edges.size(); ++k) {
        if (edges[k] == e) {
            return static_cast<Index>(k);
        }
    }
    throw InputError(concat("edge ", e, " is not an edge of face ", g));
}

Index face_across(const Topology& t, Index f, Index e) {
    for (const Index g : t.edge_faces(e)) {
        if (g != f) {
            return g;
        }
    }
    return invalid_index;
}

VertexFan::VertexFan(const Topology& t, Index v)
    : t_(t), faces_(t.vertex_faces(v)), corners_(t.vertex_face_corners(v)), k_(static_cast<Index>(faces_.size())),
      boundary_(t.is_boundary_vertex(v)) {}

DirectedEdge VertexFan::spoke(Index i) const {
    if (boundary_ && i == k_) {
        // x_k is the edge entering v in the last fan face, walked the other way.
        return edge_of_face(k_ - 1, t_.face_degree(face(k_ - 1)) - 1).reversed();
    }
    return edge_of_face(boundary_ ? i : wrap(i), 0);
}

void FormRow::add_circulation(const Topology& t, Index f, double w) {
    const Index n = t.face_degree(f);
    for (Index k = 0; k < n; ++k) {
        add(face_edge(t, f, k), w);
    }
}

RowStore::RowStore(Index rows, Index cols, std::size_t entries_hint)
    : rows_(rows), cols_(cols), times_set_(static_cast<std::size_t>(rows), 0) {
    // Fresh memory faults in page by page (about 10 µs per 4 KiB page on the project's VM): the
    // large tables are advised for huge pages.
    detail::assign_huge(first_, static_cast<std::size_t>(rows));
    detail::assign_huge(count_, static_cast<std::size_t>(rows));
    detail::reserve_huge(entries_, entries_hint);
}

void RowStore::set_row(Index r, std::span<const FormRow::Entry> entries) {
    const auto row = static_cast<std::size_t>(r);
    ++times_set_[row];
    first_[row] = entries_.size();
    count_[row] = static_cast<Index>(entries.size());
    entries_.insert(entries_.end(), entries.begin(), entries.end());
}

SparseMatrix RowStore::finish(const char* what) {
    // Every fine element must get exactly one rule: a gap or a double would be a bug in the rules'
    // bookkeeping, so it is checked in every build (cheap next to the assembly).
    for (std::size_t i = 0; i < times_set_.size(); ++i) {
        if (times_set_[i] != 1) {
            throw std::logic_error(
                concat("form subdivision set ", static_cast<int>(times_set_[i]), " rows for child ", what, " ", i));
        }
    }
    SparseMatrix m(rows_, cols_);
    m.resizeNonZeros(static_cast<Eigen::Index>(entries_.size()));
    advise_huge_pages(m.valuePtr(), sizeof(double) * entries_.size());
    advise_huge_pages(m.innerIndexPtr(), sizeof(Index) * entries_.size());
    Index written = 0;
    for (std::size_t r = 0; r < static_cast<std::size_t>(rows_); ++r) {
        m.outerIndexPtr()[r] = written;
        for (std::size_t k = first_[r]; k < first_[r] + static_cast<std::size_t>(count_[r]); ++k) {
            m.innerIndexPtr()[written] = entries_[k].col;
            m.valuePtr()[written] = entries_[k].weight;
            ++written;
        }
    }
    m.outerIndexPtr()[rows_] = written;
    entries_ = {};
    return m;
}

namespace {

/// Sums the weights of each column of @p row (sorted by column), in the order they stand, times
/// @p scale into @p out, leaving out sums of zero: what setFromTriplets and prune(0) made of them.
void sum_columns(const std::vector<FormRow::Entry>& row, double scale, std::vector<FormRow::Entry>& out) {
    out.clear();
    for (std::size_t i = 0; i < row.size();) {
        double sum = 0.0;
        const Index col = row[i].col;
        for (; i < row.size() && row[i].col == col; ++i) {
            sum += row[i].weight;
        }
        if (sum != 0.0) {
            out.push_back({col, scale * sum});
        }
    }
}

}  // namespace

FormAssembler::FormAssembler(const Topology& parent, const Topology& child)
    : s1_(child.num_edges(), parent.num_edges(), static_cast<std::size_t>(child.num_edges()) * 16),
      s2_(child.num_faces(), parent.num_faces(), static_cast<std::size_t>(child.num_faces()) * 6) {}

void FormAssembler::set_edge_row(DirectedEdge fine, const FormRow& row) {
    // A rule names the same coarse edge several times (spokes, diagonals, circulations): merged here.
    merged_.assign(row.entries().begin(), row.entries().end());
    std::sort(merged_.begin(), merged_.end(), [](const auto& a, const auto& b) { return a.col < b.col; });
    sum_columns(merged_, fine.sign, sums_);
    s1_.set_row(fine.edge, sums_);
}

void FormAssembler::set_face_row(Index fine_face, const FormRow& row) {
    // Stable (insertion sort; rows are short), so that repeated faces sum in the order they come.
    merged_.assign(row.entries().begin(), row.entries().end());
    for (std::size_t i = 1; i < merged_.size(); ++i) {
        for (std::size_t j = i; j > 0 && merged_[j - 1].col > merged_[j].col; --j) {
            std::swap(merged_[j - 1], merged_[j]);
        }
    }
    sum_columns(merged_, 1.0, sums_);
    s2_.set_row(fine_face, sums_);
}

SparseMatrix FormAssembler::finish_s1() {
    return s1_.finish("edge");
}

SparseMatrix FormAssembler::finish_s2() {
    return s2_.finish("face");
}

DirectedEdge even_child(const Topology& child, const VertexFan& fan, Index i) {
    if (fan.is_boundary() && i == fan.num_faces()) {
        const Index last = fan.num_faces() - 1;
        const Index child_face = 4 * fan.face(last) + fan.corner(last);
        return face_edge(child, child_face, child.face_degree(child_face) - 1).reversed();
    }
    const Index f = fan.is_boundary() ? i : fan.wrap(i);
    return face_edge(child, 4 * fan.face(f) + fan.corner(f), 0);
}

void boundary_edge_children(const Topology& child, const VertexFan& fan, BoundaryInterpolation boundary, FormRow& row,
                            FormAssembler& out) {
    const Index k = fan.num_faces();
    const bool corner = boundary == BoundaryInterpolation::EdgeAndCorner && k == 1;
    for (const Index j : {Index{0}, k}) {
        row.clear();
        if (corner) {
            row.add(fan.spoke(j), 0.5);
        } else {
            row.add(fan.spoke(j), 0.375);
            row.add(fan.spoke(k - j), -0.125);
        }
        out.set_edge_row(even_child(child, fan, j), row);
    }
}

}  // namespace detail

namespace {

/// The first crease, corner or hole of @p t, as a phrase for an error message ("" when smooth).
std::string first_sharp_element(const Topology& t) {
    for (Index e = 0; e < t.num_edges(); ++e) {
        if (t.edge_sharpness(e) > 0.0) {
            const auto ends = t.edge_vertices(e);
            return detail::concat("edge ", e, " (vertices ", ends[0], ", ", ends[1], ") is a crease");
        }
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.vertex_sharpness(v) > 0.0) {
            return detail::concat("vertex ", v, " is a corner");
        }
    }
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (t.is_hole(f)) {
            return detail::concat("face ", f, " is a hole");
        }
    }
    return {};
}

}  // namespace

void require_form_rules(const Topology& parent, SchemeKind kind, const SchemeOptions& /*options*/,
                        const TunedWeights& weights) {
    LIMSURF_CHECK(kind == SchemeKind::Loop || kind == SchemeKind::CatmullClark, UnsupportedError,
                  "form subdivision (1- and 2-forms) is defined for loop and catmull-clark, not ", to_string(kind));
    if (parent.has_sharpness()) {
        throw UnsupportedError(
            detail::concat("form subdivision has no crease rules (the SEC paper leaves them to future work): ",
                           first_sharp_element(parent)));
    }
    LIMSURF_CHECK(weights.is_catmull_clark(), UnsupportedError,
                  "form subdivision has no 1-form rules for tuned Catmull–Clark weights");
    const Index degree = kind == SchemeKind::Loop ? 3 : 4;
    for (Index f = 0; f < parent.num_faces(); ++f) {
        LIMSURF_CHECK(parent.face_degree(f) == degree, UnsupportedError, "face ", f, " has ", parent.face_degree(f),
                      " vertices: ", to_string(kind), " form subdivision needs ",
                      kind == SchemeKind::Loop ? "triangles"
                                               : "quads (refine once without forms: every child is a quad)");
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        LIMSURF_CHECK(parent.is_boundary_vertex(v) || parent.vertex_faces(v).size() >= 3, UnsupportedError,
                      "interior vertex ", v, " has ", parent.vertex_faces(v).size(),
                      " faces: form subdivision needs at least 3");
    }
}

FormSubdivision form_subdivision(const Topology& parent, const Topology& child, SchemeKind kind,
                                 const SchemeOptions& options) {
    require_form_rules(parent, kind, options);
    const bool loop = kind == SchemeKind::Loop;
    const Index expected_vertices = parent.num_vertices() + parent.num_edges() + (loop ? 0 : parent.num_faces());
    const Index expected_faces = loop ? 4 * parent.num_faces() : parent.num_corners();
    LIMSURF_CHECK(child.num_vertices() == expected_vertices && child.num_faces() == expected_faces, InputError,
                  "form_subdivision: the child topology (", child.num_vertices(), " vertices, ", child.num_faces(),
                  " faces) is not one ", to_string(kind), " step of the parent (", expected_vertices, ", ",
                  expected_faces, ")");
    return loop ? detail::loop_form_subdivision(parent, child, options)
                : detail::catmull_clark_form_subdivision(parent, child, options);
}

Level refine_with_forms(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                        const TunedWeights& weights) {
    require_form_rules(parent, kind, options, weights);
    Level level = refine(parent, kind, options, weights);
    FormSubdivision forms = form_subdivision(parent, level.topology, kind, options);
    level.S1.swap(forms.S1);
    level.S2.swap(forms.S2);
    return level;
}

}  // namespace limsurf
