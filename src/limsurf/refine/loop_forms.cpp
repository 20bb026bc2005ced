// Loop's 1- and 2-form subdivision rules (docs/sec.md "Form subdivision", Loop): the half-box
// spline 2-form rules with β_n, and 1-form rules = exact part (from S0) + face circulations
// (from S2). The labels (x_i spokes, Ω_i fan circulations, P/C/N) are those of docs/sec.md.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "limsurf/refine/form_rules.h"
#include "limsurf/refine/form_subdivision.h"
#include "limsurf/refine/loop_weights.h"

namespace limsurf::detail {
namespace {

/// β_n of the corner 2-form rule: 1/(8(1 − cos 2π/n)), capped at the regular 1/4. This gives
/// 1/12, 1/8, 1/4 at n = 3, 4, 6 and makes 1/8 the second eigenvalue of the rule for n ≤ 6
/// (docs/sec.md explains the choice at n = 5 against the SecStencils value).
double beta(Index n) {
    const double b = 1.0 / (8.0 * (1.0 - std::cos(2.0 * std::numbers::pi / static_cast<double>(n))));
    return std::min(0.25, b);
}

/// Weights on the fan faces f_0..f_{k-1} of the corner child of f_j at a boundary vertex.
std::vector<double> boundary_corner_weights(Index k, Index j) {
    std::vector<double> w(static_cast<std::size_t>(k), 0.0);
    const auto set = [&](Index i, double x) { w[static_cast<std::size_t>(i)] = x; };
    const bool mirrored = j > k - 1 - j;
    const Index jj = mirrored ? k - 1 - j : j;
    if (k == 1) {
        set(0, 0.25);
    } else if (k == 2) {
        set(jj, 1.0 / 6.0);
        set(1 - jj, 1.0 / 12.0);
    } else if (jj == 0) {
        set(0, 1.0 / 6.0);
        set(1, 1.0 / 24.0);
        set(2, 1.0 / 24.0);
    } else if (k == 3) {  // jj == 1: the middle face of three
        set(0, 1.0 / 24.0);
        set(1, 1.0 / 6.0);
        set(2, 1.0 / 24.0);
    } else if (jj == 1) {
        set(0, 5.0 / 96.0);
        set(1, 7.0 / 48.0);
        set(2, 1.0 / 48.0);
        set(3, 1.0 / 32.0);
    } else {  // 2 <= jj <= k-3: the regular half-box rule
        set(jj, 0.125);
        for (const Index d : {-2, -1, 1, 2}) {
            set(jj + d, 1.0 / 32.0);
        }
    }
    if (mirrored) {
        std::reverse(w.begin(), w.end());
    }
    return w;
}

/// Circulation coefficients c_i (fan faces f_0..f_{k-1}) of the even child of spoke j, 1 <= j <= k-1,
/// at a boundary vertex with k faces. A mirror maps j to k - j, face i to k-1-i and flips Ω's sign.
std::vector<double> boundary_even_circulations(Index k, Index j) {
    std::vector<double> c(static_cast<std::size_t>(k), 0.0);
    const auto set = [&](Index i, double x) { c[static_cast<std::size_t>(i)] = x; };
    if (k == 2) {
        set(0, 5.0 / 96.0);
        set(1, -5.0 / 96.0);
        return c;
    }
    const bool mirrored = j == k - 1 && j != 1;
    const bool first = j == 1 || mirrored;
    if (!first) {  // 2 <= j <= k-2: the interior rule with β = 1/4
        set(j - 2, 1.0 / 32.0);
        set(j - 1, 1.0 / 32.0);
        set(j, -1.0 / 32.0);
        set(j + 1, -1.0 / 32.0);
        return c;
    }
    set(0, 5.0 / 96.0);
    set(1, -1.0 / 96.0);
    set(2, -1.0 / 24.0);
    if (mirrored) {
        std::reverse(c.begin(), c.end());
        for (auto& x : c) {
            x = -x;
        }
    }
    return c;
}

class LoopForms {
  public:
    LoopForms(const Topology& parent, const Topology& child, const SchemeOptions& options)
        : parent_(parent), child_(child), options_(options), out_(parent, child) {}

    FormSubdivision build() {
        for (Index v = 0; v < parent_.num_vertices(); ++v) {
            const VertexFan fan(parent_, v);
            even_children(fan);
            corner_children(fan);
        }
        for (Index f = 0; f < parent_.num_faces(); ++f) {
            for (Index c = 0; c < 3; ++c) {
                odd_edge(f, c);
            }
            central_child(f);
        }
        return {out_.finish_s1(), out_.finish_s2()};
    }

  private:
    // S1 of the fine edges v → edge point, one per spoke.
    void even_children(const VertexFan& fan) {
        const Index k = fan.num_faces();
        if (!fan.is_boundary()) {
            const double alpha = loop_neighbour_weight(static_cast<std::size_t>(k));
            const double b8 = beta(k) / 8.0;
            for (Index j = 0; j < k; ++j) {
                row_.clear();
                row_.add(fan.spoke(j), 0.375);
                row_.add(fan.spoke(j + 1), 0.125);
                row_.add(fan.spoke(j - 1), 0.125);
                for (Index i = 0; i < k; ++i) {
                    row_.add(fan.spoke(i), -alpha);
                }
                row_.add_circulation(parent_, fan.face(fan.wrap(j - 2)), b8);
                row_.add_circulation(parent_, fan.face(fan.wrap(j - 1)), b8);
                row_.add_circulation(parent_, fan.face(fan.wrap(j)), -b8);
                row_.add_circulation(parent_, fan.face(fan.wrap(j + 1)), -b8);
                out_.set_edge_row(even_child(child_, fan, j), row_);
            }
            return;
        }
        boundary_edge_children(child_, fan, options_.boundary, row_, out_);
        for (Index j = 1; j < k; ++j) {
            row_.clear();
            row_.add(fan.spoke(j), 0.375);
            row_.add(fan.spoke(j - 1), 0.125);
            row_.add(fan.spoke(j + 1), 0.125);
            row_.add(fan.spoke(0), -0.125);
            row_.add(fan.spoke(k), -0.125);
            const std::vector<double> c = boundary_even_circulations(k, j);
            for (Index i = 0; i < k; ++i) {
                row_.add_circulation(parent_, fan.face(i), c[static_cast<std::size_t>(i)]);
            }
            out_.set_edge_row(even_child(child_, fan, j), row_);
        }
    }

    // S2 of the corner children at v (child 4f + corner).
    void corner_children(const VertexFan& fan) {
        const Index k = fan.num_faces();
        for (Index j = 0; j < k; ++j) {
            row_.clear();
            if (fan.is_boundary()) {
                const std::vector<double> w = boundary_corner_weights(k, j);
                for (Index i = 0; i < k; ++i) {
                    row_.add_face(fan.face(i), w[static_cast<std::size_t>(i)]);
                }
            } else {
                const double b = beta(k);
                row_.add_face(fan.face(j), 3.0 / 16.0 - b / 4.0);
                row_.add_face(fan.face(fan.wrap(j + 1)), 1.0 / 32.0);
                row_.add_face(fan.face(fan.wrap(j - 1)), 1.0 / 32.0);
                row_.add_face(fan.face(fan.wrap(j + 2)), b / 8.0);
                row_.add_face(fan.face(fan.wrap(j - 2)), b / 8.0);
            }
            out_.set_face_row(4 * fan.face(j) + fan.corner(j), row_);
        }
    }

    // S2 of the middle child 4f + 3: 1/16 from each edge neighbour, the rest from f.
    void central_child(Index f) {
        row_.clear();
        double own = 0.25;
        for (const Index e : parent_.face_edges(f)) {
            const Index g = face_across(parent_, f, e);
            if (g != invalid_index) {
                row_.add_face(g, 1.0 / 16.0);
                own -= 1.0 / 16.0;
            }
        }
        row_.add_face(f, own);
        out_.set_face_row(4 * f + 3, row_);
    }

    // S1 of the fine edge that cuts corner C = corner c off f = (P, C, N), directed
    // mid(C, N) → mid(P, C): child 4f + c's edge 1 walked forwards.
    void odd_edge(Index f, Index c) {
        const DirectedEdge pc = face_edge(parent_, f, c - 1);
        const DirectedEdge cn = face_edge(parent_, f, c);
        const DirectedEdge np = face_edge(parent_, f, c + 1);
        const Index gp = face_across(parent_, f, pc.edge);  // (C, P, W_p)
        const Index gn = face_across(parent_, f, cn.edge);  // (N, C, W_n)
        row_.clear();
        if (gp != invalid_index && gn != invalid_index) {
            row_.add(np, 0.25);
            row_.add(c_to_w(gp, pc.edge), 0.125);
            row_.add(c_to_w(gn, cn.edge, true), 0.125);
            row_.add_circulation(parent_, f, -1.0 / 16.0);
            row_.add_circulation(parent_, gp, 1.0 / 32.0);
            row_.add_circulation(parent_, gn, 1.0 / 32.0);
        } else if (gp == invalid_index && gn != invalid_index) {
            row_.add(np, 0.375);
            row_.add(c_to_w(gn, cn.edge, true), 0.125);
            row_.add_circulation(parent_, f, -5.0 / 32.0);
            row_.add_circulation(parent_, gn, 1.0 / 32.0);
        } else if (gp != invalid_index) {
            row_.add(np, 0.375);
            row_.add(c_to_w(gp, pc.edge), 0.125);
            row_.add_circulation(parent_, f, -5.0 / 32.0);
            row_.add_circulation(parent_, gp, 1.0 / 32.0);
        } else {  // an ear: two boundary edges
            row_.add(np, 0.5);
            row_.add_circulation(parent_, f, -0.25);
        }
        out_.set_edge_row(face_edge(child_, 4 * f + c, 1), row_);
    }

    // In the flap g across edge e from C: g = (C, P, W_p) gives C → W_p (reverse of g's edge after
    // the next); with @p into_c, g = (N, C, W_n) gives W_n → C (reverse of g's edge after e).
    [[nodiscard]] DirectedEdge c_to_w(Index g, Index e, bool into_c = false) const {
        const Index q = edge_position(parent_, g, e);
        return into_c ? face_edge(parent_, g, q + 1).reversed() : face_edge(parent_, g, q + 2).reversed();
    }

    const Topology& parent_;
    const Topology& child_;
    const SchemeOptions& options_;
    FormAssembler out_;
    FormRow row_;
};

}  // namespace

FormSubdivision loop_form_subdivision(const Topology& parent, const Topology& child, const SchemeOptions& options) {
    return LoopForms(parent, child, options).build();
}

}  // namespace limsurf::detail
