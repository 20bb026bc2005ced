// The exact limit basis of Catmull–Clark and Loop surfaces (limit_basis.h).
//
// Every ptex face owns a small tree of local patches (local_patch.h). A node is
//   Regular     — a bicubic B-spline / quartic box-spline patch: evaluate it;
//   Stationary  — its corner child has the same canonical one-ring as itself, so
//                 the local subdivision matrix A repeats at every level (Stam's
//                 observation, iga-with-catmull-clark §4.2); a point n levels deep
//                 towards that corner lands in a regular child q, and its weights
//                 are B(q) · G_q · M_q · A^n · W — the matrices G_q M_q A^n are
//                 tabulated once per configuration and shared by all faces; a child
//                 q that is not regular yet (own tuned weights reach one level further)
//                 is a subtree whose regular patches get the same tables, G·W·R^n,
//                 built on first use;
//   Refine      — anything else (several extraordinary corners, semi-sharp
//                 creases, n-gons in the ring): subdivide locally and descend.
// W maps a node's local vertices to the root's support (control vertices).
#include "limsurf/limit/limit_basis.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <optional>
#include <unordered_map>

#include <Eigen/LU>

#include "c2g0_limit.h"
#include "doo_sabin_limit.h"
#include "limsurf/core/error.h"
#include "limsurf/detail/tuned_copy.h"
#include "limsurf/limit/patch_basis.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/refine/refine.h"
#include "local_patch.h"
#include "parameter_maps.h"

namespace limsurf {
namespace {

using detail::Affine;
using detail::child_containing;
using detail::child_map;
using detail::dense_rows;
using detail::domain_corner;
using detail::in_corner_child;
using detail::rotation;
using detail::to_ptex;

/// Depth of the stationary tables: points closer than 2^-60 (in parameter) to an
/// extraordinary corner are evaluated there (position exact, derivatives at 2^-61).
constexpr int max_stationary_levels = 60;
/// Any local configuration becomes regular or stationary once its semi-sharp
/// features have decayed (sharpness < 10 levels); this bounds a broken descent.
constexpr int max_depth = 40;

using Dense = Eigen::MatrixXd;
using Rows = Eigen::Matrix<double, 6, Eigen::Dynamic>;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// out = the first @p k rows of a · b (value; + ∂u, ∂v; + second derivatives), the
/// other rows 0: derivatives nobody asked for cost nothing.
/// The row counts are fixed per case: Eigen unrolls a product whose row count it knows (a dynamic
/// one, `a.topRows(k)`, runs a generic coefficient loop, half a tuning run's time).
template <class A, class B>
void multiply_rows(const A& a, const B& b, int k, Rows& out) {
    out.resize(6, b.cols());
    switch (k) {
    case 6:
        out.noalias() = a.lazyProduct(b);
        return;
    case 3:
        out.template topRows<3>().noalias() = a.template topRows<3>().lazyProduct(b);
        out.template bottomRows<3>().setZero();
        return;
    default:
        out.topRows(k).noalias() = a.topRows(k).lazyProduct(b);
        out.bottomRows(6 - k).setZero();
    }
}

/// The basis of a regular patch at (s, t), as ptex derivative rows, times @p M (first
/// @p k rows; fixed-size basis: no allocation per point).
template <class Matrix>
void patch_rows_times(bool quad, const Eigen::Vector2d& st, const Eigen::Matrix2d& J, const Matrix& M, int k,
                      Rows& out) {
    if (quad) {
        Eigen::Matrix<double, 6, 16> b;
        Eigen::Matrix<double, 6, 16> r;
        cubic_bspline_patch_weights(st.x(), st.y(), b);
        to_ptex<16>(b, J, r);
        multiply_rows(r, M, k, out);
    } else {
        Eigen::Matrix<double, 6, 12> b;
        Eigen::Matrix<double, 6, 12> r;
        quartic_box_spline_patch_weights(st.x(), st.y(), b, k);
        to_ptex<12>(b, J, r);
        multiply_rows(r, M, k, out);
    }
}

/// The basis of a regular patch at (s, t), as ptex derivative rows.
void patch_rows(bool quad, const Eigen::Vector2d& st, const Eigen::Matrix2d& J, Rows& out) {
    if (quad) {
        Eigen::Matrix<double, 6, 16> b;
        cubic_bspline_patch_weights(st.x(), st.y(), b);
        to_ptex<16>(b, J, out);
    } else {
        Eigen::Matrix<double, 6, 12> b;
        quartic_box_spline_patch_weights(st.x(), st.y(), b);
        to_ptex<12>(b, J, out);
    }
}

/// Limit rows over x, y, z (LimitPoint::d).
using Values = Eigen::Matrix<double, 6, 3>;
/// Points of a local copy, on the stack: the positions path (LimitPoint) takes supports of at
/// most 64 control points (valences up to 28 around a Catmull–Clark vertex) and leaves larger
/// ones to the weights.
constexpr Index max_local_points = 64;
using LocalPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, max_local_points, 3>;
/// A regular patch's 16 (bicubic) or 12 (quartic box spline) control points.
using PatchPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::ColMajor, 16, 3>;

/// out = A · P for a dense A (n × m, column-major) and points P (m × 3), as m column updates of
/// out: A is read once, contiguously, and every update is vectorised over n (Eigen's lazy
/// product would walk A's rows, strided, once per column of P).
template <class Out, class In>
void times_points(const Dense& A, const In& P, Out& out) {
    out.setZero(A.rows(), 3);
    for (Eigen::Index k = 0; k < A.cols(); ++k) {
        const auto column = A.col(k);
        out.col(0) += column * P(k, 0);
        out.col(1) += column * P(k, 1);
        out.col(2) += column * P(k, 2);
    }
}

/// out = the first @p k rows (value, derivatives) of the regular patch with points @p P (16 or 12
/// rows) at (s, t), in ptex derivatives; the other rows 0. The basis is applied to P in patch
/// coordinates and the 6 × 3 result mapped to ptex (to_ptex is linear in the columns): the
/// chain rule on 3 columns instead of 16. The products are lazy: 6 × 16 · 16 × 3 is above Eigen's
/// threshold for fixed-size coefficient products, and its general product (packing both sides
/// for a blocked kernel) took a quarter of a warm evaluation.
void patch_values(bool quad, const Eigen::Vector2d& st, const Eigen::Matrix2d& J, const PatchPoints& P, int k,
                  Values& out) {
    Values patch;
    if (quad) {
        Eigen::Matrix<double, 6, 16> b;
        cubic_bspline_patch_weights(st.x(), st.y(), b);
        patch.noalias() = b.lazyProduct(P.topRows<16>());
    } else {  // the points contracted with the monomials first: half the arithmetic of the weights
        const Eigen::Matrix<double, 12, 3> points = P.topRows<12>();
        quartic_box_spline_patch_values(st.x(), st.y(), points, patch, k);
    }
    to_ptex<3>(patch, J, out);
    out.bottomRows(6 - k).setZero();
}

/// Dense patch_size × num_local matrix of a regular patch's points.
Dense patch_matrix(const detail::RegularPatch& patch, Index num_local) {
    Dense G = Dense::Zero(patch.size, num_local);
    for (int i = 0; i < patch.size; ++i) {
        const auto& p = patch.points[at(i)];
        for (int k = 0; k < p.size; ++k) {
            G(i, p.vertex[at(k)]) += p.weight[at(k)];
        }
    }
    return G;
}

struct Node;
struct Template;

/// A self-similar local configuration (see the file comment), shared by all nodes
/// whose canonical one-ring has this signature.
struct StationaryClass {
    /// tables[q][0] = G_q · M_q, tables[q][n] = G_q · M_q · R^n (n >= 1; patch_size × K) when
    /// child q is regular; q = 0 unused. R = A − 1ℓᵀ is A without its dominant part
    /// (A^n = 1ℓᵀ + R^n), so derivatives never cancel the constant part (Stam's reason for
    /// working in the eigenbasis: here the same effect without complex eigenvectors).
    std::vector<std::vector<Dense>> tables;
    /// Child q when it is not regular (a Loop middle triangle touching a boundary
    /// corner, say): a subtree whose W is M_q, so it yields rows over the K local vertices.
    std::vector<Node*> subtrees;
    /// node coordinates = child_map(q) ∘ patch frame of child q (regular children).
    std::vector<Affine> patch_frames;
    /// R^(2^j), for the subtrees.
    std::vector<Dense> powers;
    /// The limit position mask of the corner vertex (dominant left eigenvector of A).
    Eigen::RowVectorXd limit_row;
};

/// Child q of a Refine template: its template and the rows M_q of the local step.
struct TemplateChild {
    const Template* child = nullptr;
    Dense M;                    ///< #child local × #local
    std::vector<Index> source;  ///< #child local: the local vertex of the refined copy it copies
};

/// Everything about a canonical one-ring that does not depend on the face it came
/// from: shared by all faces with the same signature (most irregular faces of a
/// mesh share a handful of templates), so its topology work is done once.
struct Template {
    enum class Kind { Regular, Stationary, Refine };
    Kind kind = Kind::Refine;
    Index num_local = 0;
    Dense G;             ///< Regular: patch points over local vertices
    Affine patch_frame;  ///< Regular: node coordinates = patch_frame(patch coordinates)
    std::shared_ptr<const StationaryClass> stationary;
    detail::PatchMesh mesh;          ///< Refine: the copy, refined below
    std::unique_ptr<Level> refined;  ///< Refine: the copy subdivided once
    std::vector<Index> control;      ///< control vertices of the copy that made it (per-vertex weights)
    std::array<std::atomic<TemplateChild*>, 4> children{};
};

/// A regular node inside a stationary class's subtree, with its rows carried n levels towards the
/// class's corner: level[n] = GW · R^n (built on first use, up to the deepest n asked for).
struct SubtreeTables {
    std::array<std::atomic<const Dense*>, max_stationary_levels + 1> level{};
    std::vector<std::unique_ptr<Dense>> owned;  ///< level[1..]; guarded by LimitBasis::Impl::mutex
};

/// A template placed on the control mesh: W maps its local vertices to the root's support.
struct Node {
    const Template* shape = nullptr;
    Dense W;   ///< #local × #support; empty: the identity
    Dense GW;  ///< Regular: G · W (patch points over the support)
    int depth = 0;
    std::vector<Index> control;  ///< per-vertex tuned weights only
    std::array<std::atomic<Node*>, 4> children{};
    /// A regular node of a class's subtree (W over the class's K local vertices): its tables.
    std::atomic<SubtreeTables*> subtree_tables{nullptr};
    std::unique_ptr<SubtreeTables> subtree_tables_storage;  ///< guarded by LimitBasis::Impl::mutex
};

struct Root {
    bool has_limit = true;
    std::vector<Index> support;
    Affine frame;  ///< ptex = frame(node coordinates)
    Node* node = nullptr;
};

/// Where a point of a stationary node lies: n levels towards its extraordinary corner, in the
/// regular-or-subtree child q of that level.
struct StationaryStep {
    int n = 0;
    int q = 0;
    bool here = false;  ///< at the extraordinary vertex itself (within 2^-60)
    Eigen::Vector2d p;  ///< in the coordinates of the level-n node
    Affine scaled;      ///< ptex = scaled(level-n node coordinates)
};

/// A walk that passes from one stationary class's subtree into another class and on, as at a
/// boundary corner next to an extraordinary vertex, takes a step or two; one that goes on for
/// max_depth hops is a cycle that would only end when the stack overflows (the constructor refuses
/// the one input known to make one: Loop's valence-2 vertices). @throws NumericalError
void check_hops(int hops) {
    LIMSURF_CHECK(hops < max_depth, NumericalError, "limit evaluation: the local subdivision passed between ",
                  "extraordinary vertices ", max_depth, " times without reaching a regular patch");
}

/// The rows of per-vertex data @p X for @p vertices (a patch's support). @throws InputError for a
/// vertex without a row
Eigen::MatrixXd gather_rows(const std::vector<Index>& vertices, const Eigen::MatrixXd& X) {
    for (const Index v : vertices) {
        LIMSURF_CHECK(v >= 0 && v < X.rows(), InputError, "limit patch: vertex ", v,
                      " of the support has no row in data of ", X.rows(), " rows");
    }
    Eigen::MatrixXd local(static_cast<Index>(vertices.size()), X.cols());
    for (Index j = 0; j < X.cols(); ++j) {  // a column at a time: X is stored by columns
        const double* column = X.col(j).data();
        double* to = local.col(j).data();
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            to[i] = column[vertices[i]];
        }
    }
    return local;
}

/// The first A.rows() rows of @p out = A · X, a column at a time: a patch's data have a few columns
/// (three coordinates, four fields), where a general matrix product packs all of A for each call
/// (as long as the product itself in `limsurf tune`).
void times_columns(const Eigen::MatrixXd& A, const Eigen::MatrixXd& X, Eigen::MatrixXd& out) {
    for (Index j = 0; j < X.cols(); ++j) {
        out.col(j).head(A.rows()).noalias() = A * X.col(j);
    }
}

}  // namespace

struct LimitBasis::Impl {
    Topology topology;
    SchemeKind scheme = SchemeKind::CatmullClark;
    SchemeOptions options;
    TunedWeights weights;
    bool quad = true;
    bool use_tables = true;
    bool per_vertex_weights = false;
    std::vector<Index> first_ptex;  // #F + 1
    std::vector<PtexFace> ptex;
    std::unique_ptr<detail::DooSabinLimit> doo_sabin;  // Doo–Sabin: its own evaluator (dual patches)
    std::unique_ptr<detail::C2g0Limit> c2g0;           // C2g0: its own evaluator (docs/c2g0_limit.md)
    /// Regular ptex faces whose patch points are plain control vertices (most faces of a
    /// typical mesh), found in the constructor and stored flat: evaluating them is one
    /// look-up, no tree. fast_index[p] is the entry of ptex face p, or -1.
    struct FastPatch {
        std::array<Index, 16> points{};
        int rotation = 0;
    };
    std::vector<Index> fast_index;
    std::vector<FastPatch> fast;
    void find_fast_patches();

    // Guards the owners and caches below; built items are published through atomics and
    // read without it. Recursive: building a root descends into a child.
    mutable std::recursive_mutex mutex;
    mutable std::vector<std::unique_ptr<Node>> nodes;
    mutable std::vector<std::unique_ptr<TemplateChild>> template_children;
    mutable std::unordered_map<std::string, std::unique_ptr<Template>> templates;
    mutable std::unordered_map<std::string, std::shared_ptr<const StationaryClass>> classes;
    mutable std::vector<std::atomic<Root*>> roots;
    mutable std::vector<std::unique_ptr<Root>> root_storage;

    [[nodiscard]] bool regular_patch(const Topology& t, Index f, detail::RegularPatch& out) const {
        return quad ? detail::catmull_clark_regular_patch(t, f, options.boundary, out)
                    : detail::loop_regular_patch(t, f, options.boundary, out);
    }

    /// Control vertex c carries own β or γ ≠ 1 where they act (a smooth vertex): the edge and face
    /// points around it differ from Catmull–Clark's, so no patch whose support holds it is a plain
    /// B-spline, and a local copy must apply them even where c is the copy's outer vertex.
    [[nodiscard]] bool wide_weights(Index c) const {
        if (!per_vertex_weights || c == invalid_index || topology.is_boundary_vertex(c) ||
            topology.vertex_sharpness(c) != 0.0) {
            return false;
        }
        const VertexRuleWeights w = weights.at(c, static_cast<int>(topology.valence(c)));
        return w.beta != 1.0 || w.gamma != 1.0;
    }
    /// True when none of @p control is wide_weights().
    [[nodiscard]] bool plain_support(const std::vector<Index>& control) const {
        return std::none_of(control.begin(), control.end(), [&](Index c) { return wide_weights(c); });
    }

    /// One refinement step of a one-ring copy whose local vertex i copies control vertex control[i].
    [[nodiscard]] Level refine_once(const Topology& t, const std::vector<Index>& control) const;
    /// The canonical signature, with the tuned weights of each local vertex when they vary per vertex.
    [[nodiscard]] std::string signature(const detail::PatchArrays& arrays, const std::vector<Index>& control) const;
    /// Control vertices of a child copy: a child of parent vertex s keeps s's control vertex.
    [[nodiscard]] static std::vector<Index> child_control(const std::vector<Index>& parent_control,
                                                          const std::vector<Index>& child_source);

    const Root& root(Index p) const;
    std::unique_ptr<Root> build_root(Index p) const;
    /// The template of a copy (built on first sight). @pre mutex held
    const Template* shape_of(detail::PatchArrays arrays, const std::vector<Index>& control) const;
    /// A node of @p shape with weights W. @pre mutex held
    Node* make_node(const Template* shape, Dense W, int depth, std::vector<Index> control) const;
    std::shared_ptr<const StationaryClass> make_class(const Level& refined, const Dense& A,
                                                      const std::vector<Index>& control) const;
    const TemplateChild& template_child(const Template& shape, int q) const;
    /// template_child, taking the mutex when the child is not built yet.
    const TemplateChild& template_step(const Template& shape, int q) const;
    Node* child(Node& node, int q) const;
    /// @param rows_needed 1, 3 or 6 (value; first; second derivatives)
    void evaluate(const SurfacePoint& point, int rows_needed, LimitWeights& out) const;
    /// The root of ptex face @p face, which must have a limit surface. @throws InputError
    const Root& root_with_limit(Index face) const;
    /// LimitBasis::patch.
    bool patch(const SurfacePoint& point, LimitPatch& out) const;
    /// Data for node_patch to contract instead of giving the points: X has rows over the columns
    /// of node->W; `data` receives the patch's points times X and, last, the offset times X.
    struct PatchData {
        const Dense& X;
        Dense& data;
    };
    /// The patch of the node that holds @p p (node coordinates; ptex = frame(p)): out's points and
    /// offset over the columns of node->W, its origin and axes — or, given @p want, their data
    /// (out's points and offset then unspecified). False at an extraordinary vertex.
    bool node_patch(Node* node, Eigen::Vector2d p, Affine frame, LimitPatch& out, const PatchData* want = nullptr,
                    int hops = 0) const;
    /// LimitBasis::patch_data.
    bool patch_data(const SurfacePoint& point, const Eigen::MatrixXd& X, LimitPatch& out, Dense& data) const;
    /// Rows over the columns of node->W (the root's support, or a class's local vertices).
    /// @p hops: how many times the walk has passed from a class's subtree into another class
    /// (check_hops bounds it).
    void descend(Node* node, Eigen::Vector2d p, Affine frame, int rows_needed, bool& at_vertex, Rows& rows,
                 int hops = 0) const;
    void stationary_rows(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame, int rows_needed,
                         bool& at_vertex, Rows& rows, int hops = 0) const;
    /// The regular patch that holds a point of a stationary class, n levels deep (StationaryStep):
    /// its rows over the class's local vertices (`table`: the class's own, or a subtree patch's
    /// G·W·R^n), its patch frame, and the point and ptex map in the patch's node coordinates.
    /// `table` is null where a subtree meets another stationary class: `leaf` is that node.
    struct StationaryPatch {
        const Dense* table = nullptr;
        Affine patch_frame;
        Eigen::Vector2d p;
        Affine frame;
        Node* leaf = nullptr;
    };
    [[nodiscard]] StationaryPatch stationary_patch(const StationaryClass& cls, const StationaryStep& step) const;
    /// The node of subtree @p root that holds @p p (moved into its coordinates, with @p frame).
    Node* subtree_leaf(Node* root, Eigen::Vector2d& p, Affine& frame) const;
    /// GW · R^n of a regular subtree node @p leaf of @p cls (n >= 1), built on first use.
    const Dense& subtree_table(const StationaryClass& cls, Node& leaf, int n) const;
    /// The positions path (LimitBasis::evaluate(X, point, LimitPoint&)); X is Points or InterleavedPoints.
    template <class Matrix>
    void evaluate(const Matrix& X, const SurfacePoint& point, int rows_needed, LimitPoint& out) const;
    /// descend() with the node's local points @p X (its columns' control points) contracted first;
    /// false, with @p out undefined, where the weights path must be taken (a stationary class's
    /// subtree, more than max_local_points local points).
    bool descend_values(Node* node, Eigen::Vector2d p, Affine frame, int rows_needed, bool& at_vertex,
                        const LocalPoints& X, Values& out) const;
    bool stationary_values(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame, int rows_needed,
                           bool& at_vertex, const LocalPoints& X, Values& out) const;
};

namespace {

/// The corner of face f at which a single irregular vertex sits, else 0.
int start_corner(const Topology& t, Index f, bool quad) {
    const auto v = t.face_vertices(f);
    int found = -1;
    for (std::size_t k = 0; k < v.size(); ++k) {
        const Index x = v[k];
        const bool regular = !t.is_boundary_vertex(x) && t.valence(x) == (quad ? 4 : 6) && t.vertex_sharpness(x) == 0.0;
        if (!regular) {
            if (found >= 0) {
                return 0;
            }
            found = static_cast<int>(k);
        }
    }
    return std::max(found, 0);
}

}  // namespace

Level LimitBasis::Impl::refine_once(const Topology& t, const std::vector<Index>& control) const {
    if (!per_vertex_weights) {
        return refine(t, scheme, options, weights);
    }
    // Per-vertex weights name control vertices: restate them for the local numbering.
    TunedWeights local;
    std::vector<bool> forced(at(t.num_vertices()), false);
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const int valence = t.valence(v);
        const Index c = control[at(v)];
        if (valence >= 3) {
            local.set_valence(valence, weights.at(invalid_index, valence));
            if (c != invalid_index) {
                local.set_vertex(v, weights.at(c, valence));
            }
        }
        if (quad && c != invalid_index && t.is_boundary_vertex(v) && wide_weights(c)) {
            forced[at(v)] = true;  // an outer vertex of the copy, smooth in the mesh
            local.set_vertex(v, weights.at(c, static_cast<int>(topology.valence(c))));
        }
    }
    if (quad) {
        return detail::refine_catmull_clark_forced(t, options, local, forced);
    }
    return refine(t, scheme, options, local);
}

std::string LimitBasis::Impl::signature(const detail::PatchArrays& arrays, const std::vector<Index>& control) const {
    std::string bytes = detail::patch_signature(arrays);
    if (per_vertex_weights) {
        // A vertex's own weights (valence 0 never has a valence entry, so a difference
        // from the default means a per-vertex override).
        const VertexRuleWeights none = weights.at(invalid_index, 0);
        for (const Index c : control) {
            const VertexRuleWeights w = weights.at(c, 0);
            const bool own = w.alpha != none.alpha || w.beta != none.beta || w.gamma != none.gamma;
            const double values[4] = {own ? w.alpha : -1.0, w.beta, w.gamma, wide_weights(c) ? 1.0 : 0.0};
            bytes.append(reinterpret_cast<const char*>(values), sizeof values);
        }
    }
    return bytes;
}

std::vector<Index> LimitBasis::Impl::child_control(const std::vector<Index>& parent_control,
                                                   const std::vector<Index>& child_source) {
    if (parent_control.empty()) {
        return {};
    }
    // Child vertex s < #parent vertices is the child of parent vertex s (Catmull–Clark, Loop).
    std::vector<Index> control(child_source.size(), invalid_index);
    for (std::size_t i = 0; i < child_source.size(); ++i) {
        if (at(child_source[i]) < parent_control.size()) {
            control[i] = parent_control[at(child_source[i])];
        }
    }
    return control;
}

std::unique_ptr<Root> LimitBasis::Impl::build_root(Index p) const {
    auto root = std::make_unique<Root>();
    const PtexFace pf = ptex[at(p)];
    const Index f = pf.control_face;
    const auto corners = topology.face_vertices(f);
    root->has_limit = !topology.is_hole(f);
    if (options.boundary == BoundaryInterpolation::None) {
        // OpenSubdiv's rule (Far::TopologyRefinerFactory, boundary faces made holes): a face has no
        // limit surface when one of its corners is a boundary vertex with a boundary edge that is
        // not infinitely sharp; infinitely sharp boundary edges keep their faces (boundary patches).
        for (Index v : corners) {
            if (!topology.is_boundary_vertex(v)) {
                continue;
            }
            for (const Index e : topology.vertex_edges(v)) {
                if (topology.is_boundary_edge(e) && topology.edge_sharpness(e) < infinite_sharpness) {
                    root->has_limit = false;
                }
            }
        }
    }
    if (!root->has_limit) {
        return root;
    }
    if (pf.corner < 0) {
        detail::RegularPatch patch;
        bool plain = regular_patch(topology, f, patch);
        for (int i = 0; plain && i < patch.size; ++i) {
            for (int k = 0; k < patch.points[at(i)].size; ++k) {
                plain = plain && !wide_weights(patch.points[at(i)].vertex[at(k)]);
            }
        }
        if (plain) {
            // A template-free node read straight off the control mesh (regular patches with
            // phantom points; those without are the flat fast patches of find_fast_patches).
            auto node = std::make_unique<Node>();
            for (int i = 0; i < patch.size; ++i) {
                auto& point = patch.points[at(i)];
                for (int k = 0; k < point.size; ++k) {
                    const Index v = point.vertex[at(k)];
                    auto it = std::find(root->support.begin(), root->support.end(), v);
                    if (it == root->support.end()) {
                        root->support.push_back(v);
                        it = root->support.end() - 1;
                    }
                    point.vertex[at(k)] = static_cast<Index>(it - root->support.begin());
                }
            }
            node->GW = patch_matrix(patch, static_cast<Index>(root->support.size()));
            root->frame = rotation(quad, patch.rotation);
            nodes.push_back(std::move(node));
            root->node = nodes.back().get();
            return root;
        }
        const int start = start_corner(topology, f, quad);
        auto arrays = detail::extract_patch_arrays(topology, f, start);
        root->support = arrays.source;
        root->frame = rotation(quad, start);
        std::vector<Index> control = per_vertex_weights ? arrays.source : std::vector<Index>{};
        const Template* shape = shape_of(std::move(arrays), control);
        root->node = make_node(shape, Dense(), 0, std::move(control));
        return root;
    }
    // Sub-face k of an n-gon: child k of the face after one local refinement.
    auto arrays = detail::extract_patch_arrays(topology, f, 0);
    root->support = arrays.source;
    std::vector<Index> control = per_vertex_weights ? arrays.source : std::vector<Index>{};
    const Template* shape = shape_of(std::move(arrays), control);
    LIMSURF_ASSERT(shape->kind == Template::Kind::Refine, "an n-gon's one-ring is refined");
    auto sub = detail::extract_patch_arrays(shape->refined->topology, pf.corner, 0);
    Dense W = dense_rows(shape->refined->S0, sub.source);
    auto sub_control = child_control(control, sub.source);
    const Template* sub_shape = shape_of(std::move(sub), sub_control);
    root->node = make_node(sub_shape, std::move(W), 1, std::move(sub_control));
    return root;
}

const Template* LimitBasis::Impl::shape_of(detail::PatchArrays arrays, const std::vector<Index>& control) const {
    std::string key = signature(arrays, control);
    if (const auto known = templates.find(key); known != templates.end()) {
        return known->second.get();
    }
    auto shape = std::make_unique<Template>();
    shape->num_local = static_cast<Index>(arrays.source.size());
    shape->control = control;
    shape->mesh = detail::make_patch_mesh(std::move(arrays));
    detail::RegularPatch patch;
    if (regular_patch(shape->mesh.topology, 0, patch) && plain_support(control)) {
        shape->kind = Template::Kind::Regular;
        shape->G = patch_matrix(patch, shape->num_local);
        shape->patch_frame = rotation(quad, patch.rotation);
    } else if (const auto known = use_tables ? classes.find(key) : classes.end(); known != classes.end()) {
        shape->kind = Template::Kind::Stationary;
        shape->stationary = known->second;
    } else {
        shape->refined = std::make_unique<Level>(refine_once(shape->mesh.topology, control));
        auto corner = detail::extract_patch_arrays(shape->refined->topology, 0, 0);
        const auto corner_control = child_control(control, corner.source);
        if (use_tables && signature(corner, corner_control) == key) {
            const Dense A = dense_rows(shape->refined->S0, corner.source);
            auto cls = make_class(*shape->refined, A, control);
            classes.emplace(key, cls);
            shape->kind = Template::Kind::Stationary;
            shape->stationary = std::move(cls);
        }
    }
    return templates.emplace(std::move(key), std::move(shape)).first->second.get();
}

Node* LimitBasis::Impl::make_node(const Template* shape, Dense W, int depth, std::vector<Index> control) const {
    const int limit = use_tables ? max_depth : max_stationary_levels;
    LIMSURF_CHECK(depth <= limit, NumericalError, "limit evaluation: local subdivision did not reach a regular or ",
                  "self-similar patch after ", limit, " levels (a point too close to an extraordinary vertex for ",
                  "LimitEvaluation::Subdivision?)");
    auto node = std::make_unique<Node>();
    node->shape = shape;
    node->depth = depth;
    node->control = std::move(control);
    if (shape->kind == Template::Kind::Regular) {
        node->GW = W.size() == 0 ? shape->G : Dense(shape->G * W);
    } else {
        node->W = std::move(W);
    }
    nodes.push_back(std::move(node));
    return nodes.back().get();
}

std::shared_ptr<const StationaryClass> LimitBasis::Impl::make_class(const Level& refined, const Dense& A,
                                                                    const std::vector<Index>& control) const {
    auto cls = std::make_shared<StationaryClass>();
    constexpr int children = 4;
    cls->tables.resize(children);
    cls->subtrees.resize(children, nullptr);
    cls->patch_frames.resize(children);
    for (int q = 1; q < children; ++q) {
        auto arrays = detail::extract_patch_arrays(refined.topology, q, 0);
        Dense M = dense_rows(refined.S0, arrays.source);
        auto sub_control = child_control(control, arrays.source);
        const Template* shape = shape_of(std::move(arrays), sub_control);
        if (shape->kind != Template::Kind::Regular) {
            cls->subtrees[at(q)] = make_node(shape, std::move(M), 1, std::move(sub_control));
            continue;
        }
        cls->patch_frames[at(q)] = child_map(quad, q).then(shape->patch_frame);
        cls->tables[at(q)].push_back(shape->G * M);
    }
    // Dominant left eigenvector ℓ (ℓᵀA = ℓᵀ, ℓ·1 = 1): any row of A^(2^8).
    Dense power = A;
    for (int j = 0; j < 8; ++j) {
        power = power * power;
    }
    cls->limit_row = power.row(0) / power.row(0).sum();
    const Dense R = A - Eigen::VectorXd::Ones(A.rows()) * cls->limit_row;
    for (auto& table : cls->tables) {
        if (table.empty()) {
            continue;
        }
        table.reserve(max_stationary_levels + 1);
        table.push_back(table.front() * R);
        for (int n = 2; n <= max_stationary_levels; ++n) {
            table.push_back(table.back() * R);
        }
    }
    cls->powers.push_back(R);
    for (int j = 1; j < 8; ++j) {
        cls->powers.push_back(cls->powers.back() * cls->powers.back());
    }
    return cls;
}

const TemplateChild& LimitBasis::Impl::template_child(const Template& shape, int q) const {
    if (const TemplateChild* known = shape.children[at(q)].load(std::memory_order_acquire)) {
        return *known;
    }
    auto made = std::make_unique<TemplateChild>();
    auto arrays = detail::extract_patch_arrays(shape.refined->topology, q, 0);
    made->M = dense_rows(shape.refined->S0, arrays.source);
    made->source = arrays.source;
    made->child = shape_of(std::move(arrays), child_control(shape.control, made->source));
    template_children.push_back(std::move(made));
    const_cast<Template&>(shape).children[at(q)].store(template_children.back().get(), std::memory_order_release);
    return *template_children.back();
}

Node* LimitBasis::Impl::child(Node& node, int q) const {
    if (Node* existing = node.children[at(q)].load(std::memory_order_acquire)) {
        return existing;
    }
    const std::lock_guard lock(mutex);
    if (Node* existing = node.children[at(q)].load(std::memory_order_relaxed)) {
        return existing;
    }
    const TemplateChild& step = template_child(*node.shape, q);
    Dense W = node.W.size() == 0 ? step.M : Dense(step.M * node.W);
    Node* made = make_node(step.child, std::move(W), node.depth + 1, child_control(node.control, step.source));
    node.children[at(q)].store(made, std::memory_order_release);
    return made;
}

const Root& LimitBasis::Impl::root(Index p) const {
    if (Root* existing = roots[at(p)].load(std::memory_order_acquire)) {
        return *existing;
    }
    const std::lock_guard lock(mutex);
    Root* existing = roots[at(p)].load(std::memory_order_relaxed);
    if (existing == nullptr) {
        root_storage.push_back(build_root(p));
        existing = root_storage.back().get();
        roots[at(p)].store(existing, std::memory_order_release);
    }
    return *existing;
}

namespace {

StationaryStep stationary_step(bool quad, Eigen::Vector2d p, const Affine& frame) {
    StationaryStep step;
    while (step.n < max_stationary_levels && in_corner_child(quad, p)) {
        p *= 2.0;
        ++step.n;
    }
    step.here = in_corner_child(quad, p);
    if (step.here) {
        // At the extraordinary vertex itself: the exact limit position, and the
        // derivatives 2^-61 away in ptex units along the first edge (they vanish or
        // diverge at the vertex itself), whatever the depth of this node.
        const int node_depth = static_cast<int>(std::lround(-0.5 * std::log2(std::abs(frame.axes.determinant()))));
        step.n = std::clamp(max_stationary_levels - node_depth, 0, max_stationary_levels);
        p = {0.5, 0.0};
    }
    step.p = p;
    step.q = child_containing(quad, p);
    step.scaled = frame;
    step.scaled.axes *= std::ldexp(1.0, -step.n);
    return step;
}

}  // namespace

LimitBasis::Impl::StationaryPatch LimitBasis::Impl::stationary_patch(const StationaryClass& cls,
                                                                     const StationaryStep& step) const {
    StationaryPatch out;
    if (cls.subtrees[at(step.q)] == nullptr) {
        out.table = &cls.tables[at(step.q)][at(step.n)];
        out.patch_frame = cls.patch_frames[at(step.q)];
        out.p = step.p;
        out.frame = step.scaled;
        return out;
    }
    // A subtree (own tuned weights keep the corner's children irregular one level more): the
    // regular patch holding the point, with its rows carried n levels by its own tables.
    const Affine map = child_map(quad, step.q);
    out.p = map.to_child(step.p);
    out.frame = step.scaled.then(map);
    out.leaf = subtree_leaf(cls.subtrees[at(step.q)], out.p, out.frame);
    if (out.leaf->shape->kind == Template::Kind::Regular) {
        out.patch_frame = out.leaf->shape->patch_frame;
        out.table = step.n == 0 ? &out.leaf->GW : &subtree_table(cls, *out.leaf, step.n);
    }
    return out;
}

namespace {

/// M = M · R^n of a stationary class, through the powers R^(2^j) of the set bits of n.
template <class Matrix>
void times_power(const StationaryClass& cls, int n, Matrix& M) {
    for (std::size_t j = 0; n != 0; ++j, n >>= 1) {
        if ((n & 1) != 0) {
            M = M * cls.powers[j];
        }
    }
}

}  // namespace

void LimitBasis::Impl::stationary_rows(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame,
                                       int rows_needed, bool& at_vertex, Rows& rows, int hops) const {
    const StationaryStep step = stationary_step(quad, p, frame);
    at_vertex = at_vertex || step.here;
    const StationaryPatch patch = stationary_patch(cls, step);
    if (patch.table != nullptr) {
        patch_rows_times(quad, patch.patch_frame.to_child(patch.p), patch.frame.then(patch.patch_frame).axes,
                         *patch.table, rows_needed, rows);
        if (step.n > 0) {
            rows.row(0) += cls.limit_row;  // the value basis sums to 1: A^n = 1ℓᵀ + R^n
        }
    } else {
        // A subtree that meets another stationary class: its rows, then the powers of R.
        check_hops(hops);
        descend(patch.leaf, patch.p, patch.frame, rows_needed, at_vertex, rows, hops + 1);
        if (step.n > 0) {
            // A^n = 1ℓᵀ + R^n; derivative rows sum to zero, so only the value row keeps 1ℓᵀ
            // (adding their rounding-level sums back would undo what R^n removes).
            const double value_sum = rows.row(0).sum();
            times_power(cls, step.n, rows);
            rows.row(0) += value_sum * cls.limit_row;
        }
    }
    if (step.here) {
        rows.row(0) = cls.limit_row;
    }
}

Node* LimitBasis::Impl::subtree_leaf(Node* root, Eigen::Vector2d& p, Affine& frame) const {
    Node* node = root;
    while (node->shape->kind == Template::Kind::Refine) {
        const int q = child_containing(quad, p);
        const Affine map = child_map(quad, q);
        p = map.to_child(p);
        frame = frame.then(map);
        node = child(*node, q);
    }
    return node;
}

const Dense& LimitBasis::Impl::subtree_table(const StationaryClass& cls, Node& leaf, int n) const {
    if (const SubtreeTables* known = leaf.subtree_tables.load(std::memory_order_acquire)) {
        if (const Dense* table = known->level[at(n)].load(std::memory_order_acquire)) {
            return *table;
        }
    }
    const std::lock_guard lock(mutex);
    if (!leaf.subtree_tables_storage) {
        leaf.subtree_tables_storage = std::make_unique<SubtreeTables>();
        leaf.subtree_tables.store(leaf.subtree_tables_storage.get(), std::memory_order_release);
    }
    SubtreeTables& tables = *leaf.subtree_tables_storage;
    while (static_cast<int>(tables.owned.size()) < n) {  // level k = level k−1 · R, as the class's tables
        const Dense& previous = tables.owned.empty() ? leaf.GW : *tables.owned.back();
        tables.owned.push_back(std::make_unique<Dense>(previous * cls.powers.front()));
        tables.level[tables.owned.size()].store(tables.owned.back().get(), std::memory_order_release);
    }
    return *tables.level[at(n)].load(std::memory_order_relaxed);
}

bool LimitBasis::Impl::stationary_values(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame,
                                         int rows_needed, bool& at_vertex, const LocalPoints& X, Values& out) const {
    const StationaryStep step = stationary_step(quad, p, frame);
    const StationaryPatch patch = stationary_patch(cls, step);
    if (patch.table == nullptr) {
        return false;  // a subtree that meets another stationary class: the weights path
    }
    at_vertex = at_vertex || step.here;
    PatchPoints P;
    times_points(*patch.table, X, P);
    patch_values(quad, patch.patch_frame.to_child(patch.p), patch.frame.then(patch.patch_frame).axes, P, rows_needed,
                 out);
    if (step.here) {
        out.row(0).noalias() = cls.limit_row.lazyProduct(X);
    } else if (step.n > 0) {
        out.row(0).noalias() += cls.limit_row.lazyProduct(X);  // A^n = 1ℓᵀ + R^n
    }
    return true;
}

void LimitBasis::Impl::descend(Node* node, Eigen::Vector2d p, Affine frame, int rows_needed, bool& at_vertex,
                               Rows& rows, int hops) const {
    while (node->shape != nullptr && node->shape->kind == Template::Kind::Refine) {
        const int q = child_containing(quad, p);
        const Affine map = child_map(quad, q);
        p = map.to_child(p);
        frame = frame.then(map);
        node = child(*node, q);
    }
    if (node->shape == nullptr || node->shape->kind == Template::Kind::Regular) {
        const Affine& patch_frame = node->shape == nullptr ? Affine{} : node->shape->patch_frame;
        const Affine patch = frame.then(patch_frame);
        patch_rows_times(quad, patch_frame.to_child(p), patch.axes, node->GW, rows_needed, rows);
        return;
    }
    Rows local;
    stationary_rows(*node->shape->stationary, p, frame, rows_needed, at_vertex, node->W.size() == 0 ? rows : local,
                    hops);
    if (node->W.size() != 0) {
        multiply_rows(local, node->W, rows_needed, rows);
    }
}

bool LimitBasis::Impl::descend_values(Node* node, Eigen::Vector2d p, Affine frame, int rows_needed, bool& at_vertex,
                                      const LocalPoints& X, Values& out) const {
    if (node->shape == nullptr) {  // a root's template-free regular patch: GW over the support
        PatchPoints P;
        times_points(node->GW, X, P);
        patch_values(quad, p, frame.axes, P, rows_needed, out);
        return true;
    }
    // Down the templates, not the nodes: the local points are carried through each level's
    // small shared matrix M_q (in cache: most faces share a few templates), where the nodes'
    // own products G·W (16 × #support per node, a cold read for every point) would be read.
    std::array<LocalPoints, 2> buffers;
    const LocalPoints* local = &X;
    if (node->W.size() != 0) {  // an n-gon's sub-face: its root node maps the support first
        if (node->W.rows() > max_local_points) {
            return false;
        }
        times_points(node->W, X, buffers[0]);
        local = &buffers[0];
    }
    const Template* shape = node->shape;
    int depth = node->depth;
    const int max_levels = use_tables ? max_depth : max_stationary_levels;
    while (shape->kind == Template::Kind::Refine) {
        if (++depth > max_levels) {
            return false;  // the weights path raises make_node's error
        }
        const int q = child_containing(quad, p);
        const Affine map = child_map(quad, q);
        p = map.to_child(p);
        frame = frame.then(map);
        const TemplateChild& step = template_step(*shape, q);
        if (step.M.rows() > max_local_points) {
            return false;
        }
        LocalPoints& next = local == &buffers[0] ? buffers[1] : buffers[0];
        times_points(step.M, *local, next);
        local = &next;
        shape = step.child;
    }
    if (shape->kind == Template::Kind::Regular) {
        const Affine patch = frame.then(shape->patch_frame);
        PatchPoints P;
        times_points(shape->G, *local, P);
        patch_values(quad, shape->patch_frame.to_child(p), patch.axes, P, rows_needed, out);
        return true;
    }
    return stationary_values(*shape->stationary, p, frame, rows_needed, at_vertex, *local, out);
}

const TemplateChild& LimitBasis::Impl::template_step(const Template& shape, int q) const {
    if (const TemplateChild* known = shape.children[at(q)].load(std::memory_order_acquire)) {
        return *known;
    }
    const std::lock_guard lock(mutex);
    return template_child(shape, q);
}

void LimitBasis::Impl::find_fast_patches() {
    fast_index.assign(ptex.size(), -1);
    fast.reserve(ptex.size());  // most ptex faces are regular: growing by doubling copied them all again
    detail::RegularPatch patch;
    for (std::size_t p = 0; p < ptex.size(); ++p) {
        const Index f = ptex[p].control_face;
        if (ptex[p].corner >= 0 || topology.is_hole(f) || !regular_patch(topology, f, patch)) {
            continue;
        }
        FastPatch entry;
        entry.rotation = patch.rotation;
        bool plain = true;
        for (int i = 0; i < patch.size && plain; ++i) {
            plain = patch.points[at(i)].size == 1 && patch.points[at(i)].weight[0] == 1.0 &&
                    !wide_weights(patch.points[at(i)].vertex[0]);
            entry.points[at(i)] = patch.points[at(i)].vertex[0];
        }
        if (plain) {  // all corners smooth and interior: never a boundary face
            fast_index[p] = static_cast<Index>(fast.size());
            fast.push_back(entry);
        }
    }
}

void LimitBasis::Impl::evaluate(const SurfacePoint& point, int rows_needed, LimitWeights& out) const {
    if (!fast_index.empty() && fast_index[at(point.face)] >= 0) {
        // A regular patch of plain control vertices: the basis is the weights.
        const FastPatch& entry = fast[at(fast_index[at(point.face)])];
        const int size = quad ? 16 : 12;
        out.vertices.assign(entry.points.begin(), entry.points.begin() + size);
        out.at_extraordinary_vertex = false;
        const Affine frame = rotation(quad, entry.rotation);
        patch_rows(quad, frame.to_child({point.u, point.v}), frame.axes, out.w);
        return;
    }
    if (doo_sabin) {
        out.at_extraordinary_vertex = false;
        doo_sabin->evaluate(point.face, point.u, point.v, out.vertices, out.w);
        return;
    }
    if (c2g0) {
        c2g0->evaluate(point.face, point.u, point.v, rows_needed, out.vertices, out.w, out.at_extraordinary_vertex);
        return;
    }
    const Root& r = root_with_limit(point.face);
    out.vertices = r.support;
    out.at_extraordinary_vertex = false;
    descend(r.node, r.frame.to_child({point.u, point.v}), r.frame, rows_needed, out.at_extraordinary_vertex, out.w);
}

const Root& LimitBasis::Impl::root_with_limit(Index face) const {
    const Root& r = root(face);
    LIMSURF_CHECK(r.has_limit, InputError, "ptex face ", face, " (control face ", ptex[at(face)].control_face,
                  ") has no limit surface (a hole, or a boundary face under boundary interpolation 'none')");
    return r;
}

bool LimitBasis::Impl::patch(const SurfacePoint& point, LimitPatch& out) const {
    out.domain = quad ? ParameterDomain::Quad : ParameterDomain::Triangle;
    if (!fast_index.empty() && fast_index[at(point.face)] >= 0) {
        const FastPatch& entry = fast[at(fast_index[at(point.face)])];
        const int size = out.size();
        out.vertices.assign(entry.points.begin(), entry.points.begin() + size);
        out.points.setIdentity(size, size);
        out.offset.setZero(size);
        const Affine frame = rotation(quad, entry.rotation);
        out.origin = frame.offset;
        out.axes = frame.axes;
        return true;
    }
    if (doo_sabin || c2g0) {
        return false;
    }
    const Root& r = root_with_limit(point.face);
    out.vertices = r.support;
    return node_patch(r.node, r.frame.to_child({point.u, point.v}), r.frame, out);
}

bool LimitBasis::Impl::node_patch(Node* node, Eigen::Vector2d p, Affine frame, LimitPatch& out, const PatchData* want,
                                  int hops) const {
    if (node->shape != nullptr) {
        node = subtree_leaf(node, p, frame);
    }
    const auto set_frame = [&out](const Affine& patch_to_ptex) {
        out.origin = patch_to_ptex.offset;
        out.axes = patch_to_ptex.axes;
    };
    if (want != nullptr) {
        want->data.resize(out.size() + 1, want->X.cols());
    }
    if (node->shape == nullptr || node->shape->kind == Template::Kind::Regular) {
        set_frame(frame.then(node->shape == nullptr ? Affine{} : node->shape->patch_frame));
        if (want != nullptr) {  // the points G·W are already over the support, the offset zero
            times_columns(node->GW, want->X, want->data);
            want->data.bottomRows<1>().setZero();
            return true;
        }
        out.points = node->GW;
        out.offset.setZero(node->GW.cols());
        return true;
    }
    const StationaryClass& cls = *node->shape->stationary;
    const StationaryStep step = stationary_step(quad, p, frame);
    if (step.here) {
        return false;  // the tables end 2^-60 from the vertex: evaluate() takes its limit position
    }
    const StationaryPatch found = stationary_patch(cls, step);
    if (found.table != nullptr) {
        set_frame(found.frame.then(found.patch_frame));
        if (want != nullptr) {
            // table · (W · X) and ℓ · (W · X): W contracted with the data first, the table read in place.
            Dense product;
            if (node->W.size() != 0) {
                product.noalias() = node->W * want->X;
            }
            const Dense& mapped = node->W.size() == 0 ? want->X : product;
            times_columns(*found.table, mapped, want->data);
            if (step.n == 0) {
                want->data.bottomRows<1>().setZero();
            } else {
                want->data.bottomRows<1>().noalias() = cls.limit_row * mapped;
            }
            return true;
        }
        out.points = *found.table;
        out.offset = step.n == 0 ? Eigen::RowVectorXd::Zero(found.table->cols()) : cls.limit_row;
    } else {
        // A subtree that meets another class: its patch over this class's local vertices, carried n
        // levels by R^n as stationary_rows does. Each point is P_i + o with rows of P summing to a
        // common s, and (P + 1o)(1ℓᵀ + R^n) = P R^n + 1(o R^n + (s + Σo) ℓ), s + Σo = 1.
        check_hops(hops);
        if (!node_patch(found.leaf, found.p, found.frame, out, nullptr, hops + 1)) {
            return false;
        }
        if (step.n > 0) {
            times_power(cls, step.n, out.points);
            times_power(cls, step.n, out.offset);
            out.offset += cls.limit_row;
        }
    }
    if (node->W.size() != 0) {  // the node's local vertices mapped to the support
        out.points = out.points * node->W;
        out.offset = out.offset * node->W;
    }
    if (want != nullptr) {
        times_columns(out.points, want->X, want->data);
        want->data.bottomRows<1>().noalias() = out.offset * want->X;
    }
    return true;
}

bool LimitBasis::Impl::patch_data(const SurfacePoint& point, const Eigen::MatrixXd& X, LimitPatch& out,
                                  Dense& data) const {
    if (!fast_index.empty() && fast_index[at(point.face)] >= 0) {  // the points are the identity
        if (!patch(point, out)) {
            return false;
        }
        data = out.control_data(X);
    } else {
        if (doo_sabin || c2g0) {
            return false;
        }
        const Root& r = root_with_limit(point.face);
        out.domain = quad ? ParameterDomain::Quad : ParameterDomain::Triangle;
        out.vertices = r.support;
        const Dense local = gather_rows(out.vertices, X);
        const PatchData want{local, data};
        if (!node_patch(r.node, r.frame.to_child({point.u, point.v}), r.frame, out, &want)) {
            return false;
        }
    }
    out.points.resize(0, 0);
    out.offset.resize(0);
    return true;
}

template <class Matrix>
void LimitBasis::Impl::evaluate(const Matrix& X, const SurfacePoint& point, int rows_needed, LimitPoint& out) const {
    out.at_extraordinary_vertex = false;
    if (!fast_index.empty() && fast_index[at(point.face)] >= 0) {
        const FastPatch& entry = fast[at(fast_index[at(point.face)])];
        const int size = quad ? 16 : 12;
        PatchPoints P(size, 3);
        for (int i = 0; i < size; ++i) {
            P.row(i) = X.row(entry.points[at(i)]);
        }
        const Affine frame = rotation(quad, entry.rotation);
        patch_values(quad, frame.to_child({point.u, point.v}), frame.axes, P, rows_needed, out.d);
        return;
    }
    if (!doo_sabin && !c2g0) {
        const Root& r = root(point.face);
        const auto support = static_cast<Index>(r.support.size());
        if (r.has_limit && support <= max_local_points) {
            LocalPoints local(support, 3);
            for (Index i = 0; i < support; ++i) {
                local.row(i) = X.row(r.support[at(i)]);
            }
            if (descend_values(r.node, r.frame.to_child({point.u, point.v}), r.frame, rows_needed,
                               out.at_extraordinary_vertex, local, out.d)) {
                return;
            }
        }
    }
    // Doo–Sabin, C2g0, large supports and the rare cases descend_values leaves: through the
    // weights (this also raises the error of a face without a limit surface).
    evaluate(point, rows_needed, out.scratch);
    out.d.setZero();
    for (Index i = 0; i < out.scratch.size(); ++i) {  // LimitWeights::apply, for either layout of X
        out.d.topRows(rows_needed) += out.scratch.w.col(i).head(rows_needed) * X.row(out.scratch.vertices[at(i)]);
    }
    out.at_extraordinary_vertex = out.scratch.at_extraordinary_vertex;
}

// --- public API --------------------------------------------------------------

Eigen::Matrix<double, 6, 3> LimitWeights::apply(const Points& X) const {
    Eigen::Matrix<double, 6, 3> r = Eigen::Matrix<double, 6, 3>::Zero();
    for (Index i = 0; i < size(); ++i) {
        r += w.col(i) * X.row(vertices[at(i)]);
    }
    return r;
}

LimitBasis::LimitBasis(const Topology& topology, SchemeKind scheme, const SchemeOptions& options,
                       const TunedWeights& weights, LimitEvaluation evaluation)
    : impl_(std::make_unique<Impl>()) {
    LIMSURF_CHECK(scheme == SchemeKind::CatmullClark || scheme == SchemeKind::Loop || scheme == SchemeKind::DooSabin ||
                      scheme == SchemeKind::C2g0,
                  UnsupportedError, "limit evaluation: scheme ", to_string(scheme),
                  " has no limit evaluation (catmull-clark, loop, doo-sabin, c2g0)");
    require_local_size(topology, max_limit_size, "the limit basis");
    const VertexRuleWeights plain = TunedWeights().at(invalid_index, 4);
    const VertexRuleWeights four = weights.at(invalid_index, 4);
    LIMSURF_CHECK(four.alpha == plain.alpha && four.beta == plain.beta && four.gamma == plain.gamma, UnsupportedError,
                  "limit evaluation: tuned weights for valence 4 change the regular patches");
    Impl& m = *impl_;
    m.topology = topology;
    m.scheme = scheme;
    m.options = options;
    m.weights = weights;
    if (scheme == SchemeKind::CatmullClark && !weights.is_catmull_clark()) {
        // Own β, γ reach beyond a vertex's faces (wide_weights): name every tuned vertex so that
        // local copies know which of their vertices carry them.
        for (Index v = 0; v < topology.num_vertices(); ++v) {
            const int n = static_cast<int>(topology.valence(v));
            const VertexRuleWeights w = weights.at(v, n);
            const VertexRuleWeights own = catmull_clark_weights(n);
            if (n >= 3 && (w.alpha != own.alpha || w.beta != own.beta || w.gamma != own.gamma)) {
                m.weights.set_vertex(v, w);
            }
        }
    }
    m.per_vertex_weights = m.weights.largest_vertex() != invalid_index;
    for (Index v = 0; m.per_vertex_weights && v <= std::min(weights.largest_vertex(), topology.num_vertices() - 1);
         ++v) {
        const VertexRuleWeights own = weights.at(v, 4);
        const bool regular = !topology.is_boundary_vertex(v) && topology.valence(v) == 4;
        LIMSURF_CHECK(!regular || (own.alpha == plain.alpha && own.beta == plain.beta && own.gamma == plain.gamma),
                      UnsupportedError, "limit evaluation: tuned weights on the valence-4 vertex ", v,
                      " change the regular patches");
    }
    m.quad = scheme != SchemeKind::Loop;
    if (scheme == SchemeKind::DooSabin) {
        LIMSURF_CHECK(weights.is_catmull_clark(), UnsupportedError, "tuned weights apply to Catmull–Clark only");
        m.doo_sabin = std::make_unique<detail::DooSabinLimit>(topology, options, evaluation);
        m.first_ptex.push_back(0);
        for (Index f = 0; f < topology.num_faces(); ++f) {
            const Index first = m.doo_sabin->first_ptex_face(f);
            const Index count = topology.face_degree(f) == 4 ? 1 : topology.face_degree(f);
            for (Index k = 0; k < count; ++k) {
                m.ptex.push_back(m.doo_sabin->ptex_face(first + k));
            }
            m.first_ptex.push_back(static_cast<Index>(m.ptex.size()));
        }
        return;
    }
    if (scheme == SchemeKind::C2g0) {
        // Closed triangle meshes with valences 3 and 6 (require_c2g0_topology), one ptex face per
        // triangle as Loop; tuned weights are Catmull–Clark's and do not apply.
        LIMSURF_CHECK(weights.is_catmull_clark(), UnsupportedError, "tuned weights apply to Catmull–Clark only");
        m.quad = false;
        m.c2g0 = std::make_unique<detail::C2g0Limit>(topology, evaluation);
        m.first_ptex.push_back(0);
        for (Index f = 0; f < topology.num_faces(); ++f) {
            m.ptex.push_back({f, -1});
            m.first_ptex.push_back(f + 1);
        }
        return;
    }
    for (Index v = 0; !m.quad && v < topology.num_vertices(); ++v) {
        // Two triangles with the same corners: every vertex of its refinements stays irregular (the
        // edge points have valence 4), so no level of local subdivision reaches a regular patch.
        LIMSURF_CHECK_AT(topology.is_boundary_vertex(v) || topology.valence(v) != 2, UnsupportedError,
                         vertex_element(v),
                         "Loop limit evaluation needs interior vertices of valence 3 or more: vertex ", v,
                         " has valence 2 (two triangles with the same corners)");
    }
    m.use_tables = evaluation == LimitEvaluation::Stationary;
    m.first_ptex.reserve(at(topology.num_faces() + 1));
    m.first_ptex.push_back(0);
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const Index degree = topology.face_degree(f);
        LIMSURF_CHECK_AT(m.quad || degree == 3, UnsupportedError, face_element(f), "Loop limit evaluation: face ", f,
                         " has ", degree, " corners (triangles only)");
        const bool one = (m.quad && degree == 4) || !m.quad;
        if (one) {
            m.ptex.push_back({f, -1});
        } else {
            for (Index k = 0; k < degree; ++k) {
                m.ptex.push_back({f, k});
            }
        }
        m.first_ptex.push_back(static_cast<Index>(m.ptex.size()));
    }
    m.roots = std::vector<std::atomic<Root*>>(m.ptex.size());
    m.find_fast_patches();
}

LimitBasis::~LimitBasis() = default;
LimitBasis::LimitBasis(LimitBasis&&) noexcept = default;
LimitBasis& LimitBasis::operator=(LimitBasis&&) noexcept = default;

const Topology& LimitBasis::topology() const noexcept {
    return impl_->topology;
}
SchemeKind LimitBasis::scheme() const noexcept {
    return impl_->scheme;
}
ParameterDomain LimitBasis::domain() const noexcept {
    return impl_->quad ? ParameterDomain::Quad : ParameterDomain::Triangle;
}
Index LimitBasis::num_ptex_faces() const noexcept {
    return static_cast<Index>(impl_->ptex.size());
}
PtexFace LimitBasis::ptex_face(Index p) const {
    LIMSURF_CHECK(p >= 0 && p < num_ptex_faces(), InputError, "ptex face ", p, " out of range (", num_ptex_faces(),
                  " ptex faces)");
    return impl_->ptex[at(p)];
}
Index LimitBasis::first_ptex_face(Index control_face) const {
    LIMSURF_CHECK(control_face >= 0 && control_face < impl_->topology.num_faces(), InputError, "face ", control_face,
                  " out of range (", impl_->topology.num_faces(), " faces)");
    return impl_->first_ptex[at(control_face)];
}
bool LimitBasis::has_limit_surface(Index p) const {
    (void)ptex_face(p);
    if (impl_->doo_sabin) {
        return impl_->doo_sabin->has_limit_surface(p);
    }
    if (impl_->c2g0) {
        return true;  // closed meshes only
    }
    if (!impl_->fast_index.empty() && impl_->fast_index[at(p)] >= 0) {
        // A plain regular patch: interior corners, not a hole. Answered without its root, which
        // evaluation never builds for such a face (root() would build one per face, under the
        // mutex, on a first pass that checks every point; and read two scattered cache lines).
        return true;
    }
    return impl_->root(p).has_limit;
}

namespace {

/// The point LimitBasis::evaluate works on: checked, and clamped into its domain (a tolerance
/// of 1e-12). @throws InputError as LimitBasis::evaluate says
SurfacePoint checked_point(const SurfacePoint& point, bool quad, Index num_ptex_faces) {
    LIMSURF_CHECK(point.face >= 0 && point.face < num_ptex_faces, InputError, "ptex face ", point.face,
                  " out of range (", num_ptex_faces, " ptex faces)");
    LIMSURF_CHECK(std::isfinite(point.u) && std::isfinite(point.v), InputError, "parameter (", point.u, ", ", point.v,
                  ") on ptex face ", point.face, " is not finite");
    constexpr double tolerance = 1e-12;
    SurfacePoint p = point;
    const bool inside = quad ? (p.u >= -tolerance && p.v >= -tolerance && p.u <= 1 + tolerance && p.v <= 1 + tolerance)
                             : (p.u >= -tolerance && p.v >= -tolerance && p.u + p.v <= 1 + tolerance);
    LIMSURF_CHECK(inside, InputError, "parameter (", p.u, ", ", p.v, ") is outside the ",
                  quad ? "unit square" : "triangle u, v >= 0, u + v <= 1", " of ptex face ", p.face);
    p.u = std::clamp(p.u, 0.0, 1.0);
    p.v = std::clamp(p.v, 0.0, 1.0);
    if (!quad && p.u + p.v > 1.0) {
        const double excess = (p.u + p.v - 1.0) / 2.0;
        p.u -= excess;
        p.v -= excess;
    }
    return p;
}

int rows_of(DerivativeOrder order) {
    return order == DerivativeOrder::Value ? 1 : order == DerivativeOrder::First ? 3 : 6;
}

}  // namespace

void LimitBasis::evaluate(const SurfacePoint& point, LimitWeights& out, DerivativeOrder order) const {
    const int keep = rows_of(order);
    impl_->evaluate(checked_point(point, impl_->quad, num_ptex_faces()), keep, out);
    out.w.bottomRows(6 - keep).setZero();
}

void LimitBasis::evaluate(const Points& X, const SurfacePoint& point, LimitPoint& out, DerivativeOrder order) const {
    LIMSURF_CHECK(X.rows() == impl_->topology.num_vertices(), InputError, "limit evaluation: ", X.rows(),
                  " positions for ", impl_->topology.num_vertices(), " vertices");
    impl_->evaluate(X, checked_point(point, impl_->quad, num_ptex_faces()), rows_of(order), out);
}

LimitWeights LimitBasis::evaluate(const SurfacePoint& point, DerivativeOrder order) const {
    LimitWeights out;
    evaluate(point, out, order);
    return out;
}

void LimitBasis::evaluate(const InterleavedPoints& X, const SurfacePoint& point, LimitPoint& out,
                          DerivativeOrder order) const {
    LIMSURF_CHECK(X.rows() == impl_->topology.num_vertices(), InputError, "limit evaluation: ", X.rows(),
                  " positions for ", impl_->topology.num_vertices(), " vertices");
    impl_->evaluate(X, checked_point(point, impl_->quad, num_ptex_faces()), rows_of(order), out);
}

bool LimitBasis::patch(const SurfacePoint& point, LimitPatch& out) const {
    return impl_->patch(checked_point(point, impl_->quad, num_ptex_faces()), out);
}

bool LimitBasis::patch_data(const SurfacePoint& point, const Eigen::MatrixXd& X, LimitPatch& out,
                            Eigen::MatrixXd& data) const {
    return impl_->patch_data(checked_point(point, impl_->quad, num_ptex_faces()), X, out, data);
}

Eigen::Vector2d LimitPatch::parameter(double u, double v) const {
    return axes.inverse() * (Eigen::Vector2d(u, v) - origin);
}

bool LimitPatch::contains(double u, double v, double tolerance) const {
    const Eigen::Vector2d st = parameter(u, v);
    const bool low = st.x() >= -tolerance && st.y() >= -tolerance;
    return domain == ParameterDomain::Quad ? low && st.x() <= 1.0 + tolerance && st.y() <= 1.0 + tolerance
                                           : low && st.x() + st.y() <= 1.0 + tolerance;
}

Eigen::MatrixXd LimitPatch::control_data(const Eigen::MatrixXd& X) const {
    const Eigen::MatrixXd local = gather_rows(vertices, X);
    Eigen::MatrixXd P(size() + 1, X.cols());
    times_columns(points, local, P);
    P.bottomRows<1>().noalias() = offset * local;
    return P;
}

void LimitPatch::evaluate(const Eigen::MatrixXd& P, double u, double v, Eigen::Matrix<double, 6, Eigen::Dynamic>& out,
                          DerivativeOrder order) const {
    LIMSURF_CHECK(P.rows() == size() + 1, InputError, "limit patch: data of ", P.rows(), " rows, expected ", size() + 1,
                  " (control_data)");
    LIMSURF_CHECK(std::isfinite(u) && std::isfinite(v), InputError, "limit patch: parameter (", u, ", ", v,
                  ") is not finite");
    const int keep = rows_of(order);
    const Eigen::Vector2d st = parameter(u, v);
    // Column by column, as sums of the basis's columns (6-vectors) scaled by the data: vectorised
    // over the rows. Eigen's products here (dynamic column count, or a 6 × 16 matrix times a
    // vector) walked the basis by rows and took a fifth of a tuning run.
    const auto combine = [&P, &out](const auto& b) {
        out.resize(6, P.cols());
        for (Eigen::Index j = 0; j < P.cols(); ++j) {
            Eigen::Matrix<double, 6, 1> sum = b.col(0) * P(0, j);
            for (Eigen::Index k = 1; k < b.cols(); ++k) {
                sum += b.col(k) * P(k, j);
            }
            out.col(j) = sum;
        }
    };
    if (domain == ParameterDomain::Quad) {
        Eigen::Matrix<double, 6, 16> b;
        cubic_bspline_patch_weights(st.x(), st.y(), b);
        combine(b);
    } else {
        Eigen::Matrix<double, 6, 12> b;
        quartic_box_spline_patch_weights(st.x(), st.y(), b, keep);
        combine(b);
    }
    to_ptex(out, axes, out);  // column by column: in place
    out.row(0) += P.bottomRows<1>();
    out.bottomRows(6 - keep).setZero();
}

void LimitBasis::prefetch(const InterleavedPoints& X, const SurfacePoint& point, PrefetchStage stage) const noexcept {
    const Impl& m = *impl_;
    if (point.face < 0 || at(point.face) >= m.fast_index.size()) {
        return;  // also every basis without fast patches (Doo–Sabin, C2g0: fast_index is empty)
    }
    const auto prefetch_rows = [&](const Index* vertices, std::size_t n) {
        if (X.rows() != m.topology.num_vertices()) {
            return;
        }
        for (std::size_t i = 0; i < n; ++i) {  // a row is 24 bytes: it may straddle two cache lines
            const double* row = X.data() + 3 * vertices[i];
            __builtin_prefetch(row);
            __builtin_prefetch(row + 2);
        }
    };
    const Index* entry = &m.fast_index[at(point.face)];
    const std::atomic<Root*>* slot = &m.roots[at(point.face)];
    if (stage == PrefetchStage::Lookup) {
        __builtin_prefetch(entry);
        __builtin_prefetch(slot);
        return;
    }
    if (*entry < 0) {  // a face near an extraordinary vertex: its root (if built) and its support
        const Root* root = slot->load(std::memory_order_acquire);
        if (root == nullptr) {
            return;
        }
        if (stage == PrefetchStage::Patch) {
            __builtin_prefetch(root);
            __builtin_prefetch(root->support.data());
        } else if (root->support.size() <= static_cast<std::size_t>(max_local_points)) {
            prefetch_rows(root->support.data(), root->support.size());
        }
        return;
    }
    const Impl::FastPatch& patch = m.fast[at(*entry)];
    if (stage == PrefetchStage::Patch) {  // 16 indices and a rotation: 68 bytes, two cache lines
        __builtin_prefetch(&patch);
        __builtin_prefetch(reinterpret_cast<const char*>(&patch + 1) - 1);
        return;
    }
    prefetch_rows(patch.points.data(), m.quad ? 16 : 12);
}

Eigen::Matrix<double, 6, 3> LimitBasis::evaluate(const Points& X, const SurfacePoint& point,
                                                 DerivativeOrder order) const {
    LimitPoint out;
    evaluate(X, point, out, order);
    return out.d;
}

namespace {

/// A point of the limit surface at control vertex v: an incident face with a limit
/// surface and the ptex coordinates of v's corner in it.
std::optional<SurfacePoint> point_at_vertex(const LimitBasis& basis, Index v) {
    const Topology& t = basis.topology();
    const auto faces = t.vertex_faces(v);
    const auto corners = t.vertex_face_corners(v);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Index f = faces[i];
        const Index first = basis.first_ptex_face(f);
        const bool split = basis.ptex_face(first).corner >= 0;
        const Index p = split ? first + corners[i] : first;
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        const Eigen::Vector2d uv =
            split ? Eigen::Vector2d(0, 0) : domain_corner(basis.domain() == ParameterDomain::Quad, corners[i]);
        return SurfacePoint{p, uv.x(), uv.y()};
    }
    return std::nullopt;
}

}  // namespace

LimitWeights LimitBasis::vertex_limit(Index v) const {
    LIMSURF_CHECK(v >= 0 && v < impl_->topology.num_vertices(), InputError, "vertex ", v, " out of range");
    const auto point = point_at_vertex(*this, v);
    if (!point) {
        LimitWeights own;
        own.vertices = {v};
        own.w = Eigen::Matrix<double, 6, 1>::Zero();
        own.w(0, 0) = 1.0;
        return own;
    }
    return evaluate(*point, DerivativeOrder::First);
}

SparseMatrix LimitBasis::vertex_limit_matrix() const {
    const Index n = impl_->topology.num_vertices();
    std::vector<Eigen::Triplet<double>> entries;
    for (Index v = 0; v < n; ++v) {
        const LimitWeights w = vertex_limit(v);
        for (Index i = 0; i < w.size(); ++i) {
            if (w.w(0, i) != 0.0) {
                entries.emplace_back(v, w.vertices[at(i)], w.w(0, i));
            }
        }
    }
    SparseMatrix P(n, n);
    P.setFromTriplets(entries.begin(), entries.end());
    return P;
}

}  // namespace limsurf
