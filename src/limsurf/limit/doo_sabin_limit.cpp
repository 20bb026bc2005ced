// Exact Doo–Sabin limit evaluation (doo_sabin_limit.h, docs/doo_sabin_limit.md).
//
// After one Doo–Sabin step every vertex has valence 4, and the limit surface is a
// union of patches, one per vertex c: the patch of c spans the limit points of the
// centres of its four faces. A node of the evaluation tree is such a vertex with its
// four faces (a "disc"), copied into a small Topology numbered canonically: local
// vertex 0 is c, faces 0..3 follow counter-clockwise about c and each starts at c.
// The patch of c depends only on the vertices of these four faces: one Doo–Sabin
// step places every child vertex by a mask of its own parent face only, the children
// of c are the children of (face g, corner c) for the four faces g, and the four faces
// of such a child — the F-face of g, the E-faces of g's two edges at c and the V-face
// of c — only have children of corners of faces around c as vertices. So refining the
// disc alone (no boundary rule: the rim is not a boundary of the surface) gives the
// four child discs exactly, and the patch of c is the union of their patches
// (child q covers the quadrant at domain corner q).
//
// A node is
//   Regular     — four quads: the biquadratic B-spline on their 3 × 3 vertices;
//   Stationary  — face 0 is an n-gon, faces 1..3 quads: child 0 is the same disc, so
//                 the local subdivision matrix A repeats at every level and a point n
//                 levels deep gets B(q) · G_q · M_q · A^n · W, tabulated with
//                 R = A − 1ℓᵀ as in limit_basis.cpp (children 1..3 are always regular);
//   Refine      — anything else (an n-gon face and a valence-n vertex both at the
//                 patch): refine once and descend; every child has at most one n-gon.
#include "doo_sabin_limit.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <mutex>
#include <string>
#include <unordered_map>

#include <Eigen/LU>

#include "limsurf/core/error.h"
#include "limsurf/limit/patch_basis.h"
#include "limsurf/refine/refine.h"
#include "local_patch.h"
#include "parameter_maps.h"

namespace limsurf::detail {
namespace {

/// Depth of the stationary tables (as limit_basis.cpp): points closer than 2^-60 to an
/// extraordinary corner are evaluated there.
constexpr int max_stationary_levels = 60;
/// Bound of a descent level by level (LimitEvaluation::Subdivision).
constexpr int max_depth = 40;

using Dense = Eigen::MatrixXd;
using Rows = Eigen::Matrix<double, 6, Eigen::Dynamic>;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

Affine rotation(int k) {
    return detail::rotation(true, k);
}
Affine child_map(int q) {
    return detail::child_map(true, q);
}
bool in_corner_child(const Eigen::Vector2d& p) {
    return detail::in_corner_child(true, p);
}
int child_containing(const Eigen::Vector2d& p) {
    return detail::child_containing(true, p);
}

/// Biquadratic basis rows at patch coordinates @p st as ptex derivatives, for
/// ptex = offset + J · (s, t).
Rows patch_rows(const Eigen::Vector2d& st, const Eigen::Matrix2d& J) {
    Eigen::Matrix<double, 6, 9> b;
    quadratic_bspline_patch_weights(st.x(), st.y(), b);
    Rows r;
    to_ptex<9>(b, J, r);
    return r;
}

/// The faces around one interior vertex x, copied canonically: local vertex 0 is x,
/// local face i is the i-th face counter-clockwise about x from the start face, each
/// starting at x. Only the spokes (edges at x) are shared between consecutive faces;
/// any other coincidence of vertices in the source is split, which changes nothing:
/// every Doo–Sabin mask reads the vertices of one face only.
struct Disc {
    Topology topology;
    std::vector<Index> source;  ///< #local: the source vertex each local vertex copies
};

Disc make_disc(const Topology& t, Index face, Index corner) {
    const Index x = t.face_vertices(face)[at(corner)];
    [[maybe_unused]] const auto valence = static_cast<Index>(t.vertex_faces(x).size());
    // Counter-clockwise about x: the next face lies across the edge (corner - 1, corner).
    std::vector<std::array<Index, 2>> ring;
    Index g = face;
    Index c = corner;
    do {
        LIMSURF_ASSERT(static_cast<Index>(ring.size()) < valence, "vertex ", x, ": the ring does not close");
        ring.push_back({g, c});
        const Index d = t.face_degree(g);
        const auto ef = t.edge_faces(t.face_edges(g)[at((c + d - 1) % d)]);
        LIMSURF_ASSERT(ef.size() == 2, "vertex ", x, " is a boundary vertex");
        g = ef[0] == g ? ef[1] : ef[0];
        const auto gv = t.face_vertices(g);
        c = static_cast<Index>(std::find(gv.begin(), gv.end(), x) - gv.begin());
    } while (g != face || c != corner);
    const auto m = ring.size();
    Disc disc;
    disc.source.push_back(x);
    std::vector<Index> spoke(m, invalid_index);
    const auto local = [&](Index& id, Index v) {
        if (id == invalid_index) {
            id = static_cast<Index>(disc.source.size());
            disc.source.push_back(v);
        }
        return id;
    };
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    for (std::size_t i = 0; i < m; ++i) {
        const auto [f, k] = ring[i];
        const auto fv = t.face_vertices(f);
        const Index d = t.face_degree(f);
        corners.push_back(0);
        corners.push_back(local(spoke[i], fv[at((k + 1) % d)]));
        for (Index j = 2; j < d - 1; ++j) {
            Index fresh = invalid_index;
            corners.push_back(local(fresh, fv[at((k + j) % d)]));
        }
        corners.push_back(local(spoke[(i + 1) % m], fv[at((k + d - 1) % d)]));
        offsets.push_back(static_cast<Index>(corners.size()));
    }
    disc.topology = Topology(static_cast<Index>(disc.source.size()), offsets, corners);
    return disc;
}

bool is_regular(const Topology& disc) {
    if (disc.num_faces() != 4) {
        return false;
    }
    for (Index f = 0; f < 4; ++f) {
        if (disc.face_degree(f) != 4) {
            return false;
        }
    }
    return true;
}

/// The 9 × #local matrix of the 3 × 3 net of a regular disc (patch_basis.h numbering,
/// c = point 4): face 0 is the cell of points 0, 1, 3, 4 — the patch's (0,0) corner —
/// and faces 1, 2, 3 are the cells at (1,0), (1,1), (0,1), so that counter-clockwise
/// from c face 0 reads [4, 3, 0, 1], face 1 [4, 1, 2, 5], face 2 [4, 5, 8, 7], face 3 [4, 7, 6, 3].
Dense grid_matrix(const Topology& disc) {
    const auto fv = [&](Index f, Index k) { return disc.face_vertices(f)[at(k)]; };
    const std::array<Index, 9> grid = {fv(0, 2), fv(0, 3), fv(1, 2), fv(0, 1), 0,
                                       fv(1, 3), fv(3, 2), fv(2, 3), fv(2, 2)};
    LIMSURF_ASSERT(fv(1, 1) == grid[1] && fv(2, 1) == grid[5] && fv(3, 1) == grid[7] && fv(3, 3) == grid[3],
                   "the regular disc is not a 3 x 3 net");
    Dense G = Dense::Zero(9, disc.num_vertices());
    for (std::size_t i = 0; i < grid.size(); ++i) {
        G(static_cast<Index>(i), grid[i]) = 1.0;
    }
    return G;
}

SchemeOptions classic() {
    SchemeOptions o;
    o.boundary = BoundaryInterpolation::None;  // the disc's rim is no boundary of the surface
    return o;
}

/// A self-similar disc (an n-gon at corner 0, quads elsewhere), shared by all nodes with
/// its topology. tables[q][0] = G_q M_q, tables[q][n] = G_q M_q R^n for q = 1, 2, 3.
struct StationaryClass {
    std::array<std::vector<Dense>, 4> tables;
    Eigen::RowVectorXd limit_row;  ///< the limit mask ℓ of the corner (ℓᵀA = ℓᵀ, ℓ·1 = 1)
};

struct Node {
    enum class Kind { Regular, Stationary, Refine };
    Kind kind = Kind::Refine;
    Disc mesh;
    Dense W;  ///< #local × #support
    int depth = 0;
    Dense G;  ///< Regular: the 3 × 3 net over local vertices
    std::shared_ptr<const StationaryClass> stationary;
    std::unique_ptr<Level> refined;  ///< Refine: the disc subdivided once
    std::array<std::atomic<Node*>, 4> children{};
};

struct Root {
    bool has_limit = true;
    std::vector<Index> support;
    Affine frame;  ///< ptex = frame(node coordinates)
    Node* node = nullptr;
};

}  // namespace

struct DooSabinLimit::Impl {
    Topology topology;
    SchemeOptions options;
    bool use_tables = true;
    std::vector<Index> first_ptex;  // #F + 1
    std::vector<PtexFace> ptex;

    mutable std::mutex mutex;
    mutable std::vector<std::unique_ptr<Node>> nodes;  // owner of every node
    mutable std::vector<std::atomic<Root*>> roots;     // one per face corner (level-1 vertex)
    mutable std::vector<std::unique_ptr<Root>> root_storage;
    mutable std::unordered_map<std::string, std::shared_ptr<const StationaryClass>> classes;

    const Root& root(Index corner) const;
    [[nodiscard]] std::unique_ptr<Root> build_root(Index corner) const;
    Node* make_node(Disc mesh, Dense W, int depth) const;
    [[nodiscard]] std::shared_ptr<const StationaryClass> make_class(const Level& refined, const Dense& A) const;
    Node* child(Node& node, int q) const;
    [[nodiscard]] Rows descend(Node* node, Eigen::Vector2d p, Affine frame) const;
    [[nodiscard]] Rows stationary_rows(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame) const;
    [[nodiscard]] bool face_has_limit(Index f) const {
        const auto fv = topology.face_vertices(f);
        return std::none_of(fv.begin(), fv.end(), [&](Index v) { return topology.is_boundary_vertex(v); });
    }
};

std::unique_ptr<Root> DooSabinLimit::Impl::build_root(Index corner) const {
    auto root = std::make_unique<Root>();
    // The face owning this corner: face_offset(f) <= corner < face_offset(f + 1).
    const auto offsets = topology.face_offsets();
    const auto f = static_cast<Index>(std::upper_bound(offsets.begin(), offsets.end(), corner) - offsets.begin()) - 1;
    const Index k = corner - topology.face_offset(f);
    root->has_limit = face_has_limit(f);
    if (!root->has_limit) {
        return root;
    }
    const Index n = topology.face_degree(f);
    // The faces around v_k (local face 0 = f, starting at v_k) hold every vertex that the
    // level-1 disc of c = child(f, k) reads: its F-face, both E-faces and the V-face of v_k.
    const Disc star = make_disc(topology, f, k);
    root->support = star.source;
    std::sort(root->support.begin(), root->support.end());
    root->support.erase(std::unique(root->support.begin(), root->support.end()), root->support.end());
    Dense P = Dense::Zero(star.topology.num_vertices(), static_cast<Index>(root->support.size()));
    for (std::size_t i = 0; i < star.source.size(); ++i) {
        const auto column = std::lower_bound(root->support.begin(), root->support.end(), star.source[i]);
        P(static_cast<Index>(i), static_cast<Index>(column - root->support.begin())) = 1.0;
    }
    const Level level = refine_doo_sabin(star.topology, classic());
    // c is child vertex 0 (corner 0 of local face 0). Its faces counter-clockwise are
    // V(v_k), E(v_k, v_k+1), F(f), E(v_k-1, v_k), domain corners (0,0), (1,0), (1,1), (0,1).
    // Start the disc at the extraordinary face, if any: the V-face (r = 0) or the F-face (r = 2).
    const Index valence = star.topology.num_faces();
    const int r = (valence == 4 && n != 4) ? 2 : 0;
    Index start = 0;  // F-face of local face 0
    Index start_corner = 0;
    if (r == 0) {
        const auto& prov = level.provenance;
        for (Index g = 0; g < level.topology.num_faces(); ++g) {
            if (prov.face_parent_kind[at(g)] == ParentKind::Vertex && prov.face_parent[at(g)] == 0) {
                start = g;
            }
        }
        const auto gv = level.topology.face_vertices(start);
        start_corner = static_cast<Index>(std::find(gv.begin(), gv.end(), 0) - gv.begin());
    }
    Disc disc = make_disc(level.topology, start, start_corner);
    Dense W = dense_rows(level.S0, disc.source) * P;
    const bool quad = n == 4;
    root->frame = (quad ? child_map(static_cast<int>(k)) : Affine{}).then(rotation(r));
    root->node = make_node(std::move(disc), std::move(W), 1);
    return root;
}

Node* DooSabinLimit::Impl::make_node(Disc mesh, Dense W, int depth) const {
    LIMSURF_CHECK(depth <= max_depth, NumericalError, "Doo-Sabin limit evaluation: no regular patch after ", max_depth,
                  " levels (a point too close to an extraordinary corner for LimitEvaluation::Subdivision?)");
    auto node = std::make_unique<Node>();
    node->W = std::move(W);
    node->depth = depth;
    if (is_regular(mesh.topology)) {
        node->kind = Node::Kind::Regular;
        node->G = grid_matrix(mesh.topology);
    } else {
        const std::string signature = topology_signature(mesh.topology);
        const auto known = use_tables ? classes.find(signature) : classes.end();
        if (known != classes.end()) {
            node->kind = Node::Kind::Stationary;
            node->stationary = known->second;
        } else {
            node->refined = std::make_unique<Level>(refine_doo_sabin(mesh.topology, classic()));
            const Disc corner = make_disc(node->refined->topology, 0, 0);
            if (use_tables && topology_signature(corner.topology) == signature) {
                const Dense A = dense_rows(node->refined->S0, corner.source);
                auto cls = make_class(*node->refined, A);
                classes.emplace(signature, cls);
                node->kind = Node::Kind::Stationary;
                node->stationary = std::move(cls);
            }
        }
    }
    node->mesh = std::move(mesh);
    nodes.push_back(std::move(node));
    return nodes.back().get();
}

std::shared_ptr<const StationaryClass> DooSabinLimit::Impl::make_class(const Level& refined, const Dense& A) const {
    auto cls = std::make_shared<StationaryClass>();
    for (int q = 1; q < 4; ++q) {
        // Child q: the child of c in local face q, i.e. corner 0 of F-face q.
        const Disc disc = make_disc(refined.topology, q, 0);
        LIMSURF_ASSERT(is_regular(disc.topology), "child ", q, " of a stationary Doo-Sabin disc is not regular");
        cls->tables[at(q)].push_back(grid_matrix(disc.topology) * dense_rows(refined.S0, disc.source));
    }
    Dense power = A;
    for (int j = 0; j < 8; ++j) {
        power = power * power;
    }
    cls->limit_row = power.row(0) / power.row(0).sum();
    const Dense R = A - Eigen::VectorXd::Ones(A.rows()) * cls->limit_row;
    for (int q = 1; q < 4; ++q) {
        auto& table = cls->tables[at(q)];
        table.reserve(max_stationary_levels + 1);
        table.push_back(table.front() * R);
        for (int n = 2; n <= max_stationary_levels; ++n) {
            table.push_back(table.back() * R);
        }
    }
    return cls;
}

Node* DooSabinLimit::Impl::child(Node& node, int q) const {
    Node* existing = node.children[at(q)].load(std::memory_order_acquire);
    if (existing != nullptr) {
        return existing;
    }
    const std::lock_guard lock(mutex);
    existing = node.children[at(q)].load(std::memory_order_relaxed);
    if (existing != nullptr) {
        return existing;
    }
    // Child q covers the quadrant at domain corner q; its disc starts at the F-face of
    // local face q (its own (0,0)), whose corner 0 is the child of c.
    Disc mesh = make_disc(node.refined->topology, q, 0);
    Dense W = dense_rows(node.refined->S0, mesh.source) * node.W;
    Node* made = make_node(std::move(mesh), std::move(W), node.depth + 1);
    node.children[at(q)].store(made, std::memory_order_release);
    return made;
}

const Root& DooSabinLimit::Impl::root(Index corner) const {
    Root* existing = roots[at(corner)].load(std::memory_order_acquire);
    if (existing != nullptr) {
        return *existing;
    }
    const std::lock_guard lock(mutex);
    existing = roots[at(corner)].load(std::memory_order_relaxed);
    if (existing == nullptr) {
        root_storage.push_back(build_root(corner));
        existing = root_storage.back().get();
        roots[at(corner)].store(existing, std::memory_order_release);
    }
    return *existing;
}

Rows DooSabinLimit::Impl::stationary_rows(const StationaryClass& cls, Eigen::Vector2d p, const Affine& frame) const {
    int n = 0;
    while (n < max_stationary_levels && in_corner_child(p)) {
        p *= 2.0;
        ++n;
    }
    const bool at_vertex = in_corner_child(p);
    if (at_vertex) {
        // At the extraordinary corner itself: the exact limit position, and the
        // derivatives 2^-61 away.
        n = max_stationary_levels;
        p = {0.5, 0.0};
    }
    const int q = child_containing(p);
    Affine scaled = frame;
    scaled.axes *= std::ldexp(1.0, -n);
    const Affine map = child_map(q);
    const Affine patch = scaled.then(map);
    const Rows basis = patch_rows(map.to_child(p), patch.axes);
    Rows rows = basis * cls.tables[at(q)][at(n)];
    if (n > 0) {
        rows.row(0) += basis.row(0).sum() * cls.limit_row;
    }
    if (at_vertex) {
        rows.row(0) = cls.limit_row;
    }
    return rows;
}

Rows DooSabinLimit::Impl::descend(Node* node, Eigen::Vector2d p, Affine frame) const {
    while (true) {
        if (node->kind == Node::Kind::Regular) {
            return patch_rows(p, frame.axes) * node->G * node->W;
        }
        if (node->kind == Node::Kind::Stationary) {
            return stationary_rows(*node->stationary, p, frame) * node->W;
        }
        const int q = child_containing(p);
        const Affine map = child_map(q);
        p = map.to_child(p);
        frame = frame.then(map);
        node = child(*node, q);
    }
}

// --- interface -----------------------------------------------------------------

DooSabinLimit::DooSabinLimit(const Topology& topology, const SchemeOptions& options, LimitEvaluation evaluation)
    : impl_(std::make_unique<Impl>()) {
    for (Index e = 0; e < topology.num_edges(); ++e) {
        LIMSURF_CHECK(topology.edge_sharpness(e) == 0.0, UnsupportedError,
                      "Doo-Sabin limit evaluation has no crease rule: edge ", e, " has sharpness ",
                      topology.edge_sharpness(e));
    }
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK(topology.vertex_sharpness(v) == 0.0, UnsupportedError,
                      "Doo-Sabin limit evaluation has no corner rule: vertex ", v, " has sharpness ",
                      topology.vertex_sharpness(v));
    }
    for (Index f = 0; f < topology.num_faces(); ++f) {
        LIMSURF_CHECK(!topology.is_hole(f), UnsupportedError,
                      "Doo-Sabin limit evaluation does not support holes: face ", f, " is a hole");
    }
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK_AT(topology.is_boundary_vertex(v) || topology.vertex_faces(v).size() >= 3, UnsupportedError,
                         vertex_element(v),
                         "Doo-Sabin limit evaluation needs interior vertices in at least 3 faces: vertex ", v,
                         " is in ", topology.vertex_faces(v).size());
    }
    Impl& m = *impl_;
    m.topology = topology;
    m.options = options;
    m.use_tables = evaluation == LimitEvaluation::Stationary;
    m.first_ptex.reserve(at(topology.num_faces() + 1));
    m.first_ptex.push_back(0);
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const Index degree = topology.face_degree(f);
        if (degree == 4) {
            m.ptex.push_back({f, -1});
        } else {
            for (Index k = 0; k < degree; ++k) {
                m.ptex.push_back({f, k});
            }
        }
        m.first_ptex.push_back(static_cast<Index>(m.ptex.size()));
    }
    m.roots = std::vector<std::atomic<Root*>>(at(topology.num_corners()));
}

DooSabinLimit::~DooSabinLimit() = default;
DooSabinLimit::DooSabinLimit(DooSabinLimit&&) noexcept = default;
DooSabinLimit& DooSabinLimit::operator=(DooSabinLimit&&) noexcept = default;

Index DooSabinLimit::num_ptex_faces() const noexcept {
    return static_cast<Index>(impl_->ptex.size());
}

PtexFace DooSabinLimit::ptex_face(Index p) const {
    LIMSURF_CHECK(p >= 0 && p < num_ptex_faces(), InputError, "ptex face ", p, " out of range (", num_ptex_faces(),
                  " ptex faces)");
    return impl_->ptex[at(p)];
}

Index DooSabinLimit::first_ptex_face(Index f) const {
    LIMSURF_CHECK(f >= 0 && f < impl_->topology.num_faces(), InputError, "face ", f, " out of range (",
                  impl_->topology.num_faces(), " faces)");
    return impl_->first_ptex[at(f)];
}

bool DooSabinLimit::has_limit_surface(Index p) const {
    return impl_->face_has_limit(ptex_face(p).control_face);
}

void DooSabinLimit::evaluate(Index ptex_face, double u, double v, std::vector<Index>& support,
                             Eigen::Matrix<double, 6, Eigen::Dynamic>& rows) const {
    const PtexFace pf = this->ptex_face(ptex_face);
    LIMSURF_CHECK(std::isfinite(u) && std::isfinite(v), InputError, "parameter (", u, ", ", v, ") on ptex face ",
                  ptex_face, " is not finite");
    constexpr double tolerance = 1e-12;
    LIMSURF_CHECK(u >= -tolerance && v >= -tolerance && u <= 1 + tolerance && v <= 1 + tolerance, InputError,
                  "parameter (", u, ", ", v, ") is outside the unit square of ptex face ", ptex_face);
    LIMSURF_CHECK(impl_->face_has_limit(pf.control_face), InputError, "ptex face ", ptex_face, " (control face ",
                  pf.control_face, ") has no Doo-Sabin limit surface here (a vertex of the face is on the boundary)");
    const Eigen::Vector2d p(std::clamp(u, 0.0, 1.0), std::clamp(v, 0.0, 1.0));
    const Index offset = impl_->topology.face_offset(pf.control_face);
    const Index corner = offset + (pf.corner < 0 ? child_containing(p) : pf.corner);
    const Root& r = impl_->root(corner);
    support = r.support;
    rows = impl_->descend(r.node, r.frame.to_child(p), r.frame);
}

}  // namespace limsurf::detail
