#include "deep_subdivision.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "limsurf/limit/patch_basis.h"
#include "limsurf/refine/refine.h"

namespace limsurf::test {

namespace {

using Vec2 = Eigen::Vector2d;

/// Corners of the parameter domain of a face in its local (s, t).
const std::array<Vec2, 4> quad_corners{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
const std::array<Vec2, 3> triangle_corners{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};

/// A child face in its parent's local coordinates: parent = origin + J · child.
struct ChildFrame {
    Vec2 origin;
    Eigen::Matrix2d J;
};

/// Child k of a split face (quad split: k = 0..3; triangle split: 0..2, 3 = middle).
/// Corner child k is [v_k, e(v_k, v_k+1), ..., e(v_k-1, v_k)]: its s axis runs to the
/// midpoint of the next edge, its t axis to the midpoint of the previous one.
ChildFrame child_frame(bool triangle, int k) {
    const int n = triangle ? 3 : 4;
    const auto corner = [&](int i) { return triangle ? triangle_corners[(i + 3) % 3] : quad_corners[(i + 4) % 4]; };
    ChildFrame frame;
    if (triangle && k == 3) {  // [e0, e1, e2]
        frame.origin = (corner(0) + corner(1)) / 2;
        frame.J.col(0) = (corner(2) - corner(0)) / 2;
        frame.J.col(1) = (corner(2) - corner(1)) / 2;
        return frame;
    }
    frame.origin = corner(k);
    frame.J.col(0) = (corner((k + 1) % n) - corner(k)) / 2;
    frame.J.col(1) = (corner(k - 1) - corner(k)) / 2;
    return frame;
}

/// How far (a, b) lies outside the unit square / the unit triangle (0 inside).
double outside(bool triangle, double a, double b) {
    double d = std::max({0.0, -a, -b});
    return triangle ? std::max(d, a + b - 1.0) : std::max({d, a - 1.0, b - 1.0});
}

void clamp_into(bool triangle, double& a, double& b) {
    a = std::clamp(a, 0.0, 1.0);
    b = std::clamp(b, 0.0, 1.0);
    if (triangle && a + b > 1.0) {
        const double excess = (a + b - 1.0) / 2;
        a -= excess;
        b -= excess;
    }
}

/// The faces around corner vertex @p v of @p face, starting with @p face, counter-clockwise,
/// each with the corner at which v sits.
std::vector<std::pair<Index, Index>> faces_from(const Topology& t, Index v, Index face) {
    const auto faces = t.vertex_faces(v);
    const auto corners = t.vertex_face_corners(v);
    const auto n = faces.size();
    std::size_t first = n;
    for (std::size_t i = 0; i < n; ++i) {
        if (faces[i] == face) {
            first = i;
        }
    }
    if (first == n) {
        throw std::logic_error("deep_subdivision: face not incident to its corner");
    }
    std::vector<std::pair<Index, Index>> out;
    for (std::size_t q = 0; q < n; ++q) {
        out.emplace_back(faces[(first + q) % n], corners[(first + q) % n]);
    }
    return out;
}

/// Why the one-ring of @p face is not a regular interior patch, or empty.
std::string irregularity(const Topology& t, Index face, bool triangle) {
    const Index degree = triangle ? 3 : 4;
    const Index valence = triangle ? 6 : 4;
    if (t.face_degree(face) != degree) {
        return "face of degree " + std::to_string(t.face_degree(face));
    }
    for (const Index v : t.face_vertices(face)) {
        if (t.is_boundary_vertex(v)) {
            return "boundary vertex " + std::to_string(v);
        }
        if (t.valence(v) != valence) {
            return "vertex " + std::to_string(v) + " of valence " + std::to_string(t.valence(v));
        }
        for (const Index g : t.vertex_faces(v)) {
            if (t.face_degree(g) != degree) {
                return "neighbour face " + std::to_string(g) + " of degree " + std::to_string(t.face_degree(g));
            }
            if (t.is_hole(g)) {
                return "neighbour face " + std::to_string(g) + " is a hole";
            }
            for (const Index e : t.face_edges(g)) {
                if (t.edge_sharpness(e) != 0.0) {
                    return "sharp edge " + std::to_string(e);
                }
            }
            for (const Index w : t.face_vertices(g)) {
                if (t.vertex_sharpness(w) != 0.0) {
                    return "sharp vertex " + std::to_string(w);
                }
            }
        }
    }
    return {};
}

/// Lattice position -> control point number of patch_basis.h.
int bspline_index(int x, int y) {
    return 4 * (y + 1) + (x + 1);
}

int box_spline_index(int x, int y) {
    switch (y) {
    case -1:
        return x >= 0 && x <= 2 ? x : -1;
    case 0:
        return x >= -1 && x <= 2 ? 3 + (x + 1) : -1;
    case 1:
        return x >= -1 && x <= 1 ? 7 + (x + 1) : -1;
    case 2:
        return x >= -1 && x <= 0 ? 10 + (x + 1) : -1;
    default:
        return -1;
    }
}

/// The 16 (quad) or 12 (triangle) control points of the regular patch over @p face, by
/// unfolding the faces around each corner onto the lattice of patch_basis.h.
template <int N>
std::array<Index, N> gather(const Topology& t, Index face) {
    constexpr bool triangle = N == 12;
    constexpr int ring = triangle ? 6 : 4;  // faces around a regular vertex
    constexpr int degree = triangle ? 3 : 4;
    // Directions of the edges around a regular vertex, counter-clockwise, in lattice units.
    static const std::array<std::array<int, 2>, ring> directions = [] {
        std::array<std::array<int, 2>, ring> d{};
        if constexpr (triangle) {
            d = {{{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}}};
        } else {
            d = {{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
        }
        return d;
    }();
    static const std::array<std::array<int, 2>, 4> positions{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
    static const std::array<std::array<int, 2>, 3> triangle_positions{{{0, 0}, {1, 0}, {0, 1}}};
    std::array<Index, N> points;
    points.fill(invalid_index);
    const auto put = [&](int x, int y, Index v) {
        const int i = triangle ? box_spline_index(x, y) : bspline_index(x, y);
        if (i < 0 || i >= N) {
            throw std::logic_error("deep_subdivision: lattice point outside the patch");
        }
        if (points[static_cast<std::size_t>(i)] != invalid_index && points[static_cast<std::size_t>(i)] != v) {
            throw std::logic_error("deep_subdivision: inconsistent one-rings");
        }
        points[static_cast<std::size_t>(i)] = v;
    };
    const auto corners = t.face_vertices(face);
    for (int k = 0; k < degree; ++k) {
        const auto p =
            triangle ? triangle_positions[static_cast<std::size_t>(k)] : positions[static_cast<std::size_t>(k)];
        // Face `face` leaves corner k along direction first, enters it along first + 1.
        const int first = triangle ? 2 * k : k;
        const auto around = faces_from(t, corners[static_cast<std::size_t>(k)], face);
        for (int q = 0; q < ring; ++q) {
            const auto [g, m] = around[static_cast<std::size_t>(q)];
            const auto d1 = directions[static_cast<std::size_t>((first + q) % ring)];
            const auto d2 = directions[static_cast<std::size_t>((first + q + 1) % ring)];
            const auto gv = t.face_vertices(g);
            const auto at = [&](int i) { return gv[static_cast<std::size_t>((m + i) % degree)]; };
            put(p[0], p[1], at(0));
            put(p[0] + d1[0], p[1] + d1[1], at(1));
            if constexpr (triangle) {
                put(p[0] + d2[0], p[1] + d2[1], at(2));
            } else {
                put(p[0] + d1[0] + d2[0], p[1] + d1[1] + d2[1], at(2));
                put(p[0] + d2[0], p[1] + d2[1], at(3));
            }
        }
    }
    for (const Index v : points) {
        if (v == invalid_index) {
            throw std::logic_error("deep_subdivision: patch point not found");
        }
    }
    return points;
}

}  // namespace

DeepSubdivision::DeepSubdivision(const Topology& topology, const Points& X, SchemeKind scheme,
                                 const SchemeOptions& options, int levels)
    : scheme_(scheme), levels_(levels) {
    if (scheme != SchemeKind::CatmullClark && scheme != SchemeKind::Loop) {
        throw std::runtime_error(std::string("deep_subdivision: scheme ") + to_string(scheme) +
                                 " is not supported (CatmullClark or Loop)");
    }
    if (levels < 1 || levels > 8) {
        throw std::runtime_error("deep_subdivision: levels " + std::to_string(levels) + " out of range [1, 8]");
    }
    if (X.rows() != topology.num_vertices()) {
        throw std::runtime_error("deep_subdivision: " + std::to_string(X.rows()) + " positions for " +
                                 std::to_string(topology.num_vertices()) + " vertices");
    }
    const bool triangle = scheme == SchemeKind::Loop;
    // Ptex faces as Far::PtexIndices numbers them.
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const Index n = topology.face_degree(f);
        if (triangle || n == 4) {
            ptex_face_.push_back(f);
            ptex_corner_.push_back(-1);
        } else {
            for (Index k = 0; k < n; ++k) {
                ptex_face_.push_back(f);
                ptex_corner_.push_back(k);
            }
        }
    }
    Topology parent = topology;
    Points points = X;
    for (int l = 0; l < levels; ++l) {
        Level level = refine(parent, scheme, options);
        std::vector<Index> offsets(static_cast<std::size_t>(parent.num_faces()) + 1, 0);
        for (Index f = 0; f < parent.num_faces(); ++f) {
            offsets[static_cast<std::size_t>(f) + 1] =
                offsets[static_cast<std::size_t>(f)] + (triangle ? 4 : parent.face_degree(f));
        }
        std::vector<Index> children(static_cast<std::size_t>(offsets.back()), invalid_index);
        const Provenance& where = level.provenance;
        for (Index c = 0; c < level.topology.num_faces(); ++c) {
            const Index f = where.face_parent[static_cast<std::size_t>(c)];
            const Index corner = where.face_parent_corner[static_cast<std::size_t>(c)];
            const Index k = corner == invalid_index ? 3 : corner;
            children[static_cast<std::size_t>(offsets[static_cast<std::size_t>(f)] + k)] = c;
        }
        child_offset_.push_back(std::move(offsets));
        children_.push_back(std::move(children));
        points = level.S0 * points;
        parent = std::move(level.topology);
    }
    finest_ = std::move(parent);
    finest_points_ = std::move(points);
}

DeepSubdivision::Located DeepSubdivision::locate(const SurfacePoint& point) const {
    if (point.face < 0 || point.face >= num_ptex_faces()) {
        throw std::runtime_error("deep_subdivision: ptex face " + std::to_string(point.face) + " out of range [0, " +
                                 std::to_string(num_ptex_faces()) + ")");
    }
    const bool triangle = scheme_ == SchemeKind::Loop;
    constexpr double tolerance = 1e-12;
    if (outside(triangle, point.u, point.v) > tolerance) {
        throw std::runtime_error("deep_subdivision: (u, v) = (" + std::to_string(point.u) + ", " +
                                 std::to_string(point.v) + ") outside the ptex domain");
    }
    Located at;
    at.s = point.u;
    at.t = point.v;
    clamp_into(triangle, at.s, at.t);
    at.K.setIdentity();
    const auto p = static_cast<std::size_t>(point.face);
    at.face = ptex_face_[p];
    int level = 0;
    if (ptex_corner_[p] >= 0) {  // an n-gon's sub-face k is child k of the first refinement
        at.face =
            children_[0]
                     [static_cast<std::size_t>(child_offset_[0][static_cast<std::size_t>(at.face)] + ptex_corner_[p])];
        level = 1;
    }
    for (; level < levels_; ++level) {
        const Index base = child_offset_[static_cast<std::size_t>(level)][static_cast<std::size_t>(at.face)];
        constexpr int num_children = 4;  // quad split or triangle split
        int best = -1;
        double best_outside = 0.0;
        Vec2 best_local;
        Eigen::Matrix2d best_inverse;
        for (int k = 0; k < num_children; ++k) {
            const ChildFrame frame = child_frame(triangle, k);
            const Eigen::Matrix2d& J = frame.J;
            const double det = J(0, 0) * J(1, 1) - J(0, 1) * J(1, 0);  // ±1/4: the inverse is exact
            Eigen::Matrix2d inverse;
            inverse << J(1, 1) / det, -J(0, 1) / det, -J(1, 0) / det, J(0, 0) / det;
            const Vec2 local = inverse * (Vec2(at.s, at.t) - frame.origin);
            const double d = outside(triangle, local.x(), local.y());
            if (best < 0 || d < best_outside) {
                best = k;
                best_outside = d;
                best_local = local;
                best_inverse = inverse;
            }
        }
        at.face = children_[static_cast<std::size_t>(level)][static_cast<std::size_t>(base + best)];
        at.s = best_local.x();
        at.t = best_local.y();
        clamp_into(triangle, at.s, at.t);
        at.K = best_inverse * at.K;
    }
    return at;
}

bool DeepSubdivision::is_regular_at(const SurfacePoint& point) const {
    return irregularity(finest_, locate(point).face, scheme_ == SchemeKind::Loop).empty();
}

Eigen::Matrix<double, 6, 3> DeepSubdivision::evaluate(const SurfacePoint& point) const {
    const bool triangle = scheme_ == SchemeKind::Loop;
    const Located at = locate(point);
    const std::string why = irregularity(finest_, at.face, triangle);
    if (!why.empty()) {
        throw std::runtime_error("deep_subdivision: ptex point (" + std::to_string(point.face) + ", " +
                                 std::to_string(point.u) + ", " + std::to_string(point.v) + ") lies in level-" +
                                 std::to_string(levels_) + " face " + std::to_string(at.face) +
                                 ", which is not a regular interior patch (" + why +
                                 "); pick points farther from extraordinary vertices and features, or more levels");
    }
    Eigen::Matrix<double, 6, 3> local = Eigen::Matrix<double, 6, 3>::Zero();  // derivatives in (s, t)
    if (triangle) {
        const auto cvs = gather<12>(finest_, at.face);
        Eigen::Matrix<double, 6, 12> w;
        quartic_box_spline_patch_weights(at.s, at.t, w);
        for (int i = 0; i < 12; ++i) {
            local += w.col(i) * finest_points_.row(cvs[static_cast<std::size_t>(i)]);
        }
    } else {
        const auto cvs = gather<16>(finest_, at.face);
        Eigen::Matrix<double, 6, 16> w;
        cubic_bspline_patch_weights(at.s, at.t, w);
        for (int i = 0; i < 16; ++i) {
            local += w.col(i) * finest_points_.row(cvs[static_cast<std::size_t>(i)]);
        }
    }
    // (s, t) = K (u, v) + c: ∇_uv = Kᵀ ∇_st and H_uv = Kᵀ H_st K, per coordinate.
    const Eigen::Matrix2d& K = at.K;
    Eigen::Matrix<double, 6, 3> out;
    out.row(0) = local.row(0);
    out.row(1) = K(0, 0) * local.row(1) + K(1, 0) * local.row(2);
    out.row(2) = K(0, 1) * local.row(1) + K(1, 1) * local.row(2);
    for (int c = 0; c < 3; ++c) {
        Eigen::Matrix2d H;
        H << local(3, c), local(4, c), local(4, c), local(5, c);
        const Eigen::Matrix2d Huv = K.transpose() * H * K;
        out(3, c) = Huv(0, 0);
        out(4, c) = Huv(0, 1);
        out(5, c) = Huv(1, 1);
    }
    return out;
}

Eigen::Matrix<double, 6, 3> deep_subdivision_limit(const Topology& topology, const Points& X, SchemeKind scheme,
                                                   const SchemeOptions& options, const SurfacePoint& point,
                                                   int levels) {
    return DeepSubdivision(topology, X, scheme, options, levels).evaluate(point);
}

}  // namespace limsurf::test
