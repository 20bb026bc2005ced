// Exact limit evaluation of C2g0 surfaces (docs/c2g0_limit.md): identities of the basis (row
// sums, the two evaluation paths, C² continuity across every edge in the lattice charts, the limit
// of refined control points through refine_c2g0), the regular patch table against polynomial
// reproduction, the C² claim of c2g0-sphere-scheme-biomembranes at a valence-3 vertex (curvature
// converges) and the meshes evaluation refuses, by name.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/c2g0_limit.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/limit/surface_frame.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

ControlMesh load(const char* name) {
    return read_mesh(test::find_bundled(name).path).mesh;
}

/// Points of the ptex triangle: corners, edge points, interior, and points approaching each corner.
std::vector<Eigen::Vector2d> sample_points() {
    std::vector<Eigen::Vector2d> p = {
        {0, 0},     {1, 0},      {0, 1},       {0.5, 0},   {0.5, 0.5}, {0, 0.5}, {1.0 / 3, 1.0 / 3},
        {0.1, 0.7}, {0.62, 0.2}, {0.25, 0.25}, {0.3, 0.05}};
    for (const int k : {3, 9, 20}) {
        const double h = std::ldexp(1.0, -k);
        p.emplace_back(h, 0.3 * h);
        p.emplace_back(1.0 - 1.3 * h, 0.6 * h);
        p.emplace_back(0.2 * h, 1.0 - 1.5 * h);
    }
    return p;
}

/// Control points with no symmetry: the mesh's, perturbed.
Points perturbed(const ControlMesh& mesh, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.1, 0.1);
    Points X = mesh.positions();
    for (Index i = 0; i < X.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            X(i, c) += jitter(rng);
        }
    }
    return X;
}

std::string format(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
}

/// Largest entry of a 6 × 3 block per row group, for relative tolerances.
double scale(const Eigen::Matrix<double, 6, 3>& a, int r0, int r1) {
    return std::max(1.0, a.middleRows(r0, r1 - r0).cwiseAbs().maxCoeff());
}

TEST(C2g0Limit, RowsSumToOneAndZero) {
    for (const char* name : {"tetra_1", "tetra_2", "tetra_3", "tetra_4", "torus_4x5", "torus_8x10"}) {
        const ControlMesh mesh = load(name);
        const LimitBasis basis(mesh.topology(), SchemeKind::C2g0);
        EXPECT_EQ(basis.num_ptex_faces(), mesh.topology().num_faces());
        EXPECT_EQ(basis.domain(), ParameterDomain::Triangle);
        double worst = 0.0;
        for (Index f = 0; f < basis.num_ptex_faces(); ++f) {
            for (const auto& p : sample_points()) {
                const LimitWeights w = basis.evaluate({f, p.x(), p.y()});
                worst = std::max(worst, std::abs(w.w.row(0).sum() - 1.0));
                for (int r = 1; r < 6; ++r) {
                    const double size = std::max(1.0, w.w.row(r).cwiseAbs().maxCoeff());
                    worst = std::max(worst, std::abs(w.w.row(r).sum()) / size);
                }
            }
        }
        EXPECT_LT(worst, 1e-12) << name;
    }
}

TEST(C2g0Limit, StationaryAndSubdivisionPathsAgree) {
    for (const char* name : {"tetra_1", "tetra_2"}) {
        const ControlMesh mesh = load(name);
        const Points X = perturbed(mesh, 7);
        const LimitBasis tables(mesh.topology(), SchemeKind::C2g0);
        const LimitBasis levels(mesh.topology(), SchemeKind::C2g0, {}, {}, LimitEvaluation::Subdivision);
        double worst = 0.0;
        for (Index f = 0; f < tables.num_ptex_faces(); ++f) {
            for (const auto& p : sample_points()) {
                const SurfacePoint point{f, p.x(), p.y()};
                if (tables.evaluate(point, DerivativeOrder::Value).at_extraordinary_vertex) {
                    continue;  // the subdivision path does not evaluate at a valence-3 vertex
                }
                const auto a = tables.evaluate(X, point);
                const auto b = levels.evaluate(X, point);
                worst = std::max(worst, (a - b).topRows(3).cwiseAbs().maxCoeff() / scale(a, 0, 3));
                worst = std::max(worst, (a - b).bottomRows(3).cwiseAbs().maxCoeff() / scale(a, 3, 6));
            }
        }
        EXPECT_LT(worst, 1e-12) << name;
        RecordProperty(std::string("stationary_vs_subdivision_") + name, format(worst));
    }
}

/// Lattice points k/N of the ptex triangle (N = 3..24), where rounding once chose a lattice triangle of
/// ring 1 at (2/3, 1/3) and the lookup read past its table (a crash in Release): every point evaluates,
/// finite, and agrees with the level-by-level path.
TEST(C2g0Limit, LatticePointsOfEveryThirdEvaluate) {
    const ControlMesh mesh = load("tetra_3");
    const LimitBasis tables(mesh.topology(), SchemeKind::C2g0);
    const LimitBasis levels(mesh.topology(), SchemeKind::C2g0, {}, {}, LimitEvaluation::Subdivision);
    double worst = 0.0;
    for (const int n : {3, 6, 9, 12, 24}) {
        for (int i = 0; i <= n; ++i) {
            for (int j = 0; i + j <= n; ++j) {
                const SurfacePoint point{0, static_cast<double>(i) / n, static_cast<double>(j) / n};
                const auto a = tables.evaluate(mesh.positions(), point);
                ASSERT_TRUE(a.allFinite()) << n << ": " << i << ", " << j;
                if (tables.evaluate(point, DerivativeOrder::Value).at_extraordinary_vertex) {
                    continue;
                }
                const auto b = levels.evaluate(mesh.positions(), point);
                worst = std::max(worst, (a - b).topRows(3).cwiseAbs().maxCoeff() / scale(a, 0, 3));
            }
        }
    }
    EXPECT_LT(worst, 1e-12);
}

/// f-chart coordinates of corner j of the ptex triangle.
Eigen::Vector2d corner(int j) {
    static const Eigen::Vector2d c[3] = {{0, 0}, {1, 0}, {0, 1}};
    return c[((j % 3) + 3) % 3];
}

TEST(C2g0Limit, ValueAndTwoDerivativesAreContinuousAcrossEveryEdge) {
    for (const char* name : {"tetra_2", "torus_4x5", "tetra_1"}) {
        const ControlMesh mesh = load(name);
        const Topology& t = mesh.topology();
        const Points X = perturbed(mesh, 11);
        const LimitBasis basis(t, SchemeKind::C2g0);
        double worst[3] = {0, 0, 0};
        for (Index e = 0; e < t.num_edges(); ++e) {
            const auto faces = t.edge_faces(e);
            const Index f = faces[0];
            const Index g = faces[1];
            const auto fv = t.face_vertices(f);
            const auto gv = t.face_vertices(g);
            const auto ends = t.edge_vertices(e);
            // Corner indices of the edge's ends in f and g; the edge runs k → k+1 in f.
            int k = 0;
            while (!((fv[k] == ends[0] && fv[(k + 1) % 3] == ends[1]) ||
                     (fv[k] == ends[1] && fv[(k + 1) % 3] == ends[0]))) {
                ++k;
            }
            // g's corners in f's chart: the shared ones, and the apex reflected (a lattice rhombus).
            const Eigen::Vector2d A = corner(k);
            const Eigen::Vector2d Bc = corner(k + 1);
            const Eigen::Vector2d D = A + Bc - corner(k + 2);
            std::array<Eigen::Vector2d, 3> Q;
            for (int j = 0; j < 3; ++j) {
                Q[j] = gv[j] == fv[k] ? A : gv[j] == fv[(k + 1) % 3] ? Bc : D;
            }
            Eigen::Matrix2d J;
            J.col(0) = Q[1] - Q[0];
            J.col(1) = Q[2] - Q[0];
            const Eigen::Matrix2d Ji = J.inverse();
            for (const double s : {0.001, 0.1, 0.37, 0.5, 0.8, 0.999}) {
                const Eigen::Vector2d pf = A + s * (Bc - A);
                const Eigen::Vector2d pg = Ji * (pf - Q[0]);
                const auto a = basis.evaluate(X, {f, pf.x(), pf.y()});
                const auto b = basis.evaluate(X, {g, pg.x(), pg.y()});
                // s_g(y) = s_f(Q0 + J y): ∇_g = Jᵀ ∇_f, H_g = Jᵀ H_f J.
                Eigen::Matrix<double, 6, 3> expected;
                expected.row(0) = a.row(0);
                expected.row(1) = J(0, 0) * a.row(1) + J(1, 0) * a.row(2);
                expected.row(2) = J(0, 1) * a.row(1) + J(1, 1) * a.row(2);
                expected.row(3) =
                    J(0, 0) * J(0, 0) * a.row(3) + 2 * J(0, 0) * J(1, 0) * a.row(4) + J(1, 0) * J(1, 0) * a.row(5);
                expected.row(4) = J(0, 0) * J(0, 1) * a.row(3) + (J(0, 0) * J(1, 1) + J(1, 0) * J(0, 1)) * a.row(4) +
                                  J(1, 0) * J(1, 1) * a.row(5);
                expected.row(5) =
                    J(0, 1) * J(0, 1) * a.row(3) + 2 * J(0, 1) * J(1, 1) * a.row(4) + J(1, 1) * J(1, 1) * a.row(5);
                const Eigen::Matrix<double, 6, 3> d = expected - b;
                worst[0] = std::max(worst[0], d.row(0).cwiseAbs().maxCoeff() / scale(a, 0, 1));
                worst[1] = std::max(worst[1], d.middleRows(1, 2).cwiseAbs().maxCoeff() / scale(a, 1, 3));
                worst[2] = std::max(worst[2], d.bottomRows(3).cwiseAbs().maxCoeff() / scale(a, 3, 6));
            }
        }
        EXPECT_LT(worst[0], 1e-12) << name;
        EXPECT_LT(worst[1], 1e-11) << name;
        EXPECT_LT(worst[2], 1e-10) << name;
        RecordProperty(std::string("continuity_") + name,
                       format(worst[0]) + " " + format(worst[1]) + " " + format(worst[2]));
    }
}

TEST(C2g0Limit, RefinedControlPointsHaveTheSameLimit) {
    for (const char* name : {"tetra_2", "tetra_1", "torus_4x5"}) {
        const ControlMesh mesh = load(name);
        const Points X = perturbed(mesh, 3);
        const Level level = refine_c2g0(mesh.topology());
        const Points Xf = level.S0 * X;
        const LimitBasis coarse(mesh.topology(), SchemeKind::C2g0);
        const LimitBasis fine(level.topology, SchemeKind::C2g0);
        double worst = 0.0;
        for (Index f = 0; f < coarse.num_ptex_faces(); ++f) {
            for (const auto& p : sample_points()) {
                // Child q of the Loop split: face 4f + q, corner children at corner q (half size),
                // the middle child with corners at the edge midpoints e0, e1, e2.
                const double u = p.x();
                const double v = p.y();
                int q = 3;
                Eigen::Vector2d c;
                Eigen::Matrix2d L;  // child = offset + L · parent
                if (u + v < 0.5) {
                    q = 0;
                    c = {2 * u, 2 * v};
                    L << 2, 0, 0, 2;
                } else if (u >= 0.5) {
                    q = 1;  // (0,0) = v1, (1,0) towards v2, (0,1) towards v0
                    c = {2 * v, 2 * (1 - u - v)};
                    L << 0, 2, -2, -2;
                } else if (v >= 0.5) {
                    q = 2;  // (0,0) = v2, (1,0) towards v0, (0,1) towards v1
                    c = {2 * (1 - u - v), 2 * u};
                    L << -2, -2, 2, 0;
                } else {
                    // corners (0.5,0), (0.5,0.5), (0,0.5): parent = (0.5,0) + c.x (0,0.5) + c.y (-0.5,0.5)
                    c = {2 * (u + v) - 1, 1 - 2 * u};
                    L << 2, 2, -2, 0;
                }
                const auto a = coarse.evaluate(X, {f, u, v});
                const auto b = fine.evaluate(Xf, {4 * f + q, std::clamp(c.x(), 0.0, 1.0), std::clamp(c.y(), 0.0, 1.0)});
                if (coarse.evaluate({f, u, v}, DerivativeOrder::Value).at_extraordinary_vertex) {
                    EXPECT_LT((a.row(0) - b.row(0)).cwiseAbs().maxCoeff(), 1e-12);
                    continue;
                }
                // Parent derivatives from child ones: ∇_parent = Lᵀ ∇_child, H_parent = Lᵀ H_child L.
                Eigen::Matrix<double, 6, 3> expected;
                expected.row(0) = b.row(0);
                expected.row(1) = L(0, 0) * b.row(1) + L(1, 0) * b.row(2);
                expected.row(2) = L(0, 1) * b.row(1) + L(1, 1) * b.row(2);
                expected.row(3) =
                    L(0, 0) * L(0, 0) * b.row(3) + 2 * L(0, 0) * L(1, 0) * b.row(4) + L(1, 0) * L(1, 0) * b.row(5);
                expected.row(4) = L(0, 0) * L(0, 1) * b.row(3) + (L(0, 0) * L(1, 1) + L(1, 0) * L(0, 1)) * b.row(4) +
                                  L(1, 0) * L(1, 1) * b.row(5);
                expected.row(5) =
                    L(0, 1) * L(0, 1) * b.row(3) + 2 * L(0, 1) * L(1, 1) * b.row(4) + L(1, 1) * L(1, 1) * b.row(5);
                const Eigen::Matrix<double, 6, 3> d = expected - a;
                worst = std::max(worst, d.topRows(3).cwiseAbs().maxCoeff() / scale(a, 0, 3));
                worst = std::max(worst, d.bottomRows(3).cwiseAbs().maxCoeff() / scale(a, 3, 6));
            }
        }
        EXPECT_LT(worst, 1e-12) << name;
        RecordProperty(std::string("refined_") + name, format(worst));
    }
}

TEST(C2g0Limit, RegularPatchReproducesPolynomials) {
    // The centred box spline reproduces linear functions, and for a cubic p the quasi-interpolant
    // Σ p(α) φ(x − α) differs from p by an affine function (Strang–Fix): equal second derivatives.
    const auto offsets = detail::c2g0_patch_offsets();
    const auto cubic = [](double x, double y) {
        return 0.3 * x * x * x - 1.1 * x * y * y + 0.7 * x * x - y * y + 2 * x * y;
    };
    Eigen::Matrix<double, 6, 27> w;
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.2, 0.3), Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.6, 0.1)}) {
        detail::c2g0_patch_weights(p.x(), p.y(), w);
        // Lattice point of ptex (u, v): (u + v, v).
        double lx = 0;
        double ly = 0;
        double c = 0;
        for (int i = 0; i < 27; ++i) {
            lx += w(0, i) * offsets[i][0];
            ly += w(0, i) * offsets[i][1];
            c += w(0, i) * cubic(offsets[i][0], offsets[i][1]);
        }
        EXPECT_NEAR(lx, p.x() + p.y(), 1e-14);
        EXPECT_NEAR(ly, p.y(), 1e-14);
        // Second derivatives of p(u + v, v) in (u, v).
        const double x = p.x() + p.y();
        const double y = p.y();
        const double pxx = 1.8 * x + 1.4;
        const double pxy = -2.2 * y + 2;
        const double pyy = -2.2 * x - 2;
        const double expected[3] = {pxx, pxx + pxy, pxx + 2 * pxy + pyy};
        for (int r = 0; r < 3; ++r) {
            double got = 0;
            for (int i = 0; i < 27; ++i) {
                got += w(3 + r, i) * cubic(offsets[i][0], offsets[i][1]);
            }
            EXPECT_NEAR(got, expected[r], 1e-12);
        }
        (void)c;
    }
}

namespace patch_table {
#include "limsurf/limit/c2g0_patch_table.inc"
}  // namespace patch_table

TEST(C2g0Limit, RegularPatchIsItsBezierTableByDegreeRaising) {
    // An independent evaluation of the table's polynomials: c2g0_patch_weights writes each
    // Bernstein function and its derivatives in powers of the barycentrics; here they come from the
    // recurrence B^n_ijk = l0 B^(n−1)_(i−1)jk + l1 B^(n−1)_i(j−1)k + l2 B^(n−1)_ij(k−1), and the
    // derivatives from differences of the Bézier coefficients (a derivative along the barycentric
    // direction d is of degree n − 1 with coefficients n Σ_x d_x c_(γ+e_x)).
    using patch_table::c2g0_bernstein;
    using patch_table::c2g0_coefficients;
    const auto index = [](int n, int j, int k) { return k * (n + 1) - k * (k - 1) / 2 + j; };
    // bernstein[n][index(n, j, k)] at barycentrics (1 − u − v, u, v), n = 0..7.
    const auto bernstein = [&](double u, double v) {
        const double l[3] = {1.0 - u - v, u, v};
        std::vector<std::vector<double>> b{{1.0}};
        for (int n = 1; n <= 7; ++n) {
            std::vector<double> next(static_cast<std::size_t>((n + 1) * (n + 2) / 2), 0.0);
            for (int k = 0; k <= n; ++k) {
                for (int j = 0; j + k <= n; ++j) {
                    const std::vector<double>& lower = b.back();
                    double sum = j + k < n ? l[0] * lower[static_cast<std::size_t>(index(n - 1, j, k))] : 0.0;
                    sum += j > 0 ? l[1] * lower[static_cast<std::size_t>(index(n - 1, j - 1, k))] : 0.0;
                    sum += k > 0 ? l[2] * lower[static_cast<std::size_t>(index(n - 1, j, k - 1))] : 0.0;
                    next[static_cast<std::size_t>(index(n, j, k))] = sum;
                }
            }
            b.push_back(std::move(next));
        }
        return b;
    };
    std::mt19937_64 random(20261207);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Eigen::Vector2d> points{{0, 0}, {1, 0}, {0, 1}, {1.0 / 3, 1.0 / 3}, {0.5, 0.5}};
    for (int n = 0; n < 20; ++n) {
        Eigen::Vector2d p(unit(random), unit(random));
        if (p.sum() > 1) {
            p = Eigen::Vector2d(1, 1) - p;
        }
        points.push_back(p);
    }
    double worst = 0.0;
    Eigen::Matrix<double, 6, 27> w;
    for (const Eigen::Vector2d& p : points) {
        detail::c2g0_patch_weights(p.x(), p.y(), w);
        const auto b = bernstein(p.x(), p.y());
        for (int f = 0; f < 27; ++f) {
            double c[8][8] = {};  // c[j][k]: the coefficient of B^7 with exponents (7 − j − k, j, k)
            for (int q = 0; q < 36; ++q) {
                c[c2g0_bernstein[q][0]][c2g0_bernstein[q][1]] =
                    static_cast<double>(c2g0_coefficients[f][q][0]) / static_cast<double>(c2g0_coefficients[f][q][1]);
            }
            double expected[6] = {};
            for (int k = 0; k <= 7; ++k) {
                for (int j = 0; j + k <= 7; ++j) {
                    expected[0] += c[j][k] * b[7][static_cast<std::size_t>(index(7, j, k))];
                    if (j + k <= 6) {
                        const double b6 = b[6][static_cast<std::size_t>(index(6, j, k))];
                        expected[1] += 7.0 * (c[j + 1][k] - c[j][k]) * b6;  // d = (−1, 1, 0)
                        expected[2] += 7.0 * (c[j][k + 1] - c[j][k]) * b6;  // d = (−1, 0, 1)
                    }
                    if (j + k <= 5) {
                        const double b5 = b[5][static_cast<std::size_t>(index(5, j, k))];
                        expected[3] += 42.0 * (c[j + 2][k] - 2.0 * c[j + 1][k] + c[j][k]) * b5;
                        expected[4] += 42.0 * (c[j + 1][k + 1] - c[j + 1][k] - c[j][k + 1] + c[j][k]) * b5;
                        expected[5] += 42.0 * (c[j][k + 2] - 2.0 * c[j][k + 1] + c[j][k]) * b5;
                    }
                }
            }
            for (int r = 0; r < 6; ++r) {
                worst = std::max(worst, std::abs(w(r, f) - expected[r]));
            }
        }
    }
    EXPECT_LT(worst, 1e-13);
    RecordProperty("degree_raising_difference", format(worst));
}

TEST(C2g0Limit, RepeatedPointsGiveTheBitsOfTheFirstEvaluation) {
    // The evaluator keeps the regular patch's weights of the points it has met (a fixed table,
    // filled by whichever thread comes first): a point met again, on any face and from any
    // thread, must give the bits of a fresh computation. On a regular torus (every face a type-0
    // patch whose 27 lattice points are distinct vertices) each point's rows are
    // c2g0_patch_weights' over the face's lattice. The points: a quadrature rule's on every face
    // (repeated on every face, as the sampler places them) and 3000 random ones (more than the
    // table holds), through four threads at once on a fresh evaluator.
    constexpr Index n = 12;
    const auto id = [](Index i, Index j) { return ((i + n) % n) * n + (j + n) % n; };
    std::vector<std::vector<Index>> faces;
    for (Index i = 0; i < n; ++i) {
        for (Index j = 0; j < n; ++j) {
            faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    const Topology t = Topology::from_polygons(n * n, faces);
    std::vector<SurfacePoint> points;
    const std::array<Eigen::Vector2d, 4> rule{Eigen::Vector2d(1.0 / 3, 1.0 / 3), Eigen::Vector2d(0.6, 0.2),
                                              Eigen::Vector2d(0.2, 0.6), Eigen::Vector2d(0.2, 0.2)};
    for (Index f = 0; f < t.num_faces(); ++f) {
        for (const Eigen::Vector2d& p : rule) {
            points.push_back({f, p.x(), p.y()});
        }
    }
    std::mt19937_64 random(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<Index> face(0, t.num_faces() - 1);
    for (int k = 0; k < 3000; ++k) {
        double u = unit(random);
        double v = unit(random);
        if (u + v > 1) {
            u = 1 - u;
            v = 1 - v;
        }
        points.push_back({face(random), u, v});
    }
    const auto evaluate_all = [&](const LimitBasis& basis, std::vector<LimitWeights>& out, std::size_t first,
                                  std::size_t step) {
        for (std::size_t i = first; i < points.size(); i += step) {
            basis.evaluate(points[i], out[i], DerivativeOrder::Second);
        }
    };
    const LimitBasis first(t, SchemeKind::C2g0);
    std::vector<LimitWeights> expected(points.size());
    evaluate_all(first, expected, 0, 1);
    std::vector<LimitWeights> again(points.size());
    evaluate_all(first, again, 0, 1);
    const LimitBasis fresh(t, SchemeKind::C2g0);
    std::vector<LimitWeights> threaded(points.size());
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < 4; ++k) {
        threads.emplace_back([&, k] { evaluate_all(fresh, threaded, k, 4); });
    }
    for (std::thread& thread : threads) {
        thread.join();
    }
    const auto same_bits = [](const LimitWeights& a, const LimitWeights& b) {
        return a.vertices == b.vertices && a.w.cols() == b.w.cols() &&
               std::memcmp(a.w.data(), b.w.data(), sizeof(double) * static_cast<std::size_t>(a.w.size())) == 0;
    };
    Eigen::Matrix<double, 6, 27> computed;
    for (std::size_t i = 0; i < points.size(); ++i) {
        detail::c2g0_patch_weights(points[i].u, points[i].v, computed);
        ASSERT_EQ(expected[i].w.cols(), 27) << "point " << i;
        ASSERT_EQ(std::memcmp(expected[i].w.data(), computed.data(), sizeof(double) * 6 * 27), 0) << "point " << i;
        ASSERT_TRUE(same_bits(expected[i], again[i])) << "point " << i;
        ASSERT_TRUE(same_bits(expected[i], threaded[i])) << "point " << i;
    }
}

TEST(C2g0Limit, VertexLimitsAndSnappingMatrix) {
    const ControlMesh mesh = load("tetra_2");
    const Topology& t = mesh.topology();
    const LimitBasis basis(t, SchemeKind::C2g0);
    const Points X = perturbed(mesh, 5);
    const SparseMatrix P = basis.vertex_limit_matrix();
    const Eigen::VectorXd ones = P * Eigen::VectorXd::Ones(t.num_vertices());
    EXPECT_LT((ones.array() - 1.0).abs().maxCoeff(), 1e-13);
    const Points snapped = P * X;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const LimitWeights w = basis.vertex_limit(v);
        EXPECT_EQ(w.at_extraordinary_vertex, t.valence(v) == 3) << v;
        // The same limit point from every incident face's corner.
        const auto faces = t.vertex_faces(v);
        const auto corners = t.vertex_face_corners(v);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const Eigen::Vector2d c = corner(corners[i]);
            const auto at = basis.evaluate(X, {faces[i], c.x(), c.y()}, DerivativeOrder::Value);
            EXPECT_LT((at.row(0) - snapped.row(v)).cwiseAbs().maxCoeff(), 1e-12) << v;
        }
    }
}

TEST(C2g0Limit, CurvatureConvergesAtValence3Vertices) {
    // c2g0-sphere-scheme-biomembranes §2: the surface is C² at a valence-3 vertex, with subdominant
    // eigenvalue 1/4 (§2.5, the Bers chart z ↦ z²). Approaching the vertex through each of its three
    // faces and along different directions, H and K converge to common values (spread like the
    // distance h); on the sphere-like tetra_3 the limit has K > 0 (not a flat spot). The ptex
    // derivatives at distance h from the vertex scale like h (λ = 1/4 per halving): |∂u| halves.
    // (The ptex chart is singular there, so curvature from ptex derivatives loses about 4^k ε: the
    // normal part of the second derivatives shrinks like h² while their rounding does not. The
    // spread of K shrinks about 8× from 2^-8 to 2^-11 to 2^-14 (truncation), then grows again by
    // 2^-16, where rounding is as large as the truncation (6.8e-5 → 1.7e-4; 6.5e-5 → 2.3e-4 with
    // patch weights that differ from these in their last bits). So its decrease is asserted
    // through 2^-14, and the bound 64 h |K| up to 2^-16.)
    const ControlMesh mesh = load("tetra_3");
    const Topology& t = mesh.topology();
    const LimitBasis basis(t, SchemeKind::C2g0);
    int checked = 0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.valence(v) != 3) {
            continue;
        }
        ++checked;
        const auto faces = t.vertex_faces(v);
        const auto corners = t.vertex_face_corners(v);
        double previous_spread = 1e300;
        for (const int k : {8, 11, 14, 16}) {
            std::vector<double> H;
            std::vector<double> K;
            const double h = std::ldexp(1.0, -k);
            for (std::size_t i = 0; i < faces.size(); ++i) {
                const Eigen::Vector2d c = corner(corners[i]);
                const Eigen::Vector2d e1 = corner(corners[i] + 1) - c;
                const Eigen::Vector2d e2 = corner(corners[i] + 2) - c;
                for (const double a : {0.5, 0.2, 0.8}) {
                    const Eigen::Vector2d p = c + h * (a * e1 + (1 - a) * e2);
                    const SurfaceFrame frame =
                        surface_frame(basis.evaluate(mesh.positions(), {faces[i], p.x(), p.y()}));
                    H.push_back(frame.mean_curvature);
                    K.push_back(frame.gaussian_curvature);
                }
                const Eigen::Vector2d p1 = c + h * (0.3 * e1 + 0.3 * e2);
                const Eigen::Vector2d p2 = c + 0.5 * h * (0.3 * e1 + 0.3 * e2);
                const auto d1 = basis.evaluate(mesh.positions(), {faces[i], p1.x(), p1.y()});
                const auto d2 = basis.evaluate(mesh.positions(), {faces[i], p2.x(), p2.y()});
                EXPECT_NEAR(d2.row(1).norm() / d1.row(1).norm(), 0.5, 16 * h) << "vertex " << v << " at 2^-" << k;
            }
            const auto [hmin, hmax] = std::minmax_element(H.begin(), H.end());
            const auto [kmin, kmax] = std::minmax_element(K.begin(), K.end());
            EXPECT_LT(*hmax - *hmin, 64 * h * std::abs(*hmax)) << "vertex " << v << " at 2^-" << k;
            EXPECT_LT(*kmax - *kmin, 64 * h * std::abs(*kmax)) << "vertex " << v << " at 2^-" << k;
            if (k <= 14) {
                EXPECT_LT(*kmax - *kmin, previous_spread) << "vertex " << v << " at 2^-" << k;
            }
            previous_spread = *kmax - *kmin;
            EXPECT_GT(*kmin, 0.0) << "vertex " << v << " at 2^-" << k;
        }
    }
    EXPECT_EQ(checked, 4);
}

TEST(C2g0Limit, RefusesMeshesItCannotEvaluateByName) {
    const auto refusal = [](const char* name) -> std::optional<ErrorElement> {
        try {
            const LimitBasis basis(load(name).topology(), SchemeKind::C2g0);
        } catch (const UnsupportedError& error) {
            return error.element();
        }
        return std::nullopt;
    };
    const auto tetra = refusal("tetra_0");  // adjacent valence-3 vertices
    ASSERT_TRUE(tetra.has_value());
    EXPECT_EQ(tetra->kind, ErrorElement::Kind::Vertex);
    const auto ico = refusal("icosahedron");  // valence 5
    ASSERT_TRUE(ico.has_value());
    EXPECT_EQ(ico->kind, ErrorElement::Kind::Vertex);
    EXPECT_EQ(ico->index, 0);
    const auto cube = refusal("cube");  // quads
    ASSERT_TRUE(cube.has_value());
    EXPECT_EQ(cube->kind, ErrorElement::Kind::Face);
    EXPECT_EQ(cube->index, 0);
    // Subdivision path: no evaluation at the valence-3 vertex itself.
    const ControlMesh mesh = load("tetra_2");
    const LimitBasis levels(mesh.topology(), SchemeKind::C2g0, {}, {}, LimitEvaluation::Subdivision);
    const Index f = mesh.topology().vertex_faces(0)[0];
    const Eigen::Vector2d c = corner(mesh.topology().vertex_face_corners(0)[0]);
    EXPECT_THROW((void)levels.evaluate({f, c.x(), c.y()}), NumericalError);
}

// Deep subdivision converges to the limit surface: the distance of the level-k control points to
// their own limit positions falls like h² (by 4 per level; the box spline is not interpolating),
// on a regular torus and on a subdivided tetrahedron (valence 3: the same rate, λ² = 1/16 < 1/4).
TEST(C2g0Limit, ControlPointsConvergeToTheLimitQuadratically) {
    for (const char* name : {"torus_4x5", "tetra_2"}) {
        const ControlMesh mesh = load(name);
        Topology t = mesh.topology();
        Points X = mesh.positions();
        std::vector<double> distance;
        for (int k = 0; k <= 4; ++k) {
            const LimitBasis basis(t, SchemeKind::C2g0);
            const Points limit = basis.vertex_limit_matrix() * X;
            distance.push_back((limit - X).rowwise().norm().maxCoeff());
            if (k < 4) {
                Level level = refine_c2g0(t);
                X = level.S0 * X;
                t = std::move(level.topology);
            }
        }
        for (int k = 2; k < 5; ++k) {
            const double ratio = distance[static_cast<std::size_t>(k - 1)] / distance[static_cast<std::size_t>(k)];
            EXPECT_GT(ratio, 3.5) << name << " level " << k;
            EXPECT_LT(ratio, 4.5) << name << " level " << k;
        }
    }
}

}  // namespace
}  // namespace limsurf
