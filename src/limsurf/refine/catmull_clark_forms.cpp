// Catmull–Clark's 1- and 2-form subdivision rules on quad meshes (docs/sec.md "Form subdivision",
// Catmull–Clark): Doo–Sabin-like 2-form rules, and 1-form rules = exact part (from S0) + face
// circulations (from S2), with the closed forms of the circulation weights. Labels as in docs/sec.md.
#include <algorithm>
#include <cstddef>

#include "limsurf/refine/form_rules.h"
#include "limsurf/refine/form_subdivision.h"

namespace limsurf::detail {
namespace {

class CatmullClarkForms {
  public:
    CatmullClarkForms(const Topology& parent, const Topology& child, const SchemeOptions& options)
        : parent_(parent), child_(child), options_(options), out_(parent, child) {}

    FormSubdivision build() {
        for (Index v = 0; v < parent_.num_vertices(); ++v) {
            const VertexFan fan(parent_, v);
            if (fan.is_boundary()) {
                boundary_even_children(fan);
            } else {
                interior_even_children(fan);
            }
            corner_children(fan);
        }
        for (Index f = 0; f < parent_.num_faces(); ++f) {
            for (Index c = 0; c < 4; ++c) {
                odd_edge(f, c);
            }
        }
        return {out_.finish_s1(), out_.finish_s2()};
    }

  private:
    // D_i = ½(x_i + a_i) + ½(x_{i+1} − b_i): the diagonal v → d_i of fan face i as the mean of
    // its two two-edge paths, i.e. ½ of the face's edges 0 and 1 minus ½ of its edges 2 and 3.
    void add_diagonal(const VertexFan& fan, Index i, double w) {
        row_.add(fan.edge_of_face(i, 0), 0.5 * w);
        row_.add(fan.edge_of_face(i, 1), 0.5 * w);
        row_.add(fan.edge_of_face(i, 2), -0.5 * w);
        row_.add(fan.edge_of_face(i, 3), -0.5 * w);
    }

    // The edge point of spoke j minus the vertex point, as a chain, for the parts the interior and
    // boundary rules share: 3/8 x_j + 1/16 (x_{j−1} + x_{j+1} + D_{j−1} + D_j).
    void edge_point_part(const VertexFan& fan, Index j) {
        row_.add(fan.spoke(j), 0.375);
        row_.add(fan.spoke(j - 1), 0.0625);
        row_.add(fan.spoke(j + 1), 0.0625);
        add_diagonal(fan, fan.wrap(j - 1), 0.0625);
        add_diagonal(fan, fan.wrap(j), 0.0625);
    }

    void interior_even_children(const VertexFan& fan) {
        const Index k = fan.num_faces();
        const double kd = static_cast<double>(k);
        for (Index j = 0; j < k; ++j) {
            row_.clear();
            edge_point_part(fan, j);
            for (Index i = 0; i < k; ++i) {
                row_.add(fan.spoke(i), -1.5 / (kd * kd));
                add_diagonal(fan, i, -0.25 / (kd * kd));
            }
            // Circulations: a linear ramp (2m − k + 1)/(32k) over the fan, starting at f_j.
            for (Index m = 0; m < k; ++m) {
                row_.add_circulation(parent_, fan.face(fan.wrap(j + m)),
                                     static_cast<double>(2 * m - k + 1) / (32.0 * kd));
            }
            out_.set_edge_row(even_child(child_, fan, j), row_);
        }
    }

    void boundary_even_children(const VertexFan& fan) {
        const Index k = fan.num_faces();
        const double kd = static_cast<double>(k);
        boundary_edge_children(child_, fan, options_.boundary, row_, out_);
        for (Index j = 1; j < k; ++j) {
            row_.clear();
            edge_point_part(fan, j);
            row_.add(fan.spoke(0), -0.125);
            row_.add(fan.spoke(k), -0.125);
            // Circulations: a step, (k − j)/(16k) before spoke j and −j/(16k) after it.
            for (Index i = 0; i < k; ++i) {
                const double c = i < j ? static_cast<double>(k - j) : -static_cast<double>(j);
                row_.add_circulation(parent_, fan.face(i), c / (16.0 * kd));
            }
            out_.set_edge_row(even_child(child_, fan, j), row_);
        }
    }

    // S2 of the child quads at v: (k+2)/(32k) from the fan neighbours of the parent, 1/(16k) from
    // every other fan face, the rest (to a row sum of 1/4) from the parent.
    void corner_children(const VertexFan& fan) {
        const Index k = fan.num_faces();
        const double kd = static_cast<double>(k);
        for (Index j = 0; j < k; ++j) {
            row_.clear();
            double own = 0.25;
            for (Index i = 0; i < k; ++i) {
                if (i == j) {
                    continue;
                }
                const Index distance =
                    fan.is_boundary() ? (i > j ? i - j : j - i) : std::min(fan.wrap(i - j), fan.wrap(j - i));
                const double w = distance == 1 ? (kd + 2.0) / (32.0 * kd) : 1.0 / (16.0 * kd);
                row_.add_face(fan.face(i), w);
                own -= w;
            }
            row_.add_face(fan.face(j), own);
            out_.set_face_row(4 * fan.face(j) + fan.corner(j), row_);
        }
    }

    // S1 of the fine edge from the point of edge (v0, v1) to the face point of f = (v0, v1, v2, v3):
    // child 4f + c's edge 1, walked forwards; g = (v1, v0, a, b) is the face across (v0, v1).
    void odd_edge(Index f, Index c) {
        const DirectedEdge v0v1 = face_edge(parent_, f, c);
        const Index g = face_across(parent_, f, v0v1.edge);
        row_.clear();
        if (g == invalid_index) {
            row_.add(face_edge(parent_, f, c + 1), 0.25);
            row_.add(face_edge(parent_, f, c + 3), -0.25);
        } else {
            const Index q = edge_position(parent_, g, v0v1.edge);
            row_.add(face_edge(parent_, f, c + 1), 3.0 / 16.0);
            row_.add(face_edge(parent_, f, c + 3), -3.0 / 16.0);
            row_.add(face_edge(parent_, g, q + 1), -1.0 / 16.0);  // v0 → a
            row_.add(face_edge(parent_, g, q + 3), 1.0 / 16.0);   // b → v1
        }
        out_.set_edge_row(face_edge(child_, 4 * f + c, 1), row_);
    }

    const Topology& parent_;
    const Topology& child_;
    const SchemeOptions& options_;
    FormAssembler out_;
    FormRow row_;
};

}  // namespace

FormSubdivision catmull_clark_form_subdivision(const Topology& parent, const Topology& child,
                                               const SchemeOptions& options) {
    return CatmullClarkForms(parent, child, options).build();
}

}  // namespace limsurf::detail
