// Reverse Catmull–Clark (iga-with-catmull-clark §3): classes the fine vertices as old vertices,
// edge points and face points, rebuilds the coarse topology, checks it by refining it again, and
// fits the coarse positions by least squares on S0 (docs/guide/reverse.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/SparseCore>

#include "limsurf/core/error.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "limsurf/refine/refine.h"
#include "limsurf/refine/reverse.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// The role of a fine vertex in the refinement it came from.
enum class Role : std::int8_t { Unknown, Old, Edge, Face };

/// A reason a classing or a level fails, with the fine element it is about.
struct Refusal {
    std::string message;
    std::optional<ErrorElement> element;
};

[[noreturn]] void refuse(const Refusal& r) {
    if (r.element) {
        throw InputError(r.message, *r.element);
    }
    throw InputError(r.message);
}

/// Classes of one connected component, or why the seed fails.
struct Classing {
    std::vector<Role> role;  // over all vertices; Unknown outside the component
    std::optional<Refusal> refusal;
};

/// Propagates the pattern (V, E, F, E) from corner @p seed of face @p first over its component:
/// across a shared edge, the neighbour's pattern follows from the classes of the edge's two ends.
Classing class_component(const Topology& t, Index first, int seed) {
    Classing out;
    out.role.assign(at(t.num_vertices()), Role::Unknown);
    std::vector<int> offset(at(t.num_faces()), -1);  // the corner of each face that is V
    std::vector<Index> queue{first};
    offset[at(first)] = seed;
    const auto fail = [&](std::string message, ErrorElement element) {
        out.refusal = Refusal{std::move(message), element};
        return out;
    };
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const Index f = queue[q];
        const auto corners = t.face_vertices(f);
        const int r = offset[at(f)];
        for (int k = 0; k < 4; ++k) {
            const Role want = k == 0 ? Role::Old : (k == 2 ? Role::Face : Role::Edge);
            const Index v = corners[at((r + k) % 4)];
            Role& have = out.role[at(v)];
            if (have != Role::Unknown && have != want) {
                return fail(detail::concat("vertex ", v,
                                           " cannot be classed consistently as an old vertex, edge "
                                           "point or face point: the mesh is not a Catmull-Clark refinement"),
                            vertex_element(v));
            }
            have = want;
        }
        const auto edges = t.face_edges(f);
        for (int k = 0; k < 4; ++k) {
            for (const Index g : t.edge_faces(edges[at(k)])) {
                if (offset[at(g)] >= 0) {
                    continue;
                }
                // The end of the shared edge that is not an edge point is V or F in g too.
                const Index a = corners[at(k)];
                const Index b = corners[at((k + 1) % 4)];
                const Index key = out.role[at(a)] == Role::Edge ? b : a;
                const auto gc = t.face_vertices(g);
                const auto j = static_cast<int>(std::find(gc.begin(), gc.end(), key) - gc.begin());
                offset[at(g)] = out.role[at(key)] == Role::Old ? j : (j + 2) % 4;
                queue.push_back(g);
            }
        }
    }
    // What a refinement guarantees: face points interior with valence >= 3, edge points of valence
    // 4 (interior) or 3 (on the boundary, between two old vertices).
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const Role role = out.role[at(v)];
        if (role == Role::Face && t.is_boundary_vertex(v)) {
            return fail(detail::concat("vertex ", v, " would be a face point but lies on the boundary"),
                        vertex_element(v));
        }
        if (role == Role::Face && t.valence(v) < 3) {
            return fail(detail::concat("vertex ", v, " would be the face point of a ", t.valence(v), "-gon"),
                        vertex_element(v));
        }
        const Index want = t.is_boundary_vertex(v) ? 3 : 4;
        if (role == Role::Edge && t.valence(v) != want) {
            return fail(detail::concat("vertex ", v, " would be an edge point but has valence ", t.valence(v),
                                       " (an edge point has valence 4, or 3 on the boundary)"),
                        vertex_element(v));
        }
    }
    return out;
}

/// A candidate coarse level: topology, where its refinement's vertices are in the fine mesh, fit.
struct Candidate {
    Topology coarse;
    std::vector<Index> fine_vertex;  // #V_coarse
    Points positions;
    std::vector<double> error;  // #V_fine: ‖(S0 P)_i − P_fine,i‖
    bool unique = true;
};

/// Decodes a fine sharpness into the coarse one that Uniform creasing decrements to it.
std::optional<double> coarse_sharpness(double fine) {
    if (fine <= 0.0) {
        return 0.0;
    }
    if (fine >= infinite_sharpness) {
        return infinite_sharpness;
    }
    if (fine + 1.0 >= infinite_sharpness) {
        return std::nullopt;  // a coarse value >= 10 is infinite and stays infinite
    }
    return fine + 1.0;
}

/// The E vertex between fine vertices a and b (both old vertices), or invalid_index.
Index edge_point_between(const Topology& t, Index a, Index b) {
    for (const Index e : t.vertex_edges(a)) {
        const Index m = t.other_vertex(e, a);
        for (const Index e2 : t.vertex_edges(m)) {
            if (t.other_vertex(e2, m) == b) {
                return m;
            }
        }
    }
    return invalid_index;
}

/// The face point of the fine face that has old vertex @p v and, next counter-clockwise, edge point @p e.
Index face_point_after(const Topology& t, Index v, Index e) {
    const auto faces = t.vertex_faces(v);
    const auto corners = t.vertex_face_corners(v);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const auto c = t.face_vertices(faces[i]);
        const auto k = at(corners[i]);
        if (c.size() == 4 && c[(k + 1) % 4] == e) {
            return c[(k + 2) % 4];
        }
    }
    return invalid_index;
}

/// perm[c]: the fine vertex that child vertex c of @p coarse's refinement is (limsurf's child order:
/// vertices, face points, edge points; level.h).
std::vector<Index> child_to_fine(const Topology& fine, const Topology& coarse, const std::vector<Index>& fine_vertex) {
    const Index V = coarse.num_vertices();
    const Index F = coarse.num_faces();
    std::vector<Index> perm(at(V + F + coarse.num_edges()), invalid_index);
    for (Index v = 0; v < V; ++v) {
        perm[at(v)] = fine_vertex[at(v)];
    }
    for (Index e = 0; e < coarse.num_edges(); ++e) {
        const auto ends = coarse.edge_vertices(e);
        perm[at(V + F + e)] = edge_point_between(fine, fine_vertex[at(ends[0])], fine_vertex[at(ends[1])]);
    }
    for (Index f = 0; f < F; ++f) {
        const auto c = coarse.face_vertices(f);
        const Index e = perm[at(V + F + coarse.face_edges(f)[0])];
        perm[at(V + f)] = e == invalid_index ? invalid_index : face_point_after(fine, fine_vertex[at(c[0])], e);
    }
    return perm;
}

/// A face's corners rotated to start at the smallest, for comparing faces up to rotation.
std::vector<Index> canonical(std::vector<Index> face) {
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    return face;
}

/// The coarse topology for the classes @p role, checked by refining it again.
Candidate build_topology(const ControlMesh& fine, const std::vector<Role>& role) {
    const Topology& t = fine.topology();
    Candidate out;
    std::vector<Index> coarse_index(at(t.num_vertices()), invalid_index);
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (role[at(v)] == Role::Old) {
            coarse_index[at(v)] = static_cast<Index>(out.fine_vertex.size());
            out.fine_vertex.push_back(v);
        }
    }
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    SharpnessTags tags;
    Index coarse_faces = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (role[at(v)] != Role::Face) {
            continue;
        }
        LIMSURF_CHECK_AT(t.vertex_sharpness(v) == 0.0, InputError, vertex_element(v), "vertex ", v,
                         " is a face point with sharpness ", t.vertex_sharpness(v), ": no coarse tag refines to that");
        const auto faces = t.vertex_faces(v);
        const auto at_face = t.vertex_face_corners(v);
        int holes = 0;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const auto c = t.face_vertices(faces[i]);
            corners.push_back(coarse_index[at(c[(at(at_face[i]) + 2) % 4])]);
            holes += t.is_hole(faces[i]) ? 1 : 0;
        }
        for (const Index e : t.vertex_edges(v)) {
            LIMSURF_CHECK_AT(t.edge_sharpness(e) == 0.0, InputError, vertex_element(v), "the edge from face point ", v,
                             " to vertex ", t.other_vertex(e, v),
                             " is sharp: it lies inside a coarse face, where no coarse tag makes a crease");
        }
        if (holes > 0) {
            tags.holes.push_back({coarse_faces, 0});
        }
        offsets.push_back(static_cast<Index>(corners.size()));
        ++coarse_faces;
    }
    // Creases: the two halves of a coarse edge carry its sharpness decremented once (Uniform).
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (role[at(v)] == Role::Edge) {
            LIMSURF_CHECK_AT(t.vertex_sharpness(v) == 0.0, InputError, vertex_element(v), "vertex ", v,
                             " is an edge point with sharpness ", t.vertex_sharpness(v),
                             ": no coarse tag refines to that");
            std::vector<std::pair<Index, double>> ends;
            for (const Index e : t.vertex_edges(v)) {
                const Index w = t.other_vertex(e, v);
                if (role[at(w)] == Role::Old) {
                    ends.emplace_back(coarse_index[at(w)], t.edge_sharpness(e));
                }
            }
            LIMSURF_CHECK_AT(ends.size() == 2, InputError, vertex_element(v), "edge point ", v, " has ", ends.size(),
                             " old-vertex neighbours, not 2");
            LIMSURF_CHECK_AT(ends[0].second == ends[1].second, InputError, vertex_element(v),
                             "the two halves of the "
                             "coarse edge at edge point ",
                             v, " have different sharpness (", ends[0].second, ", ", ends[1].second, ")");
            const auto s = coarse_sharpness(ends[0].second);
            LIMSURF_CHECK_AT(s.has_value(), InputError, vertex_element(v), "the edges at edge point ", v,
                             " have sharpness ", ends[0].second, ": no coarse crease refines to that");
            if (*s > 0.0) {
                tags.creases.push_back({ends[0].first, ends[1].first, *s, 0});
            }
        } else if (role[at(v)] == Role::Old && t.vertex_sharpness(v) > 0.0) {
            const auto s = coarse_sharpness(t.vertex_sharpness(v));
            LIMSURF_CHECK_AT(s.has_value(), InputError, vertex_element(v), "vertex ", v, " has sharpness ",
                             t.vertex_sharpness(v), ": no coarse corner refines to that");
            tags.corners.push_back({coarse_index[at(v)], *s, 0});
        }
    }
    try {
        out.coarse = Topology(static_cast<Index>(out.fine_vertex.size()), offsets, corners, tags);
    } catch (const TopologyError& error) {
        throw InputError(detail::concat("the recovered coarse mesh is not a valid mesh: ", error.what()));
    }
    return out;
}

/// Refines @p c.coarse and compares with the fine mesh: faces (up to rotation), sharpness, holes.
/// @return the child → fine vertex map and S0
std::pair<std::vector<Index>, SparseMatrix> check_refines_to(const ControlMesh& fine, const Candidate& c,
                                                             const SchemeOptions& options) {
    const Topology& t = fine.topology();
    Level level = refine_catmull_clark(c.coarse, options);
    const std::vector<Index> perm = child_to_fine(t, c.coarse, c.fine_vertex);
    const Topology& child = level.topology;
    LIMSURF_CHECK(child.num_vertices() == t.num_vertices() && child.num_faces() == t.num_faces(), InputError,
                  "the recovered coarse mesh refines to ", child.num_vertices(), " vertices and ", child.num_faces(),
                  " faces, not ", t.num_vertices(), " and ", t.num_faces());
    std::vector<char> seen(at(t.num_vertices()), 0);
    for (const Index p : perm) {
        LIMSURF_CHECK(p != invalid_index && seen[at(p)] == 0, InputError,
                      "the recovered coarse mesh does not refine to the given one (vertex correspondence)");
        seen[at(p)] = 1;
    }
    std::map<std::vector<Index>, Index> fine_faces;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto c4 = t.face_vertices(f);
        fine_faces.emplace(canonical({c4.begin(), c4.end()}), f);
    }
    for (Index f = 0; f < child.num_faces(); ++f) {
        std::vector<Index> mapped;
        for (const Index v : child.face_vertices(f)) {
            mapped.push_back(perm[at(v)]);
        }
        const auto found = fine_faces.find(canonical(mapped));
        LIMSURF_CHECK_AT(found != fine_faces.end(), InputError, vertex_element(mapped[0]),
                         "the recovered coarse mesh does not refine to the given one near vertex ", mapped[0]);
        LIMSURF_CHECK_AT(child.is_hole(f) == t.is_hole(found->second), InputError, face_element(found->second), "face ",
                         found->second, " is ", t.is_hole(found->second) ? "" : "not ",
                         "a hole but other faces of its coarse face are not: no coarse hole refines to that");
    }
    for (Index e = 0; e < child.num_edges(); ++e) {
        const auto ends = child.edge_vertices(e);
        const Index a = perm[at(ends[0])];
        const Index fe = t.find_edge(a, perm[at(ends[1])]);
        LIMSURF_CHECK_AT(std::abs(child.edge_sharpness(e) - t.edge_sharpness(fe)) <= 1e-12, InputError,
                         vertex_element(a), "the edge from vertex ", a, " to vertex ", perm[at(ends[1])],
                         " has sharpness ", t.edge_sharpness(fe), " but the recovered coarse mesh refines to ",
                         child.edge_sharpness(e), " (only Uniform creasing can be reversed)");
    }
    for (Index v = 0; v < child.num_vertices(); ++v) {
        const Index a = perm[at(v)];
        LIMSURF_CHECK_AT(std::abs(child.vertex_sharpness(v) - t.vertex_sharpness(a)) <= 1e-12, InputError,
                         vertex_element(a), "vertex ", a, " has sharpness ", t.vertex_sharpness(a),
                         " but the recovered coarse mesh refines to ", child.vertex_sharpness(v));
    }
    // Swapped in, not moved: Eigen 3.4's SparseMatrix has no move constructor, so the pair's would copy it.
    std::pair<std::vector<Index>, SparseMatrix> out;
    out.first = perm;
    out.second.swap(level.S0);
    return out;
}

/// min ‖S0 X − P‖ through the normal equations N X = S0ᵀP, N = S0ᵀ S0. N is factored once (CHOLMOD's
/// supernodal Cholesky where built with it): when its pivots show no kernel, the fit is the unique
/// solution, with one step of iterative refinement. Otherwise (or should N not factor) by iterated
/// Tikhonov, started at (and, in the kernel of S0, staying at) X0: each step solves
/// (N + λI) X_{k+1} = S0ᵀP + λ X_k, which converges to the least-squares solution closest to X0.
Points least_squares(const SparseMatrix& S0, const Points& P, const Points& X0, bool& unique) {
    const SparseMatrix N = SparseMatrix(S0.transpose()) * S0;
    const Eigen::MatrixXd rhs = S0.transpose() * P;
    const auto check_finite = [](const Points& X) {
        LIMSURF_CHECK(X.allFinite(), NumericalError, "the least-squares fit of the coarse positions is not finite");
    };
    // Uniqueness: the pivots of N itself (a pivot at rounding level: a kernel).
    std::optional<detail::SparseCholesky> plain;
    try {
        plain.emplace(N, "the normal equations of the fit");
    } catch (const NumericalError&) {
        // not positive definite: a kernel (handled below)
    }
    unique = plain && plain->pivot_ratio() > 1e-10;
    if (unique) {
        Points X = plain->solve_columns(rhs);
        X += plain->solve_columns(rhs - N * X);
        check_finite(X);
        return X;
    }
    double largest = 0.0;
    for (Index i = 0; i < N.rows(); ++i) {
        largest = std::max(largest, N.coeff(i, i));
    }
    const double lambda = 1e-8 * largest;
    SparseMatrix A = N;
    for (Index i = 0; i < A.cols(); ++i) {
        A.coeffRef(i, i) += lambda;
    }
    const detail::SparseCholesky solver(A, "the regularised normal equations of the fit");
    const double scale = std::max(1.0, P.cwiseAbs().maxCoeff());
    Points X = X0;
    for (int k = 0; k < 60; ++k) {
        const Eigen::MatrixXd b = rhs + lambda * Eigen::MatrixXd(X);
        const Points next = solver.solve_columns(b);
        const double change = (next - X).cwiseAbs().maxCoeff();
        X = next;
        if (!(change > 1e-17 * scale)) {
            break;
        }
    }
    check_finite(X);
    return X;
}

/// Builds the candidate for @p role: topology, check, fit.
Candidate fit(const ControlMesh& fine, const std::vector<Role>& role, const SchemeOptions& options) {
    Candidate c = build_topology(fine, role);
    auto [perm, S0] = check_refines_to(fine, c, options);
    Points target(fine.num_vertices(), 3);
    for (std::size_t i = 0; i < perm.size(); ++i) {
        target.row(static_cast<Index>(i)) = fine.positions().row(perm[i]);
    }
    Points start(c.coarse.num_vertices(), 3);
    for (Index v = 0; v < c.coarse.num_vertices(); ++v) {
        start.row(v) = fine.positions().row(c.fine_vertex[at(v)]);
    }
    c.positions = least_squares(S0, target, start, c.unique);
    const Points refit = S0 * c.positions;
    c.error.assign(at(fine.num_vertices()), 0.0);
    for (std::size_t i = 0; i < perm.size(); ++i) {
        const auto row = static_cast<Index>(i);
        // stableNorm: near the largest double the squares of a plain norm overflow to inf
        c.error[at(perm[i])] = (refit.row(row) - target.row(row)).stableNorm();
    }
    return c;
}

/// One level: classes every component and keeps, per component, the classing whose fit is best.
/// The pattern can start at any of the 4 corners of the first face: corners 0 and 2 (or 1 and 3)
/// swap old vertices and face points, i.e. the coarse mesh and its dual, both consistent on a closed
/// mesh; corners 0 and 1 differ in which vertices are edge points (both consistent on a closed
/// mesh of valence 4 only). The residual decides; ties keep the earliest corner (limsurf's child
/// faces start at their old vertex, so corner 0 for its own refinements).
Candidate reverse_one(const ControlMesh& fine, const SchemeOptions& options) {
    const Topology& t = fine.topology();
    for (Index f = 0; f < t.num_faces(); ++f) {
        LIMSURF_CHECK_AT(t.face_degree(f) == 4, InputError, face_element(f), "face ", f, " has ", t.face_degree(f),
                         " corners: a Catmull-Clark refinement has quads only");
    }
    LIMSURF_CHECK(t.num_faces() > 0, InputError, "the mesh has no faces");
    // choices[c]: the consistent classings of component c, at most 4.
    std::vector<std::vector<Classing>> choices(at(t.num_components()));
    std::size_t most = 1;
    for (Index f = 0; f < t.num_faces(); ++f) {
        auto& mine = choices[at(t.face_component(f))];
        if (!mine.empty()) {
            continue;
        }
        std::optional<Refusal> first_refusal;
        for (int seed = 0; seed < 4; ++seed) {
            Classing c = class_component(t, f, seed);
            if (c.refusal) {
                if (!first_refusal) {
                    first_refusal = c.refusal;
                }
            } else {
                mine.push_back(std::move(c));
            }
        }
        if (mine.empty()) {
            refuse(*first_refusal);
        }
        most = std::max(most, mine.size());
    }
    // Candidate k: every component with its k-th consistent classing (or its last).
    const auto roles_for = [&](const std::vector<std::size_t>& pick) {
        std::vector<Role> role(at(t.num_vertices()), Role::Unknown);
        for (std::size_t c = 0; c < choices.size(); ++c) {
            const Classing& chosen = choices[c][pick[c]];
            for (Index v = 0; v < t.num_vertices(); ++v) {
                if (chosen.role[at(v)] != Role::Unknown) {
                    role[at(v)] = chosen.role[at(v)];
                }
            }
        }
        return role;
    };
    std::vector<std::size_t> best_pick(choices.size(), 0);
    std::vector<double> best_error(choices.size(), 0.0);
    std::optional<Candidate> first;
    std::optional<Refusal> failure;
    for (std::size_t k = 0; k < most; ++k) {
        std::vector<std::size_t> pick(choices.size());
        for (std::size_t c = 0; c < choices.size(); ++c) {
            pick[c] = std::min(k, choices[c].size() - 1);
        }
        std::optional<Candidate> candidate;
        try {
            candidate = fit(fine, roles_for(pick), options);
        } catch (const InputError& error) {
            if (!failure) {
                failure = Refusal{error.what(), error.element()};
            }
            continue;
        }
        std::vector<double> error(choices.size(), 0.0);
        for (Index v = 0; v < t.num_vertices(); ++v) {
            auto& e = error[at(t.vertex_component(v))];
            e = std::max(e, candidate->error[at(v)]);
        }
        for (std::size_t c = 0; c < choices.size(); ++c) {
            if (!first || error[c] < 0.5 * best_error[c]) {
                best_pick[c] = pick[c];
                best_error[c] = error[c];
            }
        }
        if (!first) {
            first = std::move(candidate);
        }
    }
    if (!first) {
        refuse(*failure);
    }
    if (most == 1) {
        return std::move(*first);
    }
    return fit(fine, roles_for(best_pick), options);
}

SchemeHints hints_of(const SchemeOptions& options) {
    SchemeHints hints;
    hints.boundary = options.boundary;
    hints.creasing = options.creasing;
    hints.triangles = options.triangles;
    return hints;
}

}  // namespace

ReverseResult reverse_catmull_clark(const ControlMesh& fine, int max_levels, const SchemeOptions& options,
                                    double tolerance) {
    LIMSURF_CHECK(max_levels >= 1 || max_levels == -1, InputError,
                  "the number of levels to reverse must be >= 1 or "
                  "-1 (as many as possible), not ",
                  max_levels);
    // A nan tolerance compared false with every residual and silently stopped after one level.
    LIMSURF_CHECK(std::isfinite(tolerance) && tolerance >= 0.0, InputError,
                  "the tolerance must be a finite number >= 0, not ", tolerance);
    ReverseResult result;
    ControlMesh current = fine;
    for (int level = 0; max_levels == -1 || level < max_levels; ++level) {
        Candidate c;
        try {
            c = reverse_one(current, options);
        } catch (const InputError& error) {
            if (level == 0) {
                throw;
            }
            if (max_levels == -1) {
                break;
            }
            throw InputError(detail::concat("level ", level + 1, " of ", max_levels, " cannot be reversed (", level,
                                            " could): ", error.what()));
        }
        // stableNorm: the squares of errors near the largest double overflow in a plain norm
        const Eigen::Map<const Eigen::VectorXd> errors(c.error.data(), static_cast<Eigen::Index>(c.error.size()));
        const double largest = errors.size() > 0 ? errors.maxCoeff() : 0.0;
        if (max_levels == -1 && level > 0) {
            // Past the first level, "as many as possible" takes only levels that fit.
            const Points& p = current.positions();
            const Eigen::RowVector3d box = p.colwise().maxCoeff() / 2.0 - p.colwise().minCoeff() / 2.0;
            const double diagonal = 2.0 * box.stableNorm();  // halves: max − min itself may overflow
            if (!(largest <= tolerance * diagonal)) {
                break;
            }
        }
        ReverseStep step;
        step.fine_vertices = current.num_vertices();
        step.fine_faces = current.num_faces();
        step.coarse_vertices = c.coarse.num_vertices();
        step.coarse_faces = c.coarse.num_faces();
        step.residual_max = largest;
        step.residual_rms = errors.stableNorm() / std::sqrt(static_cast<double>(c.error.size()));
        step.unique = c.unique;
        step.fine_vertex = std::move(c.fine_vertex);
        result.steps.push_back(std::move(step));
        current = ControlMesh(std::move(c.coarse), std::move(c.positions), hints_of(options));
        ++result.levels_reversed;
    }
    result.coarse = std::move(current);
    return result;
}

Points reverse_rule_positions(const ControlMesh& fine, const Topology& coarse, const std::vector<Index>& fine_vertex,
                              const SchemeOptions& options) {
    LIMSURF_CHECK(!coarse.has_sharpness(), UnsupportedError,
                  "the rule of §3 covers meshes without creases, corners or holes: use the least-squares fit");
    LIMSURF_CHECK(options.boundary != BoundaryInterpolation::None, UnsupportedError,
                  "the rule of §3 needs boundary interpolation (edge-only or edge-and-corner)");
    LIMSURF_CHECK(fine_vertex.size() == at(coarse.num_vertices()), InputError, "fine_vertex has ", fine_vertex.size(),
                  " entries for ", coarse.num_vertices(), " coarse vertices");
    if (options.triangles == TriangleSubdivision::Smooth) {
        for (Index f = 0; f < coarse.num_faces(); ++f) {
            LIMSURF_CHECK_AT(coarse.face_degree(f) != 3, UnsupportedError, face_element(f),
                             "the rule of §3 does not cover the smooth triangle rule (face ", f, ")");
        }
    }
    const Topology& t = fine.topology();
    const Points& X = fine.positions();
    const std::vector<Index> perm = child_to_fine(t, coarse, fine_vertex);
    const Index V = coarse.num_vertices();
    const Index F = coarse.num_faces();
    const auto face_point = [&](Index f) -> Eigen::RowVector3d { return X.row(perm[at(V + f)]); };
    const auto edge_point = [&](Index e) -> Eigen::RowVector3d { return X.row(perm[at(V + F + e)]); };
    // M_j: a boundary edge point is the midpoint; an interior one is (a + b + F_a + F_b)/4.
    const auto midpoint = [&](Index e) -> Eigen::RowVector3d {
        const auto faces = coarse.edge_faces(e);
        if (faces.size() == 1) {
            return edge_point(e);
        }
        return 2.0 * edge_point(e) - 0.5 * (face_point(faces[0]) + face_point(faces[1]));
    };
    Points P(V, 3);
    std::vector<char> known(at(V), 0);
    for (Index v = 0; v < V; ++v) {
        const Eigen::RowVector3d fine_v = X.row(fine_vertex[at(v)]);
        const auto edges = coarse.vertex_edges(v);
        if (coarse.is_boundary_vertex(v)) {
            if (coarse.vertex_faces(v).size() == 1 && options.boundary == BoundaryInterpolation::EdgeAndCorner) {
                P.row(v) = fine_v;  // a corner
            } else {
                P.row(v) = 2.0 * fine_v - 0.5 * (edge_point(edges.front()) + edge_point(edges.back()));
            }
            known[at(v)] = 1;
            continue;
        }
        const auto n = static_cast<double>(edges.size());
        if (edges.size() == 3) {
            continue;  // (n − 3) V_old vanishes: from a neighbour below
        }
        Eigen::RowVector3d faces = Eigen::RowVector3d::Zero();
        for (const Index f : coarse.vertex_faces(v)) {
            faces += face_point(f);
        }
        Eigen::RowVector3d mids = Eigen::RowVector3d::Zero();
        for (const Index e : edges) {
            mids += midpoint(e);
        }
        P.row(v) = (n * fine_v - faces / n - 2.0 * mids / n) / (n - 3.0);
        known[at(v)] = 1;
    }
    // Valence 3: V_old = 2 M_j − P_j from a known neighbour P_j, spreading until nothing changes.
    for (bool changed = true; changed;) {
        changed = false;
        for (Index v = 0; v < V; ++v) {
            if (known[at(v)] != 0) {
                continue;
            }
            for (const Index e : coarse.vertex_edges(v)) {
                const Index w = coarse.other_vertex(e, v);
                if (known[at(w)] != 0) {
                    P.row(v) = 2.0 * midpoint(e) - P.row(w);
                    known[at(v)] = 1;
                    changed = true;
                    break;
                }
            }
        }
    }
    for (Index v = 0; v < V; ++v) {
        LIMSURF_CHECK_AT(known[at(v)] != 0, UnsupportedError, vertex_element(v), "coarse vertex ", v,
                         " has valence 3 and no chain of valence-3 neighbours reaches a vertex the rule of §3 "
                         "determines: use the least-squares fit");
    }
    return P;
}

}  // namespace limsurf
