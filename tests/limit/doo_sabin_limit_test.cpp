// Identities of the exact Doo–Sabin limit evaluation (src/limsurf/limit/doo_sabin_limit.h)
// on every closed bundled mesh without sharpness tags:
//   (a) partition of unity, derivative rows summing to zero;
//   (b) derivatives = central finite differences (away from patch boundaries, where
//       the biquadratic surface is only C1);
//   (c) C0 and normal continuity across every control edge and across the internal
//       quadrant / sub-face boundaries (with first derivatives across a quad's quadrants);
//   (d) an independent witness: global refine_doo_sabin to level 5, the point followed
//       to its level-5 vertex by bookkeeping written here, the biquadratic B-spline on
//       that vertex's 3 × 3 net (positions and derivatives, 1e-12 of the mesh size);
//   (e) the stationary tables against plain local subdivision at 2^-k from the corners.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/doo_sabin_limit.h"
#include "limsurf/limit/patch_basis.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

using detail::DooSabinLimit;
using Rows6 = Eigen::Matrix<double, 6, 3>;

struct Loaded {
    Topology topology;
    Points X;
    double scale = 1.0;  // bounding-box diagonal
};

Loaded load(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    Loaded m{built.mesh.topology(), built.mesh.positions(), 1.0};
    m.scale = (m.X.colwise().maxCoeff() - m.X.colwise().minCoeff()).norm();
    return m;
}

std::vector<std::string> closed_cases() {
    std::vector<std::string> names;
    for (const auto& m : closed_meshes()) {
        if (!load(m.name).topology.has_sharpness()) {
            names.push_back(m.name);
        }
    }
    return names;
}

Rows6 eval(const DooSabinLimit& ds, const Points& X, Index p, double u, double v) {
    std::vector<Index> support;
    Eigen::Matrix<double, 6, Eigen::Dynamic> w;
    ds.evaluate(p, u, v, support, w);
    Rows6 r = Rows6::Zero();
    for (std::size_t i = 0; i < support.size(); ++i) {
        r += w.col(static_cast<Index>(i)) * X.row(support[i]);
    }
    return r;
}

Eigen::Vector3d normal(const Rows6& r) {
    return Eigen::Vector3d(r.row(1)).cross(Eigen::Vector3d(r.row(2))).normalized();
}

/// Whether x in (0, 1) keeps a margin m from every dyadic line 2^-j and 1 - 2^-j, where
/// the nested patches next to a corner meet (the surface is only C1 there).
bool clear_of_patch_lines(double x, double m) {
    for (double y : {x, 1.0 - x}) {
        if (y < 8 * m) {
            return false;
        }
        for (double line = 0.5; line > y / 4; line /= 2) {
            if (std::abs(y - line) < m) {
                return false;
            }
        }
    }
    return true;
}

class DooSabinLimitIdentity : public ::testing::TestWithParam<std::string> {};

// (a)
TEST_P(DooSabinLimitIdentity, WeightsArePartitionOfUnity) {
    const Loaded m = load(GetParam());
    const DooSabinLimit ds(m.topology);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (Index p = 0; p < ds.num_ptex_faces(); ++p) {
        ASSERT_TRUE(ds.has_limit_surface(p));
        std::vector<Eigen::Vector2d> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {1, 0.5}};
        for (int i = 0; i < 10; ++i) {
            points.emplace_back(uniform(rng), uniform(rng));
        }
        for (const auto& uv : points) {
            std::vector<Index> support;
            Eigen::Matrix<double, 6, Eigen::Dynamic> w;
            ds.evaluate(p, uv.x(), uv.y(), support, w);
            ASSERT_EQ(w.cols(), static_cast<Index>(support.size()));
            ASSERT_NEAR(w.row(0).sum(), 1.0, 1e-12) << "ptex " << p << " at " << uv.transpose();
            // At a domain corner that is an extraordinary point, derivatives are taken 2^-61 away
            // and second derivatives diverge there (as for Catmull–Clark): check the value only.
            const bool corner = (uv.x() == 0.0 || uv.x() == 1.0) && (uv.y() == 0.0 || uv.y() == 1.0);
            for (int r = 1; r < (corner ? 1 : 6); ++r) {
                const double size = w.row(r).cwiseAbs().sum();
                ASSERT_NEAR(w.row(r).sum(), 0.0, 1e-12 * std::max(1.0, size)) << "row " << r << " ptex " << p;
            }
        }
    }
}

// (b)
TEST_P(DooSabinLimitIdentity, DerivativesMatchFiniteDifferences) {
    const Loaded m = load(GetParam());
    const DooSabinLimit ds(m.topology);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uniform(0.05, 0.95);
    const double h = 1e-5;
    int checked = 0;
    for (Index p = 0; p < ds.num_ptex_faces(); ++p) {
        const bool quad = ds.ptex_face(p).corner < 0;
        for (int i = 0; i < 6; ++i) {
            const double u = uniform(rng);
            const double v = uniform(rng);
            // Node coordinates: a quad's quadrant is half size.
            const double s = quad ? std::fmod(2 * u, 1.0) : u;
            const double t = quad ? std::fmod(2 * v, 1.0) : v;
            const double margin = (quad ? 2 : 1) * 3 * h;
            if (!clear_of_patch_lines(s, margin) || !clear_of_patch_lines(t, margin)) {
                continue;
            }
            ++checked;
            const auto at = [&](double du, double dv) { return eval(ds, m.X, p, u + du, v + dv); };
            const Rows6 c = at(0, 0);
            const Rows6 pu = at(h, 0), mu = at(-h, 0), pv = at(0, h), mv = at(0, -h);
            const double tol = 1e-6 * m.scale;
            EXPECT_LT((c.row(1) - (pu.row(0) - mu.row(0)) / (2 * h)).norm(), tol) << "du, ptex " << p;
            EXPECT_LT((c.row(2) - (pv.row(0) - mv.row(0)) / (2 * h)).norm(), tol) << "dv, ptex " << p;
            EXPECT_LT((c.row(3) - (pu.row(1) - mu.row(1)) / (2 * h)).norm(), 1e-4 * m.scale) << "duu, ptex " << p;
            EXPECT_LT((c.row(4) - (pv.row(1) - mv.row(1)) / (2 * h)).norm(), 1e-4 * m.scale) << "duv, ptex " << p;
            EXPECT_LT((c.row(4) - (pu.row(2) - mu.row(2)) / (2 * h)).norm(), 1e-4 * m.scale) << "dvu, ptex " << p;
            EXPECT_LT((c.row(5) - (pv.row(2) - mv.row(2)) / (2 * h)).norm(), 1e-4 * m.scale) << "dvv, ptex " << p;
        }
    }
    EXPECT_GT(checked, ds.num_ptex_faces());
}

/// The point at parameter a in [0, 1] along edge k (from corner k to k+1) of face f:
/// (ptex face, u, v).
struct PtexPoint {
    Index p;
    double u;
    double v;
};

PtexPoint edge_point(const DooSabinLimit& ds, const Topology& t, Index f, Index k, double a) {
    const Index first = ds.first_ptex_face(f);
    const Index n = t.face_degree(f);
    if (n == 4) {
        static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        const Eigen::Vector2d x = (1 - a) * square[k] + a * square[(k + 1) % 4];
        return {first, x.x(), x.y()};
    }
    // Sub-face k: (0,0) = v_k, (1,0) = middle of edge k; sub-face k+1: (0,0) = v_k+1, (0,1) = middle of edge k.
    if (a < 0.5) {
        return {first + k, 2 * a, 0.0};
    }
    return {first + (k + 1) % n, 0.0, 2 * (1 - a)};
}

// (c) across control edges
TEST_P(DooSabinLimitIdentity, ContinuousAcrossControlEdges) {
    const Loaded m = load(GetParam());
    const Topology& t = m.topology;
    const DooSabinLimit ds(t);
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto faces = t.edge_faces(e);
        ASSERT_EQ(faces.size(), 2u);
        const auto ends = t.edge_vertices(e);
        // Each face's edge index and whether it runs from ends[0] to ends[1].
        const auto locate = [&](Index f, Index& k, bool& forward) {
            const auto fe = t.face_edges(f);
            const auto fv = t.face_vertices(f);
            for (std::size_t i = 0; i < fe.size(); ++i) {
                if (fe[i] == e) {
                    k = static_cast<Index>(i);
                    forward = fv[i] == ends[0];
                }
            }
        };
        Index k0 = 0, k1 = 0;
        bool forward0 = true, forward1 = true;
        locate(faces[0], k0, forward0);
        locate(faces[1], k1, forward1);
        ASSERT_NE(forward0, forward1);
        for (double a : {0.0, 0.1, 0.25, 0.37, 0.5, 0.75, 0.9, 1.0}) {
            const PtexPoint x = edge_point(ds, t, faces[0], k0, forward0 ? a : 1 - a);
            const PtexPoint y = edge_point(ds, t, faces[1], k1, forward1 ? a : 1 - a);
            const Rows6 rx = eval(ds, m.X, x.p, x.u, x.v);
            const Rows6 ry = eval(ds, m.X, y.p, y.u, y.v);
            EXPECT_LT((rx.row(0) - ry.row(0)).norm(), 1e-12 * m.scale) << "edge " << e << " at " << a;
            EXPECT_LT((normal(rx) - normal(ry)).norm(), 1e-9) << "edge " << e << " at " << a;
        }
    }
}

// (c) inside a control face: a quad's quadrants (u or v = 1/2), an n-gon's sub-faces.
TEST_P(DooSabinLimitIdentity, ContinuousInsideControlFaces) {
    const Loaded m = load(GetParam());
    const Topology& t = m.topology;
    const DooSabinLimit ds(t);
    const double d = std::ldexp(1.0, -40);
    for (Index f = 0; f < t.num_faces(); ++f) {
        const Index first = ds.first_ptex_face(f);
        const Index n = t.face_degree(f);
        for (double a : {0.0, 0.1, 0.3, 0.5, 0.61, 0.9, 1.0}) {
            if (n == 4) {
                // Just before the line and on it (the evaluator takes the upper quadrant there).
                for (const auto& [x, y] : {std::pair<Eigen::Vector2d, Eigen::Vector2d>{{0.5 - d, a}, {0.5, a}},
                                           std::pair<Eigen::Vector2d, Eigen::Vector2d>{{a, 0.5 - d}, {a, 0.5}}}) {
                    const Rows6 rx = eval(ds, m.X, first, x.x(), x.y());
                    const Rows6 ry = eval(ds, m.X, first, y.x(), y.y());
                    EXPECT_LT((rx.row(0) - ry.row(0)).norm(), 1e-10 * m.scale) << "face " << f << " at " << a;
                    EXPECT_LT((normal(rx) - normal(ry)).norm(), 1e-9) << "face " << f << " at " << a;
                    if (a > 0.0 && a < 1.0) {  // ptex derivatives at the corners are taken 2^-61 away
                        EXPECT_LT((rx.middleRows(1, 2) - ry.middleRows(1, 2)).norm(), 1e-8 * m.scale)
                            << "face " << f << " at " << a;
                    }
                }
                continue;
            }
            for (Index k = 0; k < n; ++k) {
                // Sub-face k's side u = 1 (edge middle at v = 0, centre at v = 1) is sub-face k+1's side v = 1.
                const Rows6 rx = eval(ds, m.X, first + k, 1.0, a);
                const Rows6 ry = eval(ds, m.X, first + (k + 1) % n, a, 1.0);
                EXPECT_LT((rx.row(0) - ry.row(0)).norm(), 1e-12 * m.scale) << "face " << f << " side " << k;
                EXPECT_LT((normal(rx) - normal(ry)).norm(), 1e-9) << "face " << f << " side " << k << " at " << a;
                if (a > 0.0 && a < 1.0) {
                    EXPECT_LT((rx.row(2) - ry.row(1)).norm(), 1e-9 * m.scale) << "face " << f << " side " << k;
                }
            }
        }
    }
}

// (d) The independent witness: global Doo–Sabin refinement and the biquadratic patch of
// the level-L vertex whose patch holds the point. Bookkeeping: at level 1 the point of
// region (f, k) lies in the patch of vertex c = corner k of f, whose faces counter-
// clockwise are the V-face of v_k (domain corner (0,0)), the E-face of edge k, the F-face
// of f and the E-face of edge k-1. One level down, the quadrant at domain corner q
// belongs to the child of (the face at corner q, corner c) — a child vertex is a parent
// corner — and that child's own (0,0) face is the F-face of the face at corner q (same
// index: F-faces come first), its (1,0) the next face counter-clockwise.
struct Tracked {
    Index vertex;       // at the current level
    Index face;         // the face at domain corner (0,0)
    Eigen::Vector2d x;  // point in the vertex patch's domain
    Eigen::Matrix2d J;  // ptex = ... + J · x
};

/// The four faces of vertex c counter-clockwise (Topology's vertex_faces order), starting at @p first.
std::array<Index, 4> faces_from(const Topology& t, Index c, Index first) {
    const auto vf = t.vertex_faces(c);
    EXPECT_EQ(vf.size(), 4u);
    std::array<Index, 4> out{};
    const auto i0 = static_cast<std::size_t>(std::find(vf.begin(), vf.end(), first) - vf.begin());
    for (std::size_t i = 0; i < 4; ++i) {
        out[i] = vf[(i0 + i) % 4];
    }
    return out;
}

Index corner_of(const Topology& t, Index f, Index v) {
    const auto fv = t.face_vertices(f);
    return static_cast<Index>(std::find(fv.begin(), fv.end(), v) - fv.begin());
}

/// The deep-subdivision comparison refines the whole mesh five times: the closed untagged meshes of
/// at most 300 faces (the others, e.g. tetra_4, are covered by the other tests of the suite).
class DooSabinDeepSubdivision : public ::testing::TestWithParam<std::string> {};

std::vector<std::string> small_closed_cases() {
    std::vector<std::string> names;
    for (const std::string& name : closed_cases()) {
        if (load(name).topology.num_faces() <= 300) {
            names.push_back(name);
        }
    }
    return names;
}

TEST_P(DooSabinDeepSubdivision, MatchesDeepSubdivisionOnRegularPatches) {
    const Loaded m = load(GetParam());
    const DooSabinLimit ds(m.topology);
    constexpr int levels = 5;
    std::vector<Level> refined;
    std::vector<Points> X{m.X};
    for (int l = 0; l < levels; ++l) {
        refined.push_back(refine_doo_sabin(l == 0 ? m.topology : refined.back().topology));
        X.push_back(refined.back().S0 * X.back());
    }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int compared = 0;
    const Index num_ptex = std::min<Index>(ds.num_ptex_faces(), 60);
    for (Index p = 0; p < num_ptex; ++p) {
        const PtexFace pf = ds.ptex_face(p);
        const Index f = pf.control_face;
        std::vector<Eigen::Vector2d> points;
        for (int i = 0; i < 6; ++i) {
            points.emplace_back(uniform(rng), uniform(rng));
        }
        // Close to the corners (extraordinary ones included): 2^-4 and 2^-5 in.
        for (double d : {0.04, 0.02}) {
            points.emplace_back(d, 1.3 * d);
            points.emplace_back(1 - 1.2 * d, 1 - d);
        }
        for (const Eigen::Vector2d& uv : points) {
            // Level 1: the region (f, k) and its patch coordinates.
            Index k = pf.corner;
            Eigen::Vector2d x = uv;
            Eigen::Matrix2d J = Eigen::Matrix2d::Identity();
            if (k < 0) {
                // Quadrant k of the quad: (0,0) at corner k, (1,0) towards corner k+1, half size.
                k = uv.x() < 0.5 ? (uv.y() < 0.5 ? 0 : 3) : (uv.y() < 0.5 ? 1 : 2);
                static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                J.col(0) = 0.5 * (square[(k + 1) % 4] - square[k]);
                J.col(1) = 0.5 * (square[(k + 3) % 4] - square[k]);
                x = J.inverse() * (uv - square[k]);
            }
            const Topology& t1 = refined[0].topology;
            const Index vk = m.topology.face_vertices(f)[static_cast<std::size_t>(k)];
            Tracked tr{m.topology.face_offset(f) + k, invalid_index, x, J};
            for (Index g : t1.vertex_faces(tr.vertex)) {
                const auto& prov = refined[0].provenance;
                if (prov.face_parent_kind[static_cast<std::size_t>(g)] == ParentKind::Vertex &&
                    prov.face_parent[static_cast<std::size_t>(g)] == vk) {
                    tr.face = g;
                }
            }
            ASSERT_NE(tr.face, invalid_index);
            for (int l = 1; l < levels; ++l) {
                const Topology& t = refined[static_cast<std::size_t>(l - 1)].topology;
                const auto faces = faces_from(t, tr.vertex, tr.face);
                const int q = tr.x.x() < 0.5 ? (tr.x.y() < 0.5 ? 0 : 3) : (tr.x.y() < 0.5 ? 1 : 2);
                const Index g = faces[static_cast<std::size_t>(q)];
                tr.vertex = t.face_offset(g) + corner_of(t, g, tr.vertex);
                tr.face = g;
                // The quadrant's frame as in the ptex quadrants.
                static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                Eigen::Matrix2d A;
                A.col(0) = 0.5 * (square[(q + 1) % 4] - square[q]);
                A.col(1) = 0.5 * (square[(q + 3) % 4] - square[q]);
                tr.x = A.inverse() * (tr.x - square[q]);
                tr.J = tr.J * A;
            }
            const Topology& tl = refined.back().topology;
            const auto faces = faces_from(tl, tr.vertex, tr.face);
            bool regular = true;
            for (Index g : faces) {
                regular = regular && tl.face_degree(g) == 4;
            }
            if (!regular) {
                continue;
            }
            // The 3 × 3 net: face i seen from c reads [c, a, b, d]; patch_basis.h numbering,
            // c = 4, face 0 the cell (0,0) = {0, 1, 3, 4}, faces 1, 2, 3 the cells (1,0), (1,1), (0,1).
            const auto from_c = [&](std::size_t i, Index j) {
                const Index g = faces[i];
                const auto fv = tl.face_vertices(g);
                return fv[static_cast<std::size_t>((corner_of(tl, g, tr.vertex) + j) % 4)];
            };
            const std::array<Index, 9> net = {from_c(0, 2), from_c(1, 1), from_c(1, 2), from_c(0, 1), tr.vertex,
                                              from_c(2, 1), from_c(3, 2), from_c(3, 1), from_c(2, 2)};
            Eigen::Matrix<double, 6, 9> b;
            quadratic_bspline_patch_weights(tr.x.x(), tr.x.y(), b);
            Eigen::Matrix<double, 9, 3> P;
            for (int i = 0; i < 9; ++i) {
                P.row(i) = X.back().row(net[static_cast<std::size_t>(i)]);
            }
            const Eigen::Matrix<double, 6, 3> st = b * P;
            // ptex derivatives: ∇_uv = J^-T ∇_st, H_uv = J^-T H_st J^-1.
            const Eigen::Matrix2d Ji = tr.J.inverse();
            Rows6 expected;
            expected.row(0) = st.row(0);
            expected.row(1) = Ji(0, 0) * st.row(1) + Ji(1, 0) * st.row(2);
            expected.row(2) = Ji(0, 1) * st.row(1) + Ji(1, 1) * st.row(2);
            for (int c = 0; c < 3; ++c) {
                Eigen::Matrix2d H;
                H << st(3, c), st(4, c), st(4, c), st(5, c);
                const Eigen::Matrix2d Huv = Ji.transpose() * H * Ji;
                expected(3, c) = Huv(0, 0);
                expected(4, c) = Huv(0, 1);
                expected(5, c) = Huv(1, 1);
            }
            const Rows6 got = eval(ds, m.X, p, uv.x(), uv.y());
            ++compared;
            EXPECT_LT((got.row(0) - expected.row(0)).norm(), 1e-12 * m.scale) << "ptex " << p << " " << uv.transpose();
            EXPECT_LT((got.middleRows(1, 2) - expected.middleRows(1, 2)).norm(), 1e-12 * m.scale)
                << "ptex " << p << " " << uv.transpose();
            EXPECT_LT((got.bottomRows(3) - expected.bottomRows(3)).norm(), 1e-11 * m.scale)
                << "ptex " << p << " " << uv.transpose();
        }
    }
    EXPECT_GT(compared, num_ptex);
}

// (e) The stationary tables against plain local subdivision (no tables) at 2^-k from
// every corner of the ptex faces, k up to 30.
TEST_P(DooSabinLimitIdentity, StationaryTablesAgreeWithLocalSubdivisionNearCorners) {
    const Loaded m = load(GetParam());
    const DooSabinLimit fast(m.topology);
    const DooSabinLimit slow(m.topology, {}, LimitEvaluation::Subdivision);
    const Index num_ptex = std::min<Index>(fast.num_ptex_faces(), 24);
    static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (Index p = 0; p < num_ptex; ++p) {
        for (int corner = 0; corner < 4; ++corner) {
            const Eigen::Vector2d c = square[corner];
            const Eigen::Vector2d inward = Eigen::Vector2d(0.5, 0.5) - c;
            for (int k : {1, 5, 12, 20, 30}) {
                const double d = std::ldexp(1.0, -k);
                const Eigen::Vector2d uv = c + d * (inward + Eigen::Vector2d(0.1, -0.05));
                const Rows6 a = eval(fast, m.X, p, uv.x(), uv.y());
                const Rows6 b = eval(slow, m.X, p, uv.x(), uv.y());
                EXPECT_LT((a.row(0) - b.row(0)).norm(), 1e-12 * m.scale)
                    << "ptex " << p << " corner " << corner << " at 2^-" << k;
                if (k > 12) {
                    continue;
                }
                const double size = a.row(1).norm() + a.row(2).norm();
                EXPECT_LT((a.middleRows(1, 2) - b.middleRows(1, 2)).norm(),
                          1e-9 * size + std::ldexp(1e-15, k) * m.scale)
                    << "derivatives, ptex " << p << " corner " << corner << " at 2^-" << k;
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(ClosedMeshes, DooSabinLimitIdentity, ::testing::ValuesIn(closed_cases()),
                         [](const auto& param_info) { return param_info.param; });
INSTANTIATE_TEST_SUITE_P(ClosedMeshes, DooSabinDeepSubdivision, ::testing::ValuesIn(small_closed_cases()),
                         [](const auto& param_info) { return param_info.param; });

TEST(DooSabinLimit, RefusesSharpnessAndReportsBoundaryFaces) {
    const Loaded creases = load("cube_creases");
    ASSERT_TRUE(creases.topology.has_sharpness());
    EXPECT_THROW(DooSabinLimit(creases.topology), UnsupportedError);
    const Loaded grid = load("disk_ev5_quads");
    const DooSabinLimit ds(grid.topology);
    int with = 0;
    int without = 0;
    for (Index p = 0; p < ds.num_ptex_faces(); ++p) {
        const Index f = ds.ptex_face(p).control_face;
        bool interior = true;
        for (Index v : grid.topology.face_vertices(f)) {
            interior = interior && !grid.topology.is_boundary_vertex(v);
        }
        EXPECT_EQ(ds.has_limit_surface(p), interior);
        if (interior) {
            ++with;
            const Rows6 r = eval(ds, grid.X, p, 0.3, 0.6);
            EXPECT_TRUE(r.allFinite());
        } else {
            ++without;
            std::vector<Index> support;
            Eigen::Matrix<double, 6, Eigen::Dynamic> w;
            EXPECT_THROW(ds.evaluate(p, 0.3, 0.6, support, w), InputError);
        }
    }
    EXPECT_GT(with, 0);
    EXPECT_GT(without, 0);
}

}  // namespace
}  // namespace limsurf::test
