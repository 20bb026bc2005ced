// Triangle-triangle intersection by orientation predicates, found through a uniform grid
// (see the header for the rule and its peer).
#include "limsurf/mesh/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"

namespace limsurf {
namespace {

using Vec = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

int sign(double x) noexcept {
    return (x > 0.0) - (x < 0.0);
}

// > 0 when d lies on the side of the plane (a, b, c) that (b − a) × (c − a) points to.
int orient3d(const Vec& a, const Vec& b, const Vec& c, const Vec& d) noexcept {
    return sign((b - a).cross(c - a).dot(d - a));
}

int orient2d(const Vec2& a, const Vec2& b, const Vec2& c) noexcept {
    return sign((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}

// Coplanar geometry is decided in the coordinate plane the triangle's normal is most nearly
// perpendicular to, where the projection keeps orientations.
struct Projection {
    int x = 0, y = 1;
    explicit Projection(const Vec& normal) noexcept {
        const Vec n = normal.cwiseAbs();
        const int drop = n.x() >= n.y() && n.x() >= n.z() ? 0 : (n.y() >= n.z() ? 1 : 2);
        x = (drop + 1) % 3;
        y = (drop + 2) % 3;
    }
    [[nodiscard]] Vec2 operator()(const Vec& p) const noexcept { return {p[x], p[y]}; }
};

// p on the closed segment ab, given that the three are collinear.
bool within(const Vec2& a, const Vec2& b, const Vec2& p) noexcept {
    return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= p.y() &&
           p.y() <= std::max(a.y(), b.y());
}

bool segments_meet_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) noexcept {
    const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) {
        return true;
    }
    return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
           (o4 == 0 && within(c, d, b));
}

bool point_in_triangle_2d(const Vec2& p, const std::array<Vec2, 3>& t) noexcept {
    const int s0 = orient2d(t[0], t[1], p), s1 = orient2d(t[1], t[2], p), s2 = orient2d(t[2], t[0], p);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

bool segment_meets_triangle_2d(const Vec2& p, const Vec2& q, const std::array<Vec2, 3>& t) noexcept {
    return point_in_triangle_2d(p, t) || segments_meet_2d(p, q, t[0], t[1]) || segments_meet_2d(p, q, t[1], t[2]) ||
           segments_meet_2d(p, q, t[2], t[0]);
}

using Triangle = std::array<Vec, 3>;

Vec normal_of(const Triangle& t) noexcept {
    return (t[1] - t[0]).cross(t[2] - t[0]);
}

std::array<Vec2, 3> project(const Projection& to_2d, const Triangle& t) noexcept {
    return {to_2d(t[0]), to_2d(t[1]), to_2d(t[2])};
}

// The closed segment pq meets the closed triangle t.
bool segment_meets_triangle(const Vec& p, const Vec& q, const Triangle& t) noexcept {
    const int op = orient3d(t[0], t[1], t[2], p), oq = orient3d(t[0], t[1], t[2], q);
    if (op == oq && op != 0) {
        return false;  // both strictly on one side of the plane
    }
    if (op == 0 && oq == 0) {
        const Projection to_2d(normal_of(t));
        return segment_meets_triangle_2d(to_2d(p), to_2d(q), project(to_2d, t));
    }
    // pq reaches the plane: the point where it does lies in t when the line pq passes on the same
    // side of the three edges.
    const int s0 = orient3d(p, q, t[0], t[1]), s1 = orient3d(p, q, t[1], t[2]), s2 = orient3d(p, q, t[2], t[0]);
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
}

bool disjoint_triangles_meet(const Triangle& a, const Triangle& b) noexcept {
    const auto all_one_side = [](const Triangle& plane, const Triangle& t) {
        const int s0 = orient3d(plane[0], plane[1], plane[2], t[0]);
        const int s1 = orient3d(plane[0], plane[1], plane[2], t[1]);
        const int s2 = orient3d(plane[0], plane[1], plane[2], t[2]);
        return s0 == s1 && s1 == s2 && s0 != 0;
    };
    if (all_one_side(a, b) || all_one_side(b, a)) {
        return false;
    }
    // Two triangles meet exactly when an edge of one meets the other: their intersection is convex,
    // and its extreme points lie on edges (this also covers the coplanar case).
    for (int i = 0; i < 3; ++i) {
        if (segment_meets_triangle(a[i], a[(i + 1) % 3], b) || segment_meets_triangle(b[i], b[(i + 1) % 3], a)) {
            return true;
        }
    }
    return false;
}

// a = (p, a1, a2), b = (p, b1, b2) with p shared: they meet elsewhere than p exactly when the edge
// opposite p of one meets the other (their intersection is convex and holds p).
bool triangles_with_a_vertex_meet(const Triangle& a, const Triangle& b) noexcept {
    return segment_meets_triangle(a[1], a[2], b) || segment_meets_triangle(b[1], b[2], a);
}

// a = (e0, e1, c), b = (e0, e1, d) with the edge e0 e1 shared: they overlap when d lies in a's plane
// on c's side of the edge.
bool triangles_with_an_edge_overlap(const Triangle& a, const Triangle& b) noexcept {
    if (orient3d(a[0], a[1], a[2], b[2]) != 0) {
        return false;
    }
    const Projection to_2d(normal_of(a));
    const int c_side = orient2d(to_2d(a[0]), to_2d(a[1]), to_2d(a[2]));
    const int d_side = orient2d(to_2d(a[0]), to_2d(a[1]), to_2d(b[2]));
    return c_side != 0 && c_side == d_side;
}

// Rotates the corners of each triangle so that the shared vertices come first, in the same order.
bool pair_intersects(const Points& points, const Triangles& triangles, Index i, Index j) {
    std::array<Index, 3> ti{triangles(i, 0), triangles(i, 1), triangles(i, 2)};
    std::array<Index, 3> tj{triangles(j, 0), triangles(j, 1), triangles(j, 2)};
    std::array<Index, 3> shared_i{}, shared_j{};
    int shared = 0;
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            if (ti[a] == tj[b]) {
                shared_i[shared] = a;
                shared_j[shared] = b;
                ++shared;
            }
        }
    }
    const auto corners = [&](const std::array<Index, 3>& t, std::array<int, 3> order) {
        return Triangle{points.row(t[order[0]]).transpose(), points.row(t[order[1]]).transpose(),
                        points.row(t[order[2]]).transpose()};
    };
    const auto rest = [](int x, int y) { return 3 - x - y; };
    switch (shared) {
    case 0:
        return disjoint_triangles_meet(corners(ti, {0, 1, 2}), corners(tj, {0, 1, 2}));
    case 1: {
        const int a = shared_i[0], b = shared_j[0];
        return triangles_with_a_vertex_meet(corners(ti, {a, (a + 1) % 3, (a + 2) % 3}),
                                            corners(tj, {b, (b + 1) % 3, (b + 2) % 3}));
    }
    case 2:
        return triangles_with_an_edge_overlap(corners(ti, {shared_i[0], shared_i[1], rest(shared_i[0], shared_i[1])}),
                                              corners(tj, {shared_j[0], shared_j[1], rest(shared_j[0], shared_j[1])}));
    default:
        return false;  // the same three vertices: one triangle twice (or a degenerate one)
    }
}

void check_mesh(const Points& points, const Triangles& triangles) {
    for (Index p = 0; p < points.rows(); ++p) {
        LIMSURF_CHECK(points.row(p).allFinite(), InputError, "point ", p, " is not finite");
    }
    for (Index t = 0; t < triangles.rows(); ++t) {
        for (int c = 0; c < 3; ++c) {
            LIMSURF_CHECK(triangles(t, c) >= 0 && triangles(t, c) < points.rows(), InputError, "triangle ", t,
                          " corner ", c, ": index ", triangles(t, c), " out of range (", points.rows(), " points)");
        }
    }
}

bool degenerate(const Triangles& triangles, Index t) noexcept {
    return triangles(t, 0) == triangles(t, 1) || triangles(t, 1) == triangles(t, 2) ||
           triangles(t, 0) == triangles(t, 2);
}

struct Box {
    Vec lo, hi;
};

// Integer cell coordinates of the grid; a key packs the three into one 64-bit number.
struct Grid {
    Vec origin;
    double cell = 1.0;
    std::array<std::int64_t, 3> size{};

    [[nodiscard]] std::array<std::int64_t, 3> cell_of(const Vec& p) const noexcept {
        std::array<std::int64_t, 3> c{};
        for (int k = 0; k < 3; ++k) {
            c[k] = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((p[k] - origin[k]) / cell)), 0,
                                            size[k] - 1);
        }
        return c;
    }
    [[nodiscard]] std::int64_t key(const std::array<std::int64_t, 3>& c) const noexcept {
        return (c[0] * size[1] + c[1]) * size[2] + c[2];
    }
};

// Cells about twice the mean largest extent of a triangle's box, so that a triangle covers a few
// cells and a cell holds a few triangles; at most 10^4 cells per axis; and coarser (doubled until it
// holds) when the boxes would cover more than 16 cells each on average plus 10^6 in all — a few
// triangles far larger than the rest would otherwise list themselves in millions of cells.
Grid make_grid(const std::vector<Box>& boxes) {
    Box all{Vec::Constant(std::numeric_limits<double>::infinity()),
            Vec::Constant(-std::numeric_limits<double>::infinity())};
    double extent_sum = 0.0;
    for (const Box& b : boxes) {
        all.lo = all.lo.cwiseMin(b.lo);
        all.hi = all.hi.cwiseMax(b.hi);
        extent_sum += (b.hi - b.lo).maxCoeff();
    }
    Grid grid;
    grid.origin = all.lo;
    const double span = std::max((all.hi - all.lo).maxCoeff(), std::numeric_limits<double>::min());
    grid.cell = extent_sum > 0.0 ? 2.0 * extent_sum / static_cast<double>(boxes.size()) : span;
    grid.cell = std::max(grid.cell, span / 1e4);
    const double budget = 16.0 * static_cast<double>(boxes.size()) + 1e6;
    for (;;) {
        for (int k = 0; k < 3; ++k) {
            grid.size[k] = static_cast<std::int64_t>(std::floor((all.hi[k] - all.lo[k]) / grid.cell)) + 1;
        }
        double entries = 0.0;
        for (const Box& b : boxes) {
            const auto lo = grid.cell_of(b.lo), hi = grid.cell_of(b.hi);
            entries += static_cast<double>(hi[0] - lo[0] + 1) * static_cast<double>(hi[1] - lo[1] + 1) *
                       static_cast<double>(hi[2] - lo[2] + 1);
        }
        if (entries <= budget || grid.cell >= span) {
            return grid;
        }
        grid.cell *= 2.0;
    }
}

bool boxes_overlap(const Box& a, const Box& b) noexcept {
    return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

}  // namespace

std::vector<std::array<Index, 2>> intersecting_triangle_pairs(const Points& given, const Triangles& triangles,
                                                              std::size_t max_pairs) {
    check_mesh(given, triangles);
    // The tests multiply coordinates (cubes of them): points 1e200 across overflowed them and a
    // cube "met itself" in tens of thousands of pairs. Far from order one the points are brought
    // there by a power of two, which is exact (every product scales exactly: the same verdicts);
    // near it they are used as they are.
    const int e = magnitude_exponent(given);
    const Points scaled = std::abs(e) > 64 ? Points(times_power_of_two(given, -e)) : Points();
    const Points& points = std::abs(e) > 64 ? scaled : given;
    std::vector<Index> live;
    std::vector<Box> boxes(static_cast<std::size_t>(triangles.rows()));
    for (Index t = 0; t < triangles.rows(); ++t) {
        if (degenerate(triangles, t)) {
            continue;
        }
        live.push_back(t);
        Box& b = boxes[static_cast<std::size_t>(t)];
        b.lo = b.hi = points.row(triangles(t, 0)).transpose();
        for (int c = 1; c < 3; ++c) {
            b.lo = b.lo.cwiseMin(points.row(triangles(t, c)).transpose());
            b.hi = b.hi.cwiseMax(points.row(triangles(t, c)).transpose());
        }
    }
    std::vector<std::array<Index, 2>> pairs;
    if (live.size() < 2) {
        return pairs;
    }
    std::vector<Box> live_boxes;
    live_boxes.reserve(live.size());
    for (Index t : live) {
        live_boxes.push_back(boxes[static_cast<std::size_t>(t)]);
    }
    const Grid grid = make_grid(live_boxes);

    // (cell, triangle) for every cell a triangle's box overlaps, sorted by cell.
    std::vector<std::pair<std::int64_t, Index>> entries;
    entries.reserve(live.size() * 4);
    for (Index t : live) {
        const Box& b = boxes[static_cast<std::size_t>(t)];
        const auto lo = grid.cell_of(b.lo), hi = grid.cell_of(b.hi);
        for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
            for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
                for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
                    entries.emplace_back(grid.key({x, y, z}), t);
                }
            }
        }
    }
    std::sort(entries.begin(), entries.end());

    for (std::size_t begin = 0; begin < entries.size();) {
        std::size_t end = begin;
        while (end < entries.size() && entries[end].first == entries[begin].first) {
            ++end;
        }
        for (std::size_t a = begin; a < end; ++a) {
            for (std::size_t b = a + 1; b < end; ++b) {
                const Index i = entries[a].second, j = entries[b].second;
                const Box& bi = boxes[static_cast<std::size_t>(i)];
                const Box& bj = boxes[static_cast<std::size_t>(j)];
                // Test the pair only in the cell of the low corner of the boxes' overlap: once.
                if (!boxes_overlap(bi, bj) || grid.key(grid.cell_of(bi.lo.cwiseMax(bj.lo))) != entries[a].first) {
                    continue;
                }
                if (pair_intersects(points, triangles, i, j)) {
                    pairs.push_back({std::min(i, j), std::max(i, j)});
                }
            }
        }
        begin = end;
    }
    std::sort(pairs.begin(), pairs.end());
    if (pairs.size() > max_pairs) {
        pairs.resize(max_pairs);
    }
    return pairs;
}

WeldedTriangles weld_coincident_points(const Points& given, const Triangles& triangles, double given_tolerance) {
    LIMSURF_CHECK(std::isfinite(given_tolerance) && given_tolerance >= 0.0, InputError,
                  "weld tolerance must be finite and >= 0, got ", given_tolerance);
    check_mesh(given, triangles);
    // Distances are compared by their squares: at 1e-200 those underflowed to 0 and every nearby
    // point merged. Far from order one, points and tolerance are compared scaled by one power of
    // two (exact, as in intersecting_triangle_pairs); the welded points are the given ones.
    const int e = magnitude_exponent(given);
    const bool rescale = std::abs(e) > 64;
    const Points scaled = rescale ? Points(times_power_of_two(given, -e)) : Points();
    const Points& points = rescale ? scaled : given;
    const double tolerance = rescale ? std::ldexp(given_tolerance, -e) : given_tolerance;
    // Cells of the tolerance's size: a point within the tolerance of another lies in one of the 27
    // cells around it. With tolerance 0 only equal points merge, and any cell size works.
    double largest = 0.0;
    for (Index p = 0; p < points.rows(); ++p) {
        largest = std::max(largest, points.row(p).cwiseAbs().maxCoeff());
    }
    // A cell index must fit 53 bits; a tolerance far below the coordinates' rounding gains nothing.
    const double cell = std::max({tolerance, largest * 1e-15, std::numeric_limits<double>::min()});
    const auto cell_of = [&](Index p) {
        std::array<std::int64_t, 3> c{};
        for (int k = 0; k < 3; ++k) {
            c[k] = static_cast<std::int64_t>(std::floor(points(p, k) / cell));
        }
        return c;
    };
    const auto hash = [](const std::array<std::int64_t, 3>& c) {
        std::uint64_t h = 1469598103934665603ULL;
        for (std::int64_t v : c) {
            h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ULL;
        }
        return h;
    };
    std::unordered_map<std::uint64_t, std::vector<Index>> representatives_in;  // by cell hash
    WeldedTriangles welded;
    welded.index.assign(static_cast<std::size_t>(points.rows()), invalid_index);
    std::vector<Index> representative_of_new;  // input index of each welded point
    for (Index p = 0; p < points.rows(); ++p) {
        const auto c = cell_of(p);
        Index found = invalid_index;
        for (std::int64_t dx = -1; dx <= 1 && found == invalid_index; ++dx) {
            for (std::int64_t dy = -1; dy <= 1 && found == invalid_index; ++dy) {
                for (std::int64_t dz = -1; dz <= 1 && found == invalid_index; ++dz) {
                    const auto it = representatives_in.find(hash({c[0] + dx, c[1] + dy, c[2] + dz}));
                    if (it == representatives_in.end()) {
                        continue;
                    }
                    for (Index r : it->second) {
                        if ((points.row(r) - points.row(p)).norm() <= tolerance) {
                            found = r;
                            break;
                        }
                    }
                }
            }
        }
        if (found == invalid_index) {
            representatives_in[hash(c)].push_back(p);
            welded.index[static_cast<std::size_t>(p)] = static_cast<Index>(representative_of_new.size());
            representative_of_new.push_back(p);
        } else {
            welded.index[static_cast<std::size_t>(p)] = welded.index[static_cast<std::size_t>(found)];
        }
    }
    welded.points.resize(static_cast<Index>(representative_of_new.size()), 3);
    for (std::size_t k = 0; k < representative_of_new.size(); ++k) {
        welded.points.row(static_cast<Index>(k)) = given.row(representative_of_new[k]);
    }
    welded.triangles.resize(triangles.rows(), 3);
    for (Index t = 0; t < triangles.rows(); ++t) {
        for (int c = 0; c < 3; ++c) {
            welded.triangles(t, c) = welded.index[static_cast<std::size_t>(triangles(t, c))];
        }
    }
    return welded;
}

}  // namespace limsurf
