// Form subdivision: shared machinery, checks and dispatch (the rules are in loop_forms.cpp and
// catmull_clark_forms.cpp).
#include "limsurf/refine/form_subdivision.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "limsurf/core/error.h"
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

FormAssembler::FormAssembler(const Topology& parent, const Topology& child)
    : parent_edges_(parent.num_edges()), parent_faces_(parent.num_faces()), child_edges_(child.num_edges()),
      child_faces_(child.num_faces()), edge_seen_(static_cast<std::size_t>(child.num_edges()), 0),
      face_seen_(static_cast<std::size_t>(child.num_faces()), 0) {
    s1_.reserve(static_cast<std::size_t>(child.num_edges()) * 16);
    s2_.reserve(static_cast<std::size_t>(child.num_faces()) * 6);
}

void FormAssembler::set_edge_row(DirectedEdge fine, const FormRow& row) {
    ++edge_seen_[static_cast<std::size_t>(fine.edge)];
    // A rule names the same coarse edge several times (spokes, diagonals, circulations): merge
    // them here, so that the triplet list (and its sort) is a few times shorter.
    merged_.assign(row.entries().begin(), row.entries().end());
    std::sort(merged_.begin(), merged_.end(), [](const auto& a, const auto& b) { return a.col < b.col; });
    for (std::size_t i = 0; i < merged_.size();) {
        double sum = 0.0;
        const Index col = merged_[i].col;
        for (; i < merged_.size() && merged_[i].col == col; ++i) {
            sum += merged_[i].weight;
        }
        if (sum != 0.0) {
            s1_.emplace_back(fine.edge, col, fine.sign * sum);
        }
    }
}

void FormAssembler::set_face_row(Index fine_face, const FormRow& row) {
    ++face_seen_[static_cast<std::size_t>(fine_face)];
    for (const auto& entry : row.entries()) {
        s2_.emplace_back(fine_face, entry.col, entry.weight);
    }
}

namespace {

/// Every fine element must get exactly one rule: a gap or a double would be a bug in the rules'
/// bookkeeping, so it is checked in every build (cheap next to the assembly).
void check_coverage(const std::vector<std::uint8_t>& seen, const char* what) {
    for (std::size_t i = 0; i < seen.size(); ++i) {
        if (seen[i] != 1) {
            throw std::logic_error(
                concat("form subdivision set ", static_cast<int>(seen[i]), " rows for child ", what, " ", i));
        }
    }
}

SparseMatrix build(Index rows, Index cols, const std::vector<Eigen::Triplet<double, Index>>& triplets) {
    SparseMatrix m(rows, cols);
    m.setFromTriplets(triplets.begin(), triplets.end());
    m.prune(0.0);
    return m;
}

}  // namespace

SparseMatrix FormAssembler::finish_s1() {
    check_coverage(edge_seen_, "edge");
    return build(child_edges_, parent_edges_, s1_);
}

SparseMatrix FormAssembler::finish_s2() {
    check_coverage(face_seen_, "face");
    return build(child_faces_, parent_faces_, s2_);
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
