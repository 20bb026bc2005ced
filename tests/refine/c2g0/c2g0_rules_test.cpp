// C2g0 refinement (c2g0-sphere-scheme-biomembranes §1.2, §2): the regular rules are the mask of
// the box spline's symbol (1.3), expanded here independently; around a valence-3 vertex the rows of
// S0 are the published matrix (2.2) and the blocks A, B of (2.3), entry by entry; and the scheme
// refuses what it cannot refine, naming the element.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"
#include "limsurf/scheme/c2g0.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

/// An exact fraction with a small denominator, for comparing rules.
struct Fraction {
    long long num = 0;
    long long den = 1;
};

bool operator==(const Fraction& a, const Fraction& b) {
    return a.num * b.den == b.num * a.den;
}

Fraction operator+(const Fraction& a, const Fraction& b) {
    const long long n = a.num * b.den + b.num * a.den;
    const long long d = a.den * b.den;
    const long long g = std::gcd(n, d);
    return {n / g, d / g};
}

Fraction of(const Rational& r) {
    return {r.num, r.den};
}

/// The coefficients a_α of â(z) = z1⁻³ z2⁻³ (1 + z1)³ (1 + z2)³ (1 + z1 z2)³ / 128, by multiplying
/// out the three binomials (C(3, i) C(3, j) C(3, k) at α = (i + k − 3, j + k − 3)).
std::map<std::pair<int, int>, Fraction> symbol_mask() {
    const int binomial[4] = {1, 3, 3, 1};
    std::map<std::pair<int, int>, Fraction> mask;
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            for (int k = 0; k < 4; ++k) {
                auto& a = mask[{i + k - 3, j + k - 3}];
                a = a + Fraction{binomial[i] * binomial[j] * binomial[k], 128};
            }
        }
    }
    return mask;
}

TEST(C2g0Rules, RegularRulesAreTheMaskOfTheBoxSplinesSymbol) {
    const auto mask = symbol_mask();
    const C2g0RegularRules rules;
    // Even part (a new vertex at a lattice point): a_{−2β} on the coarse neighbours β.
    EXPECT_TRUE((mask.at({0, 0}) == of(rules.vertex_self)));
    for (const auto& beta : std::vector<std::pair<int, int>>{{1, 0}, {0, 1}, {1, 1}, {-1, 0}, {0, -1}, {-1, -1}}) {
        EXPECT_TRUE((mask.at({-2 * beta.first, -2 * beta.second}) == of(rules.vertex_neighbour)));
    }
    // Odd part (1, 0): the new vertex on edge p = (0, 0), q = (1, 0); the triangles (p, q, (1, 1)) and
    // (p, q, (0, −1)) give the opposite vertices; a_{(1,0) − 2β} on coarse β.
    const auto edge = [&](int x, int y) { return mask.at({1 - 2 * x, -2 * y}); };
    EXPECT_TRUE(edge(0, 0) == of(rules.edge_end));
    EXPECT_TRUE(edge(1, 0) == of(rules.edge_end));
    EXPECT_TRUE(edge(1, 1) == of(rules.edge_opposite));
    EXPECT_TRUE(edge(0, -1) == of(rules.edge_opposite));
    for (const auto& side : std::vector<std::pair<int, int>>{{0, 1}, {-1, -1}, {2, 1}, {1, -1}}) {
        EXPECT_TRUE(edge(side.first, side.second) == of(rules.edge_side)) << side.first << "," << side.second;
    }
    EXPECT_TRUE(edge(-1, 0) == of(rules.edge_far));
    EXPECT_TRUE(edge(2, 0) == of(rules.edge_far));
    // Nothing else: the ten entries of each rule exhaust the mask (â(1, 1) = 4: one vertex, three edges).
    Fraction total;
    for (const auto& [alpha, a] : mask) {
        total = total + a;
    }
    EXPECT_TRUE((total == (Fraction{4, 1})));
}

TEST(C2g0Rules, EveryRowOfARegularTorusIsTheMask) {
    for (const char* name : {"torus_4x5", "torus_8x10"}) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const Level level = refine_c2g0(built.mesh.topology());
        const Index V = built.mesh.num_vertices();
        for (Index row = 0; row < level.S0.rows(); ++row) {
            std::vector<double> weights;
            for (SparseMatrix::InnerIterator it(level.S0, row); it; ++it) {
                weights.push_back(it.value() * 128.0);
            }
            std::sort(weights.begin(), weights.end());
            const std::vector<double> expected = row < V ? std::vector<double>{12, 12, 12, 12, 12, 12, 56}
                                                         : std::vector<double>{1, 1, 3, 3, 3, 3, 18, 18, 39, 39};
            EXPECT_EQ(weights, expected) << "row " << row;
        }
    }
}

/// The 19 vertices of the three rings around the valence-3 vertex c in the paper's order
/// (Fig. 4(a), recovered from the characteristic map of (2.16): its vertices are z² of the
/// hexagonal lattice, numbered by angle): c; the ring r₀, r₁, r₂; per sector i the vertex tᵢ beyond
/// rᵢ and uᵢ across (rᵢ, rᵢ₊₁); per sector the vertex beyond tᵢ and the common neighbours of (tᵢ, uᵢ)
/// and of (uᵢ, tᵢ₊₁) outside the second ring. r₀ is given, to align two levels.
std::array<Index, 19> paper_order(const Topology& t, Index c, Index r0) {
    const auto ring = [&](Index v) {
        std::vector<Index> out;
        for (const Index e : t.vertex_edges(v)) {
            out.push_back(t.other_vertex(e, v));
        }
        return out;
    };
    const auto step = [](const std::vector<Index>& around, Index from, int by) {
        const auto n = static_cast<int>(around.size());
        const int k = static_cast<int>(std::find(around.begin(), around.end(), from) - around.begin());
        return around[static_cast<std::size_t>(((k + by) % n + n) % n)];
    };
    std::array<Index, 19> order{};
    order[0] = c;
    const std::vector<Index> r = ring(c);
    const std::size_t start = static_cast<std::size_t>(std::find(r.begin(), r.end(), r0) - r.begin());
    for (std::size_t i = 0; i < 3; ++i) {
        order[1 + i] = r[(start + i) % 3];
    }
    std::array<Index, 3> tv{};
    std::array<Index, 3> uv{};
    for (std::size_t i = 0; i < 3; ++i) {
        const Index ri = order[1 + i];
        const Index rn = order[1 + (i + 1) % 3];
        tv[i] = step(ring(ri), c, 3);
        // Across (rᵢ, rᵢ₊₁) from c: the common neighbour of rᵢ and rᵢ₊₁ other than c.
        for (const Index w : ring(ri)) {
            const auto rn_ring = ring(rn);
            if (w != c && std::find(rn_ring.begin(), rn_ring.end(), w) != rn_ring.end()) {
                uv[i] = w;
            }
        }
    }
    for (std::size_t i = 0; i < 3; ++i) {
        order[4 + 2 * i] = tv[i];
        order[5 + 2 * i] = uv[i];
    }
    const auto common_outside = [&](Index a, Index b) {
        const auto ra = ring(a);
        const auto rb = ring(b);
        for (const Index w : ra) {
            const bool inner = std::find(order.begin(), order.begin() + 10, w) != order.begin() + 10;
            if (!inner && std::find(rb.begin(), rb.end(), w) != rb.end()) {
                return w;
            }
        }
        return invalid_index;
    };
    for (std::size_t i = 0; i < 3; ++i) {
        order[10 + 3 * i] = step(ring(tv[i]), order[1 + i], 3);  // beyond tᵢ, away from rᵢ
        order[11 + 3 * i] = common_outside(tv[i], uv[i]);
        order[12 + 3 * i] = common_outside(uv[i], tv[(i + 1) % 3]);
    }
    return order;
}

TEST(C2g0Rules, RowsAroundAValence3VertexAreThePublishedMatrix) {
    const C2g0Valence3Rules w;
    const double z = w.z.value(), s = w.s.value(), t = w.t.value(), u = w.u.value();
    const double a = w.a.value(), b = w.b.value(), cc = w.c.value(), d = w.d.value(), e = w.e.value();
    // (2.2): M, the 10×10 block on the first two rings.
    const double M[10][10] = {
        {z, s, s, s, t, u, t, u, t, u},
        {a, b, cc, cc, e, d, 0, 0, 0, d},
        {a, cc, b, cc, 0, d, e, d, 0, 0},
        {a, cc, cc, b, 0, 0, 0, d, e, d},
        {3. / 32, 7. / 16, 3. / 32, 3. / 32, 3. / 32, 3. / 32, 0, 0, 0, 3. / 32},
        {9. / 64, 39. / 128, 39. / 128, 3. / 64, 3. / 128, 9. / 64, 3. / 128, 1. / 128, 0, 1. / 128},
        {3. / 32, 3. / 32, 7. / 16, 3. / 32, 0, 3. / 32, 3. / 32, 3. / 32, 0, 0},
        {9. / 64, 3. / 64, 39. / 128, 39. / 128, 0, 1. / 128, 3. / 128, 9. / 64, 3. / 128, 1. / 128},
        {3. / 32, 3. / 32, 3. / 32, 7. / 16, 0, 0, 0, 3. / 32, 3. / 32, 3. / 32},
        {9. / 64, 39. / 128, 3. / 64, 39. / 128, 3. / 128, 1. / 128, 0, 1. / 128, 3. / 128, 9. / 64}};
    // (2.3): A (9×10) and B (9×9), times 128. Rows 5 and 8 of B as printed ([0 0 0 3 1 0 0 0 0] and
    // [0 0 0 0 0 0 3 1 3]) are typographical errors: row 8 makes its row of S sum to 135/128, and
    // both break the three-fold rotational symmetry the paper relies on (§2.1: S is block circulant).
    // Here they are rows 2 and 3's rotations, as rows 4, 6, 7 and 9 are of rows 1 and 3; with them
    // B has the eigenvalues the paper states (checked below).
    const int A[9][10] = {
        {1, 39, 3, 3, 39, 18, 0, 0, 0, 18}, {3, 39, 18, 1, 18, 39, 3, 0, 0, 3}, {3, 18, 39, 1, 3, 39, 18, 3, 0, 0},
        {1, 3, 39, 3, 0, 18, 39, 18, 0, 0}, {3, 1, 39, 18, 0, 3, 18, 39, 3, 0}, {3, 1, 18, 39, 0, 0, 3, 39, 18, 3},
        {1, 3, 3, 39, 0, 0, 0, 18, 39, 18}, {3, 18, 1, 39, 3, 0, 0, 3, 18, 39}, {3, 39, 1, 18, 18, 3, 0, 0, 3, 39}};
    const int B[9][9] = {{1, 3, 0, 0, 0, 0, 0, 0, 3}, {0, 3, 1, 0, 0, 0, 0, 0, 0}, {0, 1, 3, 0, 0, 0, 0, 0, 0},
                         {0, 0, 3, 1, 3, 0, 0, 0, 0}, {0, 0, 0, 0, 3, 1, 0, 0, 0}, {0, 0, 0, 0, 1, 3, 0, 0, 0},
                         {0, 0, 0, 0, 0, 3, 1, 3, 0}, {0, 0, 0, 0, 0, 0, 0, 3, 1}, {0, 0, 0, 0, 0, 0, 0, 1, 3}};
    {
        // §2.1: "The eigenvalues of the 9×9 matrix B are 1/32, 1/64, 1/128, each repeated thrice."
        Eigen::Matrix<double, 9, 9> Bm;
        for (int i = 0; i < 9; ++i) {
            for (int j = 0; j < 9; ++j) {
                Bm(i, j) = B[i][j] / 128.0;
            }
        }
        std::vector<double> eigenvalues;
        for (const auto& lambda : Eigen::EigenSolver<Eigen::Matrix<double, 9, 9>>(Bm).eigenvalues()) {
            EXPECT_NEAR(lambda.imag(), 0.0, 1e-6);
            eigenvalues.push_back(lambda.real());
        }
        std::sort(eigenvalues.begin(), eigenvalues.end());
        const double expected[9] = {1. / 128, 1. / 128, 1. / 128, 1. / 64, 1. / 64, 1. / 64, 1. / 32, 1. / 32, 1. / 32};
        for (int k = 0; k < 9; ++k) {
            EXPECT_NEAR(eigenvalues[static_cast<std::size_t>(k)], expected[k], 1e-6) << k;  // triple roots: ~1e-6
        }
    }
    // F_tetra,2: the valence-3 vertices are 4 edges apart, so each has three regular rings.
    const BuildResult built = read_mesh(test::find_bundled("tetra_2").path);
    const Topology& coarse = built.mesh.topology();
    const Level level = refine_c2g0(coarse);
    const Eigen::MatrixXd S0(level.S0);
    int checked = 0;
    for (Index c = 0; c < coarse.num_vertices(); ++c) {
        if (coarse.valence(c) != 3) {
            continue;
        }
        SCOPED_TRACE("valence-3 vertex " + std::to_string(c));
        const Index r0 = coarse.other_vertex(coarse.vertex_edges(c)[0], c);
        const auto from = paper_order(coarse, c, r0);
        // The fine ring starts at the point of edge (c, r₀): same sector, same orientation.
        const auto to = paper_order(level.topology, c, coarse.num_vertices() + coarse.find_edge(c, r0));
        for (std::size_t i = 0; i < 19; ++i) {
            for (std::size_t j = 0; j < 19; ++j) {
                double expected = 0.0;
                if (i < 10 && j < 10) {
                    expected = M[i][j];
                } else if (i >= 10 && j < 10) {
                    expected = A[i - 10][j] / 128.0;
                } else if (i >= 10) {
                    expected = B[i - 10][j - 10] / 128.0;
                }
                EXPECT_NEAR(S0(to[i], from[j]), expected, 1e-15) << "row " << i + 1 << " column " << j + 1;
            }
            // The 19 vertices are closed under refinement: no weight outside them.
            double row_sum = 0.0;
            for (std::size_t j = 0; j < 19; ++j) {
                row_sum += S0(to[i], from[j]);
            }
            EXPECT_NEAR(row_sum, 1.0, 1e-15) << "row " << i + 1;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 4);
}

TEST(C2g0Rules, TheWeightsAreThePapersRationalsAndEveryRuleSumsToOne) {
    const C2g0Valence3Rules w;
    // z = 1 − 3(s + t + u), a = 1 − b − 2(c + d) − e (§2.1); the conditions (2.15), (2.26) and
    // s = 3/16 + 2t (§2.7); e, t, u of the end of §2.7 (15/896, 295/19264, 1403/28896).
    const auto exact = [](const Rational& r) { return Fraction{r.num, r.den}; };
    EXPECT_TRUE((exact(w.z) + Fraction{3 * (12606 + 885 + 2806), 57792} == (Fraction{1, 1})));
    EXPECT_TRUE((exact(w.a) + exact(w.b) + Fraction{2 * (171 + 29), 896} + exact(w.e) == (Fraction{1, 1})));
    EXPECT_TRUE((exact(w.b) == exact(w.c) + Fraction{-3 * 29 - 4 * 15, 896} + Fraction{1, 4}));  // (2.15)
    EXPECT_TRUE((exact(w.c) == Fraction{9, 64} + Fraction{3 * 15, 896}));                        // (2.26)
    EXPECT_TRUE((exact(w.d) == Fraction{1, 64} + exact(w.e)));                                   // (2.26)
    EXPECT_TRUE((exact(w.s) == Fraction{3, 16} + Fraction{2 * 885, 57792}));
    EXPECT_TRUE((exact(w.e) == (Fraction{15, 896})));
    EXPECT_TRUE((exact(w.t) == (Fraction{295, 19264})));
    EXPECT_TRUE((exact(w.u) == (Fraction{1403, 28896})));
    // On every valence-3/6 mesh: rows sum to 1 and every weight is positive (the paper's choice).
    for (const char* name : {"tetra_1", "tetra_2", "tetra_3", "torus_4x5"}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const Level level = refine_c2g0(built.mesh.topology());
        for (Index row = 0; row < level.S0.rows(); ++row) {
            double sum = 0.0;
            for (SparseMatrix::InnerIterator it(level.S0, row); it; ++it) {
                EXPECT_GT(it.value(), 0.0) << name << " row " << row;
                sum += it.value();
            }
            EXPECT_NEAR(sum, 1.0, 1e-15) << name << " row " << row;
        }
    }
}

TEST(C2g0Rules, RefiningTheSubdividedTetrahedraGivesTheNextOne) {
    // F_tetra,j refined once has the counts of F_tetra,j+1 (the paper's Fig. 6 family), the four
    // valence-3 vertices stay where they were, and the prediction of Hierarchy is exact.
    for (int j = 1; j <= 3; ++j) {
        const BuildResult built = read_mesh(test::find_bundled("tetra_" + std::to_string(j)).path);
        const BuildResult next = read_mesh(test::find_bundled("tetra_" + std::to_string(j + 1)).path);
        RefineOptions options;
        options.scheme = SchemeKind::C2g0;
        options.levels = 2;
        const Hierarchy h(built.mesh.topology(), options);
        EXPECT_EQ(h.topology(1).num_vertices(), next.mesh.num_vertices());
        EXPECT_EQ(h.topology(1).num_faces(), next.mesh.num_faces());
        const auto predicted = predict_sizes(built.mesh.topology(), SchemeKind::C2g0, 2);
        EXPECT_EQ(predicted[2].vertices, h.topology(2).num_vertices());
        EXPECT_EQ(predicted[2].faces, h.topology(2).num_faces());
        EXPECT_GE(predicted[0].step_nonzeros, static_cast<std::int64_t>(h.step(1).S0.nonZeros()));
        for (Index v = 0; v < 4; ++v) {
            EXPECT_EQ(h.topology(2).valence(v), 3);
        }
        // The refined level is a valid mesh.
        const ControlMesh level2(h.topology(2), h.positions(2, built.mesh.positions()));
        EXPECT_FALSE(validate(to_polygon_soup(level2)).has_errors());
    }
}

TEST(C2g0Rules, MeshesTheRulesDoNotCoverAreRefusedByName) {
    const auto message = [](const char* name) {
        try {
            (void)refine_c2g0(read_mesh(test::find_bundled(name).path).mesh.topology());
        } catch (const UnsupportedError& error) {
            return std::string(error.what());
        }
        return std::string("no error");
    };
    // The tetrahedron: four valence-3 vertices, each adjacent to the others.
    EXPECT_NE(message("tetra_0").find("both have valence 3 and share an edge"), std::string::npos)
        << message("tetra_0");
    EXPECT_EQ(message("icosahedron"), "vertex 0 has valence 5: C2g0 needs valences 3 and 6 only (closed meshes of "
                                      "genus 0 or 1)");
    EXPECT_EQ(message("cube").rfind("face 0 has 4 corners: C2g0 needs triangles", 0), 0U);
    EXPECT_NE(message("tri_grid").find("is on the boundary: C2g0 needs a closed mesh"), std::string::npos)
        << message("tri_grid");
    try {
        (void)refine_c2g0(read_mesh(test::find_bundled("icosahedron").path).mesh.topology());
    } catch (const UnsupportedError& error) {
        ASSERT_TRUE(error.element().has_value());
        EXPECT_EQ(error.element()->kind, ErrorElement::Kind::Vertex);
        EXPECT_EQ(error.element()->index, 0);
    }
}

}  // namespace
}  // namespace limsurf
