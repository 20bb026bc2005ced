// Identities of the limit basis (Catmull–Clark and Loop) on every bundled mesh:
// partition of unity, derivative weights against finite differences, C1
// continuity across patch edges and at control vertices, agreement of the limit
// at a vertex from all incident faces, and the approach to an extraordinary
// vertex (points down to 2^-40 away).
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/refine.h"
#include "limsurf/scheme/tuned_weights.h"
#include "support/mesh_zoo.h"
#include "support/opensubdiv_shapes.h"

namespace limsurf::test {
namespace {

struct Case {
    std::string mesh;
    SchemeKind scheme;
};

void PrintTo(const Case& c, std::ostream* os) {
    *os << c.mesh << "/" << to_string(c.scheme);
}

std::vector<Case> all_cases() {
    std::vector<Case> cases;
    for (const auto& m : bundled_meshes()) {
        cases.push_back({m.name, SchemeKind::CatmullClark});
        if (m.triangles_only) {
            cases.push_back({m.name, SchemeKind::Loop});
        }
        // Doo–Sabin through the same API: closed meshes without tags (its limit surface
        // covers interior faces only, and it has no crease rules).
        if (m.closed && m.name != "cube_creases") {
            cases.push_back({m.name, SchemeKind::DooSabin});
        }
    }
    return cases;
}

struct Loaded {
    Topology topology;
    Points X;
    SchemeOptions options;
    double scale = 1.0;  // bounding-box diagonal
};

Loaded load(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    Loaded m{built.mesh.topology(), built.mesh.positions(), {}, 1.0};
    if (built.mesh.hints().boundary) {
        m.options.boundary = *built.mesh.hints().boundary;
    }
    if (built.mesh.hints().creasing) {
        m.options.creasing = *built.mesh.hints().creasing;
    }
    m.scale = (m.X.colwise().maxCoeff() - m.X.colwise().minCoeff()).norm();
    return m;
}

/// Random points of the domain, including its corners and edges.
std::vector<Eigen::Vector2d> sample_domain(bool quad, std::mt19937& rng, int count) {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<Eigen::Vector2d> points = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0, 0.5}};
    if (quad) {
        points.push_back({1, 1});
        points.push_back({1, 0.5});
    }
    while (static_cast<int>(points.size()) < count) {
        Eigen::Vector2d p(uniform(rng), uniform(rng));
        if (!quad && p.sum() > 1.0) {
            p = Eigen::Vector2d(1, 1) - p;
        }
        points.push_back(p);
    }
    return points;
}

class LimitIdentity : public ::testing::TestWithParam<Case> {};

TEST_P(LimitIdentity, WeightsArePartitionOfUnity) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    const bool quad = basis.domain() == ParameterDomain::Quad;
    std::mt19937 rng(7);
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        for (const auto& uv : sample_domain(quad, rng, 12)) {
            const LimitWeights w = basis.evaluate({p, uv.x(), uv.y()});
            ASSERT_NEAR(w.w.row(0).sum(), 1.0, 1e-12) << "ptex " << p << " at " << uv.transpose();
            // At a domain corner that is an extraordinary or corner vertex, derivatives are
            // taken 2^-61 away and second derivatives may diverge there: check the value only.
            const bool corner = (uv.x() == 0.0 || uv.x() == 1.0) && (uv.y() == 0.0 || uv.y() == 1.0);
            for (int r = 1; r < (corner ? 1 : 6); ++r) {
                const double size = w.w.row(r).cwiseAbs().sum();
                ASSERT_NEAR(w.w.row(r).sum(), 0.0, 1e-12 * std::max(1.0, size)) << "row " << r << " ptex " << p;
            }
        }
    }
}

TEST_P(LimitIdentity, DerivativesMatchFiniteDifferences) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    const bool quad = basis.domain() == ParameterDomain::Quad;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uniform(0.05, 0.95);
    const double h = 1e-5;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        for (int i = 0; i < 4; ++i) {
            double u = uniform(rng), v = uniform(rng);
            if (!quad && u + v > 0.9) {
                u *= 0.45;
                v *= 0.45;
            }
            // Doo–Sabin is C¹ only across the boundaries of its polynomial pieces — the quadrant lines
            // u, v = ½ and the dyadic lines 2⁻ᵏ, 1 − 2⁻ᵏ of the tiles towards its extraordinary
            // points: a difference quotient straddling one measures a jump, not a derivative. With
            // 10⁴ samples (tetra_4) that happens; keep the samples 10 h away from those lines.
            if (GetParam().scheme == SchemeKind::DooSabin) {
                const auto off_the_lines = [&](double x) {
                    for (int k = 1; k <= 30; ++k) {
                        for (const double line : {std::ldexp(1.0, -k), 1.0 - std::ldexp(1.0, -k)}) {
                            if (std::abs(x - line) < 10 * h) {
                                return line + 10 * h;
                            }
                        }
                    }
                    return x;
                };
                u = off_the_lines(u);
                v = off_the_lines(v);
            }
            const auto at = [&](double du, double dv) { return basis.evaluate(m.X, {p, u + du, v + dv}); };
            const auto c = at(0, 0);
            const auto pu = at(h, 0), mu = at(-h, 0), pv = at(0, h), mv = at(0, -h);
            const double tol = 1e-6 * m.scale;
            EXPECT_LT((c.row(1) - (pu.row(0) - mu.row(0)) / (2 * h)).norm(), tol) << "du, ptex " << p;
            EXPECT_LT((c.row(2) - (pv.row(0) - mv.row(0)) / (2 * h)).norm(), tol) << "dv, ptex " << p;
            EXPECT_LT((c.row(3) - (pu.row(1) - mu.row(1)) / (2 * h)).norm(), 1e-4 * m.scale) << "duu, ptex " << p;
            EXPECT_LT((c.row(4) - (pv.row(1) - mv.row(1)) / (2 * h)).norm(), 1e-4 * m.scale) << "duv, ptex " << p;
            EXPECT_LT((c.row(5) - (pv.row(2) - mv.row(2)) / (2 * h)).norm(), 1e-4 * m.scale) << "dvv, ptex " << p;
        }
    }
}

/// The corners of a control face in its ptex domain (one ptex face per control face).
Eigen::Vector2d corner_uv(bool quad, Index k) {
    static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const Eigen::Vector2d triangle[3] = {{0, 0}, {1, 0}, {0, 1}};
    return quad ? square[k] : triangle[k];
}

TEST_P(LimitIdentity, ContinuousWithContinuousNormalsAcrossEdges) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    const bool quad = basis.domain() == ParameterDomain::Quad;
    const Index regular_degree = quad ? 4 : 3;
    const Topology& t = m.topology;
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto faces = t.edge_faces(e);
        if (faces.size() != 2 || t.face_degree(faces[0]) != regular_degree ||
            t.face_degree(faces[1]) != regular_degree || !basis.has_limit_surface(basis.first_ptex_face(faces[0])) ||
            !basis.has_limit_surface(basis.first_ptex_face(faces[1])) || t.edge_sharpness(e) > 0.0) {
            continue;
        }
        const auto [a, b] = t.edge_vertices(e);
        // Normals at a vertex on a crease, a corner or the boundary differ between its faces.
        const auto sharp_vertex = [&](Index v) {
            if (t.is_boundary_vertex(v) || t.vertex_sharpness(v) > 0.0) {
                return true;
            }
            for (Index x : t.vertex_edges(v)) {
                if (t.edge_sharpness(x) > 0.0) {
                    return true;
                }
            }
            return false;
        };
        for (double tau : {0.0, 0.25, 0.5, 0.9, 1.0}) {
            const bool check_normal = !((tau == 0.0 && sharp_vertex(a)) || (tau == 1.0 && sharp_vertex(b)));
            Eigen::Matrix<double, 6, 3> side[2];
            for (int s = 0; s < 2; ++s) {
                const Index f = faces[static_cast<std::size_t>(s)];
                const Index p = basis.first_ptex_face(f);
                const auto fv = t.face_vertices(f);
                const Index ka = static_cast<Index>(std::find(fv.begin(), fv.end(), a) - fv.begin());
                const Index kb = static_cast<Index>(std::find(fv.begin(), fv.end(), b) - fv.begin());
                const Eigen::Vector2d uv = (1 - tau) * corner_uv(quad, ka) + tau * corner_uv(quad, kb);
                side[s] = basis.evaluate(m.X, {p, uv.x(), uv.y()});
            }
            EXPECT_LT((side[0].row(0) - side[1].row(0)).norm(), 1e-12 * m.scale) << "edge " << e << " at " << tau;
            const Eigen::Vector3d n0 = side[0].row(1).cross(side[0].row(2)).transpose();
            const Eigen::Vector3d n1 = side[1].row(1).cross(side[1].row(2)).transpose();
            if (check_normal && n0.norm() > 1e-9 * m.scale * m.scale && n1.norm() > 1e-9 * m.scale * m.scale) {
                EXPECT_LT((n0.normalized() - n1.normalized()).norm(), 1e-8) << "normal, edge " << e << " at " << tau;
            }
        }
    }
}

TEST_P(LimitIdentity, VertexLimitAgreesFromEveryFace) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    const Points limit = basis.vertex_limit_matrix() * m.X;
    const Topology& t = m.topology;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const auto faces = t.vertex_faces(v);
        const auto corners = t.vertex_face_corners(v);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const Index first = basis.first_ptex_face(faces[i]);
            const bool split = basis.ptex_face(first).corner >= 0;
            const Index p = split ? first + corners[i] : first;
            if (!basis.has_limit_surface(p)) {
                continue;
            }
            const Eigen::Vector2d uv =
                split ? Eigen::Vector2d(0, 0) : corner_uv(basis.domain() == ParameterDomain::Quad, corners[i]);
            const auto here = basis.evaluate(m.X, {p, uv.x(), uv.y()}, DerivativeOrder::Value);
            EXPECT_LT((here.row(0) - limit.row(v)).norm(), 1e-12 * m.scale) << "vertex " << v << " face " << faces[i];
        }
    }
}

// Asking for fewer derivatives gives the same leading rows and zeros below.
TEST_P(LimitIdentity, LowerOrdersAreTheLeadingRows) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    std::mt19937 rng(23);
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        for (const auto& uv : sample_domain(basis.domain() == ParameterDomain::Quad, rng, 7)) {
            const SurfacePoint point{p, uv.x(), uv.y()};
            const LimitWeights all = basis.evaluate(point, DerivativeOrder::Second);
            for (const auto& [order, rows] :
                 {std::pair{DerivativeOrder::Value, 1}, std::pair{DerivativeOrder::First, 3}}) {
                const LimitWeights some = basis.evaluate(point, order);
                ASSERT_EQ(some.vertices, all.vertices);
                EXPECT_LT((some.w.topRows(rows) - all.w.topRows(rows)).cwiseAbs().maxCoeff(),
                          1e-12 * std::max(1.0, all.w.topRows(rows).cwiseAbs().maxCoeff()))
                    << "ptex " << p;
                EXPECT_EQ(some.w.bottomRows(6 - rows).cwiseAbs().maxCoeff(), 0.0);
            }
        }
    }
}

/// The positions path (evaluate(X, point, LimitPoint&), X contracted first, down the templates)
/// against the weights applied to X (LimitWeights::apply, down the nodes), for both layouts of X,
/// at every order: the same at-vertex flag, zero rows past the order, results independent of the
/// layout bit for bit, and equal to rounding. "Rounding" is 1e-13 of the mesh's extent times the
/// size of the weights of the row's derivative order (Σ|w| of the row, plus the largest such sum
/// among the rows of that order, plus 1): the two paths sum in different orders, and where the
/// weights of a row cancel to exactly 0 (∂ss of a boundary patch with phantom points, say) the
/// positions path meets the same cancellation among points of size `extent` instead (measured:
/// up to 4e-15 × extent). Near a corner both paths descend k levels and the chain rule multiplies
/// the rounding of the patch points by 2^(k·d) for derivatives of order d: derivatives are
/// compared with that factor (δ^-d for a point δ from the nearest domain corner) and not at the
/// corners themselves, where a deep descent (an extraordinary or creased vertex: derivatives taken
/// 2^-61 away, limit_basis.h) leaves rounding noise in both. A wrong patch, table or template step
/// is off by O(extent).
/// @p got (rows value, ∂u, ∂v, ∂uu, ∂uv, ∂vv over x, y, z; the first @p rows asked for) against
/// the weights @p w at @p point applied to @p X: to rounding in the size of the weights, a derivative
/// of order d amplified by 1 / δ^d at a point δ from a domain corner (the conditioning every path
/// shares there), and not compared at the corner itself.
void expect_rows_equal_weights(const LimitBasis& basis, const Points& X, const SurfacePoint& point,
                               const LimitWeights& w, const Eigen::Matrix<double, 6, 3>& got, int rows,
                               const std::string& where) {
    const Eigen::Matrix<double, 6, 3> expected = w.apply(X);
    const double extent = X.cwiseAbs().maxCoeff();
    const Eigen::Matrix<double, 6, 1> sizes = w.w.cwiseAbs().rowwise().sum();
    const double block[3] = {sizes(0), sizes.segment<2>(1).maxCoeff(), sizes.tail<3>().maxCoeff()};
    double corner_distance = std::numeric_limits<double>::infinity();
    for (Index k = 0; k < (basis.domain() == ParameterDomain::Quad ? 4 : 3); ++k) {
        const Eigen::Vector2d c = corner_uv(basis.domain() == ParameterDomain::Quad, k);
        corner_distance = std::min(corner_distance, (Eigen::Vector2d(point.u, point.v) - c).norm());
    }
    for (int r = 0; r < 6; ++r) {
        for (int c = 0; c < 3; ++c) {
            if (r >= rows) {
                ASSERT_EQ(got(r, c), 0.0) << where << " row " << r << " past the order";
                continue;
            }
            const int d = r == 0 ? 0 : r < 3 ? 1 : 2;  // derivative order of the row
            if (d > 0 && (w.at_extraordinary_vertex || corner_distance == 0.0)) {
                continue;
            }
            const double amplification = std::pow(std::max(1.0, 1.0 / corner_distance), d);
            const double tolerance = 1e-13 * extent * (sizes(r) + block[d] + 1.0) * amplification;
            ASSERT_LE(std::abs(got(r, c) - expected(r, c)), tolerance)
                << where << " row " << r << " col " << c << ": " << got(r, c) << " vs " << expected(r, c);
        }
    }
}

constexpr std::array<std::pair<DerivativeOrder, int>, 3> orders{
    std::pair{DerivativeOrder::Value, 1}, std::pair{DerivativeOrder::First, 3}, std::pair{DerivativeOrder::Second, 6}};

void expect_positions_equal_weights(const LimitBasis& basis, const Points& X, const SurfacePoint& point,
                                    const std::string& where) {
    const InterleavedPoints interleaved = X;
    for (const auto& [order, rows] : orders) {
        const LimitWeights w = basis.evaluate(point, order);
        LimitPoint a;
        LimitPoint b;
        basis.evaluate(X, point, a, order);
        basis.evaluate(interleaved, point, b, order);
        ASSERT_EQ(a.d, b.d) << where << ": the layout of X changed the result";
        ASSERT_EQ(a.at_extraordinary_vertex, w.at_extraordinary_vertex) << where;
        ASSERT_EQ(b.at_extraordinary_vertex, w.at_extraordinary_vertex) << where;
        expect_rows_equal_weights(basis, X, point, w, a.d, rows, where);
    }
}

/// The patch LimitBasis::patch gives at @p point holds the point, and on its whole tile (the point
/// and three more) its data X contracted once give the weights' rows. Its control points' weights
/// (with the offset) sum to 1. Doo–Sabin and C2g0 have no such patches; elsewhere only a point at an
/// extraordinary vertex itself may have none.
void expect_patch_equals_weights(const LimitBasis& basis, const Points& X, const SurfacePoint& point,
                                 const std::string& where) {
    LimitPatch patch;
    const bool found = basis.patch(point, patch);
    LimitPatch framed;  // patch_data's: the same patch without its points, and the same data
    Eigen::MatrixXd direct;
    ASSERT_EQ(basis.patch_data(point, X, framed, direct), found) << where;
    if (basis.scheme() == SchemeKind::DooSabin || basis.scheme() == SchemeKind::C2g0) {
        ASSERT_FALSE(found) << where;
        return;
    }
    if (!found) {
        ASSERT_TRUE(basis.evaluate(point, DerivativeOrder::Value).at_extraordinary_vertex)
            << where << ": no patch away from an extraordinary vertex";
        return;
    }
    ASSERT_EQ(patch.size(), basis.domain() == ParameterDomain::Quad ? 16 : 12) << where;
    ASSERT_EQ(patch.points.rows(), patch.size()) << where;
    ASSERT_EQ(patch.points.cols(), static_cast<Index>(patch.vertices.size())) << where;
    ASSERT_EQ(patch.offset.size(), static_cast<Index>(patch.vertices.size())) << where;
    ASSERT_TRUE(patch.contains(point.u, point.v, 1e-9)) << where << ": the patch misses its point";
    const Eigen::VectorXd sums = patch.points.rowwise().sum().array() + patch.offset.sum();
    ASSERT_LT((sums.array() - 1.0).abs().maxCoeff(), 1e-12) << where << ": control points not affine";
    const Eigen::MatrixXd data = patch.control_data(X);
    ASSERT_EQ(framed.domain, patch.domain) << where;
    ASSERT_EQ(framed.vertices, patch.vertices) << where;
    ASSERT_EQ(framed.origin, patch.origin) << where;
    ASSERT_EQ(framed.axes, patch.axes) << where;
    ASSERT_EQ(framed.points.size() + framed.offset.size(), 0) << where << ": patch_data leaves the points empty";
    ASSERT_EQ(direct.rows(), data.rows()) << where;
    ASSERT_EQ(direct.cols(), data.cols()) << where;
    ASSERT_LE((direct - data).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + X.cwiseAbs().maxCoeff()))
        << where << ": patch_data's data differ from control_data's";
    const Eigen::Vector2d own = patch.parameter(point.u, point.v);
    for (const Eigen::Vector2d& st :
         {own, Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(0.8, 0.1), Eigen::Vector2d(0.1, 0.7)}) {
        const Eigen::Vector2d uv = patch.origin + patch.axes * st;
        const SurfacePoint there{point.face, uv.x(), uv.y()};
        ASSERT_TRUE(patch.contains(uv.x(), uv.y())) << where;
        for (const auto& [order, rows] : orders) {
            Eigen::Matrix<double, 6, Eigen::Dynamic> got;
            patch.evaluate(data, uv.x(), uv.y(), got, order);
            ASSERT_EQ(got.cols(), 3) << where;
            expect_rows_equal_weights(basis, X, there, basis.evaluate(there, order), got, rows,
                                      where + ", patch at (" + std::to_string(st.x()) + ", " + std::to_string(st.y()) +
                                          ")");
        }
    }
}

/// @p check(point, where) at eight sampled points of every ptex face with a limit surface and
/// 2^-3, 2^-17, 2^-45 from its corner 0 (an extraordinary vertex on many faces), with the points
/// @p deeper(k, uvs) adds at each of those depths k.
template <class Deeper, class Check>
void for_each_test_point(const LimitBasis& basis, unsigned seed, const Deeper& deeper, const Check& check) {
    const bool quad = basis.domain() == ParameterDomain::Quad;
    std::mt19937 rng(seed);
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        std::vector<Eigen::Vector2d> uvs = sample_domain(quad, rng, 8);
        for (const int k : {3, 17, 45}) {
            uvs.emplace_back(std::ldexp(1.0, -k), std::ldexp(0.7, -k));
            deeper(k, uvs);
        }
        for (const auto& uv : uvs) {
            check(SurfacePoint{p, uv.x(), uv.y()},
                  "ptex " + std::to_string(p) + " at (" + std::to_string(uv.x()) + ", " + std::to_string(uv.y()) + ")");
        }
    }
}

TEST_P(LimitIdentity, PositionsPathEqualsTheWeightsApplied) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    for_each_test_point(
        basis, 29, [](int, std::vector<Eigen::Vector2d>&) {},
        [&](const SurfacePoint& point, const std::string& where) {
            expect_positions_equal_weights(basis, m.X, point, where);
        });
}

// LimitBasis::patch at the positions path's points: the patch holds the point and gives the weights'
// rows on its whole tile (docs/limit_evaluation.md "Patches").
TEST_P(LimitIdentity, PatchesEqualTheWeightsOnTheirTiles) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    const bool quad = basis.domain() == ParameterDomain::Quad;
    // Triangles: in the middle child k levels deep, 2^-6 from its corners. A Loop middle triangle at
    // a boundary corner is a subtree meeting another class there: the patch is carried by powers of
    // R. (Nearer, the vertex's own conditioning costs the second derivatives of both paths digits
    // this tolerance does not count: 1e-9 at 2^-20.)
    const auto middle_child = [quad](int k, std::vector<Eigen::Vector2d>& uvs) {
        if (quad) {
            return;
        }
        const double d = std::ldexp(1.0, -6);
        for (const Eigen::Vector2d& near : {Eigen::Vector2d(0.5 - d, 1.5 * d), Eigen::Vector2d(0.5 - d, 0.5 - d),
                                            Eigen::Vector2d(1.5 * d, 0.5 - d)}) {
            uvs.push_back(std::ldexp(1.0, -k) * near);
        }
    };
    for_each_test_point(basis, 37, middle_child, [&](const SurfacePoint& point, const std::string& where) {
        expect_patch_equals_weights(basis, m.X, point, where);
    });
}

// The stationary tables against plain local subdivision (LimitEvaluation::Subdivision,
// which never uses them) at points 2^-k from every corner of every ptex face, k up
// to 30: the two paths share only the one-ring extraction and the refinement engine.
// Positions agree to 1e-12 of the mesh size at every k; derivatives up to k = 12.
TEST_P(LimitIdentity, StationaryTablesAgreeWithLocalSubdivisionNearCorners) {
    const Loaded m = load(GetParam().mesh);
    const LimitBasis fast(m.topology, GetParam().scheme, m.options);
    const LimitBasis slow(m.topology, GetParam().scheme, m.options, {}, LimitEvaluation::Subdivision);
    const bool quad = fast.domain() == ParameterDomain::Quad;
    const Index num_ptex = std::min<Index>(fast.num_ptex_faces(), 24);
    for (Index p = 0; p < num_ptex; ++p) {
        if (!fast.has_limit_surface(p)) {
            continue;
        }
        for (Index corner = 0; corner < (quad ? 4 : 3); ++corner) {
            const Eigen::Vector2d c = corner_uv(quad, corner);
            const Eigen::Vector2d inward = (quad ? Eigen::Vector2d(0.5, 0.5) : Eigen::Vector2d(1.0 / 3, 1.0 / 3)) - c;
            for (int k : {1, 5, 12, 20, 30}) {
                const double d = std::ldexp(1.0, -k);
                const Eigen::Vector2d uv = c + d * (inward + Eigen::Vector2d(0.1, -0.05) * (quad ? 1.0 : 0.0));
                const SurfacePoint point{p, uv.x(), uv.y()};
                const auto a = fast.evaluate(m.X, point, DerivativeOrder::First);
                const auto b = slow.evaluate(m.X, point, DerivativeOrder::First);
                EXPECT_LT((a.row(0) - b.row(0)).norm(), 1e-12 * m.scale)
                    << "ptex " << p << " corner " << corner << " at 2^-" << k;
                // Plain subdivision loses ~2^k·eps in derivatives (it differentiates a product of k
                // subdivision matrices); the tables do not. Compare derivatives where the reference holds.
                if (k > 12) {
                    continue;
                }
                const double size = a.row(1).norm() + a.row(2).norm();
                EXPECT_LT((a.topRows(3) - b.topRows(3)).bottomRows(2).norm(),
                          1e-9 * size + std::ldexp(1e-15, k) * m.scale)
                    << "derivatives, ptex " << p << " corner " << corner << " at 2^-" << k;
            }
        }
    }
}

// Tuned weights (iga-tuned-catmull-clark-weights): the same weights given per valence
// or per vertex (to every vertex of that valence) give the same limit surface; they
// change the surface next to the extraordinary vertices only.
TEST(LimitTunedWeights, PerVertexEqualsPerValenceAndActsLocally) {
    const Loaded m = load("quad_valence_5");
    const TunedWeights by_valence = TunedWeights::preset("cup");
    TunedWeights by_vertex;
    for (Index v = 0; v < m.topology.num_vertices(); ++v) {
        if (!m.topology.is_boundary_vertex(v) && m.topology.valence(v) == 5) {
            by_vertex.set_vertex(v, by_valence.at(v, 5));
        }
    }
    const LimitBasis plain(m.topology, SchemeKind::CatmullClark, m.options);
    const LimitBasis a(m.topology, SchemeKind::CatmullClark, m.options, by_valence);
    const LimitBasis b(m.topology, SchemeKind::CatmullClark, m.options, by_vertex);
    std::mt19937 rng(17);
    double changed = 0.0;
    for (Index p = 0; p < a.num_ptex_faces(); ++p) {
        for (const auto& uv : sample_domain(true, rng, 6)) {
            const SurfacePoint point{p, uv.x(), uv.y()};
            const auto x = a.evaluate(m.X, point);
            const auto y = b.evaluate(m.X, point);
            EXPECT_LT((x - y).norm(), 1e-12 * m.scale * std::max(1.0, x.norm() / m.scale))
                << "ptex " << p << " at " << uv.transpose() << "\n"
                << x << "\n"
                << y;
            changed = std::max(changed, (x.row(0) - plain.evaluate(m.X, point).row(0)).norm());
        }
    }
    EXPECT_GT(changed, 1e-6 * m.scale);
}

// With own β, γ ≠ 1 a tuned vertex changes the edge and face points around it, so the patches
// whose support holds it (its two rings of faces) are not plain B-splines: the limit function of
// control values is the same whether evaluated on the control mesh or on the mesh refined once or
// twice with the same weights (values carried by S0), everywhere near the vertex.
TEST(LimitTunedWeights, OwnEdgeAndFaceWeightsAreRefinementInvariant) {
    const Loaded m = load("quad_valence_5");
    TunedWeights w;
    Index tuned = invalid_index;
    for (Index v = 0; v < m.topology.num_vertices(); ++v) {
        if (!m.topology.is_boundary_vertex(v) && m.topology.valence(v) == 5) {
            w.set_vertex(v, {13.9851, 0.6, 0.8});  // β ≠ γ, far from Catmull–Clark's (15, 1, 1)
            tuned = v;
        }
    }
    ASSERT_NE(tuned, invalid_index);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Points P = m.X;
    for (Index i = 0; i < P.rows(); ++i) {
        P.row(i) += 0.1 * m.scale * Eigen::RowVector3d(unit(rng), unit(rng), unit(rng));
    }
    const Level one = refine(m.topology, SchemeKind::CatmullClark, m.options, w);
    const Points P1 = one.S0 * P;
    const LimitBasis coarse(m.topology, SchemeKind::CatmullClark, m.options, w);
    const LimitBasis fine(one.topology, SchemeKind::CatmullClark, m.options, w);
    // Child face of parent quad f at corner k: quad_split numbering (level.h provenance); its ptex
    // (u, v) maps to the parent's by the corner's half-square.
    double largest = 0.0;
    for (Index c = 0; c < one.topology.num_faces(); ++c) {
        const Index f = one.provenance.face_parent[static_cast<std::size_t>(c)];
        const Index k = one.provenance.face_parent_corner[static_cast<std::size_t>(c)];
        if (m.topology.face_degree(f) != 4) {
            continue;
        }
        for (const auto& uv : sample_domain(true, rng, 3)) {
            // The child's value at its own (u, v); the parent's at the same limit point, found by
            // matching positions over the parent's corner quadrant (both are the same surface).
            const auto x = fine.evaluate(P1, {fine.first_ptex_face(c), uv.x(), uv.y()}, DerivativeOrder::Value);
            double best = 1e300;
            for (int rot = 0; rot < 8; ++rot) {
                Eigen::Vector2d q = uv;
                if (rot & 4) {
                    std::swap(q.x(), q.y());
                }
                for (int r = 0; r < (rot & 3); ++r) {
                    q = Eigen::Vector2d(1.0 - q.y(), q.x());
                }
                static const Eigen::Vector2d corner[4] = {{0, 0}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
                const Eigen::Vector2d parent = corner[k] + 0.5 * q;
                const auto y =
                    coarse.evaluate(P, {coarse.first_ptex_face(f), parent.x(), parent.y()}, DerivativeOrder::Value);
                best = std::min(best, (x.row(0) - y.row(0)).norm());
            }
            largest = std::max(largest, best);
        }
    }
    EXPECT_LT(largest, 1e-11 * m.scale);
}

// With own β, γ ≠ 1 the corner's children are not regular patches one level more: the stationary
// class evaluates them through subtrees whose regular patches carry their own tables G·W·R^n. Those
// against plain local subdivision with the same weights (no tables, no powers of R) at points 2^-k
// from the tuned vertex inside each of the three children that are subtrees, value to 1e-12 of the
// mesh size at every k, and first and second derivatives where the reference holds (k <= 12).
TEST(LimitTunedWeights, SubtreeTablesAgreeWithLocalSubdivisionNearTheVertex) {
    const Loaded m = load("quad_valence_5");
    TunedWeights w;
    Index tuned = invalid_index;
    for (Index v = 0; v < m.topology.num_vertices() && tuned == invalid_index; ++v) {
        if (!m.topology.is_boundary_vertex(v) && m.topology.valence(v) == 5) {
            w.set_vertex(v, {13.9851, 0.6, 0.8});
            tuned = v;
        }
    }
    ASSERT_NE(tuned, invalid_index);
    const LimitBasis fast(m.topology, SchemeKind::CatmullClark, m.options, w);
    const LimitBasis slow(m.topology, SchemeKind::CatmullClark, m.options, w, LimitEvaluation::Subdivision);
    int compared = 0;
    for (const Index f : m.topology.vertex_faces(tuned)) {
        const auto verts = m.topology.face_vertices(f);
        const Eigen::Vector2d c = corner_uv(true, std::find(verts.begin(), verts.end(), tuned) - verts.begin());
        const Eigen::Vector2d inward = Eigen::Vector2d(0.5, 0.5) - c;  // (±0.5, ±0.5)
        const Eigen::Vector2d along_u(2.0 * inward.x(), 0.0), along_v(0.0, 2.0 * inward.y());
        // Inside the children across the corner's two edges and the one opposite it.
        for (const Eigen::Vector2d& offset :
             {Eigen::Vector2d(0.7 * along_u + 0.1 * along_v), Eigen::Vector2d(0.15 * along_u + 0.8 * along_v),
              Eigen::Vector2d(0.6 * along_u + 0.7 * along_v)}) {
            for (int k : {0, 1, 3, 6, 12, 20, 30}) {
                const Eigen::Vector2d uv = c + std::ldexp(1.0, -k) * offset;
                const SurfacePoint point{fast.first_ptex_face(f), uv.x(), uv.y()};
                const auto a = fast.evaluate(m.X, point, DerivativeOrder::Second);
                const auto b = slow.evaluate(m.X, point, DerivativeOrder::Second);
                const auto weights = fast.evaluate(point, DerivativeOrder::Second).apply(m.X);
                ++compared;
                EXPECT_LT((a.row(0) - b.row(0)).norm(), 1e-12 * m.scale) << "face " << f << " at 2^-" << k;
                EXPECT_LT((a - weights).norm(), 1e-12 * (a.norm() + m.scale)) << "face " << f << " at 2^-" << k;
                if (k > 12) {
                    continue;  // plain subdivision's derivatives lose ~2^k·eps (see above)
                }
                const double first = a.row(1).norm() + a.row(2).norm();
                EXPECT_LT((a - b).middleRows(1, 2).norm(), 1e-9 * first + std::ldexp(1e-15, k) * m.scale)
                    << "first derivatives, face " << f << " at 2^-" << k;
                const double second = a.bottomRows(3).norm();
                EXPECT_LT((a - b).bottomRows(3).norm(), 1e-8 * second + std::ldexp(1e-14, 2 * k) * m.scale)
                    << "second derivatives, face " << f << " at 2^-" << k;
            }
        }
    }
    EXPECT_EQ(compared, 5 * 3 * 7);
}

/// Bases off the common path: per-vertex tuned weights (templates keyed by the weights of their
/// vertices; subtrees of a stationary class), plain local subdivision (no tables: the template chain
/// goes as deep as the point needs), a valence-40 vertex (more local points than the positions path
/// keeps on its stack: the weights take over) and n-gons (a root node with W).
struct OffCommonPath {
    Loaded quad5 = load("quad_valence_5");
    Loaded ngons = load("cube_ngons");
    Points fan_X;
    std::vector<std::tuple<std::string, LimitBasis, const Points*>> subjects;

    OffCommonPath() {
        TunedWeights tuned;
        for (Index v = 0; v < quad5.topology.num_vertices(); ++v) {
            if (!quad5.topology.is_boundary_vertex(v) && quad5.topology.valence(v) == 5) {
                tuned.set_vertex(v, {13.9851, 0.6, 0.8});
                break;  // one tuned vertex: the others keep Catmull–Clark's weights
            }
        }
        // A closed fan: a valence-40 apex, a ring of 40 vertices and a valence-40 bottom vertex (quads).
        constexpr Index n = 40;
        fan_X.resize(2 * n + 2, 3);
        std::vector<Index> offsets{0};
        std::vector<Index> corners;
        for (Index i = 0; i < n; ++i) {
            const double a = 2 * M_PI * i / n;
            fan_X.row(i) << std::cos(a), std::sin(a), 0.3;
            fan_X.row(n + i) << 1.2 * std::cos(a + M_PI / n), 1.2 * std::sin(a + M_PI / n), -0.3;
            for (const std::array<Index, 4>& q :
                 {std::array<Index, 4>{2 * n, i, n + i, (i + 1) % n},
                  std::array<Index, 4>{2 * n + 1, (i + 1) % n + n, (i + 1) % n, n + i}}) {
                corners.insert(corners.end(), q.begin(), q.end());
                offsets.push_back(static_cast<Index>(corners.size()));
            }
        }
        fan_X.row(2 * n) << 0, 0, 1;
        fan_X.row(2 * n + 1) << 0, 0, -1;
        const Topology fan_topology(2 * n + 2, offsets, corners);
        subjects.emplace_back("per-vertex weights",
                              LimitBasis(quad5.topology, SchemeKind::CatmullClark, quad5.options, tuned), &quad5.X);
        subjects.emplace_back(
            "local subdivision",
            LimitBasis(quad5.topology, SchemeKind::CatmullClark, quad5.options, {}, LimitEvaluation::Subdivision),
            &quad5.X);
        subjects.emplace_back("valence 40", LimitBasis(fan_topology, SchemeKind::CatmullClark), &fan_X);
        subjects.emplace_back("n-gons", LimitBasis(ngons.topology, SchemeKind::CatmullClark, ngons.options), &ngons.X);
    }

    /// @p check(basis, X, point, where) at seven points of every ptex face with a limit surface, not at
    /// the domain's corners (plain local subdivision refuses points at an extraordinary vertex; the
    /// bundled cases above take the corners).
    template <class Check>
    void for_each_point(std::mt19937& rng, const Check& check) const {
        std::uniform_real_distribution<double> inside(0.01, 0.99);
        for (const auto& [name, basis, X] : subjects) {
            for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
                if (!basis.has_limit_surface(p)) {
                    continue;
                }
                std::vector<Eigen::Vector2d> uvs = {{std::ldexp(1.0, -9), std::ldexp(1.0, -10)}, {0.5, 0.0}};
                for (int i = 0; i < 5; ++i) {
                    uvs.emplace_back(inside(rng), inside(rng));
                }
                for (const auto& uv : uvs) {
                    check(basis, *X, SurfacePoint{p, uv.x(), uv.y()}, name + ", ptex " + std::to_string(p));
                }
            }
        }
    }
};

TEST(LimitPositionsPath, EqualsTheWeightsAppliedOffTheCommonPath) {
    std::mt19937 rng(31);
    OffCommonPath().for_each_point(rng, expect_positions_equal_weights);
}

TEST(LimitPatch, EqualsTheWeightsOnItsTileOffTheCommonPath) {
    std::mt19937 rng(41);
    OffCommonPath().for_each_point(rng, expect_patch_equals_weights);
}

TEST(LimitPatch, BadDataAndPointsAreRefused) {
    const Loaded m = load("quad_valence_5");
    const LimitBasis basis(m.topology, SchemeKind::CatmullClark, m.options);
    LimitPatch patch;
    ASSERT_TRUE(basis.patch({0, 0.3, 0.4}, patch));
    const Eigen::MatrixXd data = patch.control_data(m.X);
    Eigen::Matrix<double, 6, Eigen::Dynamic> rows;
    EXPECT_THROW(patch.evaluate(data.topRows(patch.size()), 0.3, 0.4, rows), InputError);
    EXPECT_THROW(patch.evaluate(data, std::nan(""), 0.4, rows), InputError);
    EXPECT_THROW(patch.evaluate(data, 0.3, std::numeric_limits<double>::infinity(), rows), InputError);
    EXPECT_THROW((void)patch.control_data(m.X.topRows(1)), InputError);
    Eigen::MatrixXd direct;
    EXPECT_THROW(basis.patch_data({0, 0.3, 0.4}, m.X.topRows(1), patch, direct), InputError);
    EXPECT_THROW(basis.patch_data({0, 1.5, 0.4}, m.X, patch, direct), InputError);
    EXPECT_THROW(basis.patch({basis.num_ptex_faces(), 0.3, 0.4}, patch), InputError);
    EXPECT_THROW(basis.patch({0, 1.5, 0.4}, patch), InputError);
}

TEST(LimitTunedWeights, RefusesWeightsOnRegularVertices) {
    const Loaded m = load("quad_grid");
    TunedWeights w;
    for (Index v = 0; v < m.topology.num_vertices(); ++v) {
        if (!m.topology.is_boundary_vertex(v) && m.topology.valence(v) == 4) {
            w.set_vertex(v, {13.0, 1.0, 1.0});
            break;
        }
    }
    EXPECT_THROW(LimitBasis(m.topology, SchemeKind::CatmullClark, m.options, w), UnsupportedError);
}

// has_limit_surface is the documented rule on every ptex face — not a hole, and under
// BoundaryInterpolation::None no corner on the boundary with a boundary edge that is not infinitely
// sharp — over OpenSubdiv's regression shapes (holes, creases, corners, boundaries; the peer tests
// compare the same answer with Far's patches) under both boundary rules, on a fresh basis: regular
// faces are answered from their fast patch, without the per-face root that holds the rule.
TEST(LimitHoles, HasLimitSurfaceFollowsTheHoleAndBoundaryRule) {
    int shapes = 0;
    for (const OpenSubdivShape& shape : opensubdiv_shapes()) {
        const bool pole = shape.name == "catmark_pole360" || shape.name == "loop_pole360";  // beyond the basis
        if (!shape.refusal.empty() || pole ||
            (shape.scheme != SchemeKind::CatmullClark && shape.scheme != SchemeKind::Loop)) {
            continue;
        }
        const Topology t = read_mesh(shape.path).mesh.topology();
        for (const BoundaryInterpolation boundary : {BoundaryInterpolation::None, BoundaryInterpolation::EdgeOnly}) {
            SchemeOptions options;
            options.boundary = boundary;
            const LimitBasis basis(t, shape.scheme, options);
            for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
                const Index f = basis.ptex_face(p).control_face;
                bool expected = !t.is_hole(f);
                for (const Index v : t.face_vertices(f)) {
                    for (const Index e : t.vertex_edges(v)) {
                        expected = expected && !(boundary == BoundaryInterpolation::None && t.is_boundary_edge(e) &&
                                                 t.edge_sharpness(e) < infinite_sharpness);
                    }
                }
                ASSERT_EQ(basis.has_limit_surface(p), expected) << shape.name << ", ptex face " << p;
            }
        }
        ++shapes;
    }
    EXPECT_GT(shapes, 80);
}

INSTANTIATE_TEST_SUITE_P(Bundled, LimitIdentity, ::testing::ValuesIn(all_cases()), [](const auto& test_info) {
    const SchemeKind scheme = test_info.param.scheme;
    return test_info.param.mesh + "_" +
           (scheme == SchemeKind::Loop       ? "loop"
            : scheme == SchemeKind::DooSabin ? "doo_sabin"
                                             : "catmull_clark");
});

}  // namespace
}  // namespace limsurf::test
