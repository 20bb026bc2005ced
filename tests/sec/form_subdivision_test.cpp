// Form subdivision S1, S2 (SEC §3.1, Eq. 6): on every bundled triangle mesh (Loop) and quad mesh
// (Catmull–Clark), closed and open, and on meshes carved at random out of them (boundary vertices
// with 1..8 faces, ears, several boundary loops), under both boundary rules, for three levels:
//   d0' S0 = S1 d0 and d1' S1 = S2 d1 to round-off; every row of S2 sums to 1/4, every column to 1.
// Published rules: entries of S1 and S2 equal the closed forms and tables of the SEC-era reference
// rules (Wang et al. 2006 / SEC supplemental as transcribed by SecStencils) at chosen vertices.
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/form_subdivision.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"
#include "limsurf/sec/exterior_derivative.h"
#include "support/mesh_zoo.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

double max_abs(const SparseMatrix& m) {
    double worst = 0.0;
    for (Eigen::Index r = 0; r < m.outerSize(); ++r) {
        for (SparseMatrix::InnerIterator it(m, r); it; ++it) {
            worst = std::max(worst, std::abs(it.value()));
        }
    }
    return worst;
}

struct Residuals {
    double d0 = 0.0;         ///< max |d0' S0 − S1 d0|
    double d1 = 0.0;         ///< max |d1' S1 − S2 d1|
    double row_sum = 0.0;    ///< max |row sum of S2 − 1/4|
    double col_sum = 0.0;    ///< max |column sum of S2 − 1|
    double s0_change = 0.0;  ///< max |S0 with forms − S0 without|
};

Residuals step_residuals(const Topology& parent, const Level& level, const Level& plain) {
    Residuals r;
    const Topology& child = level.topology;
    r.d0 = max_abs(SparseMatrix(exterior_derivative_0(child) * level.S0 - level.S1 * exterior_derivative_0(parent)));
    r.d1 = max_abs(SparseMatrix(exterior_derivative_1(child) * level.S1 - level.S2 * exterior_derivative_1(parent)));
    const Eigen::VectorXd rows = level.S2 * Eigen::VectorXd::Ones(parent.num_faces());
    const Eigen::RowVectorXd cols = Eigen::RowVectorXd::Ones(child.num_faces()) * level.S2;
    r.row_sum = (rows.array() - 0.25).abs().maxCoeff();
    r.col_sum = (cols.array() - 1.0).abs().maxCoeff();
    r.s0_change = max_abs(SparseMatrix(level.S0 - plain.S0));
    return r;
}

using Case = test::SchemeCase;

class FormCommutation : public ::testing::TestWithParam<Case> {};

/// Checks three levels from @p base; returns the boundary fan sizes seen at level 0.
std::set<Index> check_levels(const Topology& base, SchemeKind scheme, BoundaryInterpolation boundary,
                             const std::string& what) {
    SchemeOptions options;
    options.boundary = boundary;
    std::set<Index> fans;
    for (Index v = 0; v < base.num_vertices(); ++v) {
        if (base.is_boundary_vertex(v)) {
            fans.insert(static_cast<Index>(base.vertex_faces(v).size()));
        }
    }
    Topology parent = base;
    for (int l = 0; l < 3 && parent.num_faces() < 20000; ++l) {
        const Level level = refine_with_forms(parent, scheme, options);
        const Level plain = refine(parent, scheme, options);
        const Residuals r = step_residuals(parent, level, plain);
        EXPECT_LE(r.d0, 1e-14) << what << " level " << l;
        EXPECT_LE(r.d1, 1e-14) << what << " level " << l;
        EXPECT_LE(r.row_sum, 1e-15) << what << " level " << l;
        EXPECT_LE(r.col_sum, 1e-14) << what << " level " << l;
        EXPECT_EQ(r.s0_change, 0.0) << what << " level " << l;
        EXPECT_EQ(level.S1.rows(), level.topology.num_edges());
        EXPECT_EQ(level.S1.cols(), parent.num_edges());
        EXPECT_EQ(level.S2.rows(), level.topology.num_faces());
        EXPECT_EQ(level.S2.cols(), parent.num_faces());
        parent = level.topology;
    }
    return fans;
}

TEST_P(FormCommutation, BundledMeshBothBoundaryRules) {
    const BuildResult built = read_mesh(test::find_bundled(GetParam().name).path);
    for (const auto boundary : {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly}) {
        check_levels(built.mesh.topology(), GetParam().scheme, boundary, GetParam().name);
    }
}

TEST_P(FormCommutation, CarvedAtRandom) {
    const BuildResult built = read_mesh(test::find_bundled(GetParam().name).path);
    const Topology& t = built.mesh.topology();
    std::mt19937 random(12345);
    int checked = 0;
    for (int attempt = 0; attempt < 40 && checked < 3; ++attempt) {
        // Heavy carvings first (many boundary configurations, often pinched and skipped), then
        // lighter ones, which large meshes need to stay manifold.
        std::bernoulli_distribution drop(attempt < 8 ? 0.3 : attempt < 20 ? 0.1 : 0.03);
        std::vector<bool> keep(static_cast<std::size_t>(t.num_faces()));
        for (std::size_t f = 0; f < keep.size(); ++f) {
            keep[f] = !drop(random);
        }
        const auto carved = test::carve(t, keep);
        if (!carved) {
            continue;
        }
        ++checked;
        check_levels(carved->topology, GetParam().scheme, BoundaryInterpolation::EdgeAndCorner,
                     GetParam().name + " carved " + std::to_string(attempt));
        check_levels(carved->topology, GetParam().scheme, BoundaryInterpolation::EdgeOnly,
                     GetParam().name + " carved " + std::to_string(attempt));
    }
    EXPECT_GT(checked, 0) << "no carving of " << GetParam().name << " was a manifold";
}

INSTANTIATE_TEST_SUITE_P(Sec, FormCommutation, ::testing::ValuesIn(test::form_subdivision_cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             return param.param.name + (param.param.scheme == SchemeKind::Loop ? "_loop" : "_cc");
                         });

/// Boundary vertices with every fan size 1..8 are exercised (the carving above is random, so this
/// test makes the coverage explicit): the open fans of the valence-8 poles, cut to k faces.
TEST(FormCommutationFans, BoundaryFansOfEveryWidth) {
    for (const auto& [name, scheme] :
         {std::pair{"tri_valence_8", SchemeKind::Loop}, std::pair{"quad_valence_8", SchemeKind::CatmullClark}}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const Topology& t = built.mesh.topology();
        Index pole = 0;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (t.valence(v) == 8) {
                pole = v;
                break;
            }
        }
        for (Index k = 1; k <= 8; ++k) {
            // Keep the first k faces of the pole's fan and their neighbours' neighbours.
            std::vector<bool> keep(static_cast<std::size_t>(t.num_faces()), false);
            const auto fan = t.vertex_faces(pole);
            for (Index i = 0; i < k; ++i) {
                keep[static_cast<std::size_t>(fan[static_cast<std::size_t>(i)])] = true;
            }
            const auto carved = test::carve(t, keep);
            ASSERT_TRUE(carved.has_value()) << name << " k = " << k;
            const std::set<Index> fans = check_levels(carved->topology, scheme, BoundaryInterpolation::EdgeOnly,
                                                      std::string(name) + " fan " + std::to_string(k));
            check_levels(carved->topology, scheme, BoundaryInterpolation::EdgeAndCorner,
                         std::string(name) + " fan " + std::to_string(k));
            if (k < 8) {
                EXPECT_TRUE(fans.count(k)) << name << " k = " << k;
            }
        }
    }
}

TEST(FormHierarchy, AccumulatedOperatorsCommuteWithD) {
    // d_k^L A_k^L = A_{k+1}^L d_k^0 at L = 3 (SEC Eq. 5-6), on an open and a closed mesh per scheme.
    for (const auto& [name, scheme] :
         {std::pair{"genus2", SchemeKind::CatmullClark}, std::pair{"annulus", SchemeKind::CatmullClark},
          std::pair{"tri_valence_5", SchemeKind::Loop}, std::pair{"disk_ev7_tris", SchemeKind::Loop}}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        RefineOptions options;
        options.scheme = scheme;
        options.levels = 3;
        options.forms = true;
        const Hierarchy h(built.mesh.topology(), options);
        const Topology& base = h.topology(0);
        const Topology& fine = h.topology(3);
        EXPECT_LE(max_abs(SparseMatrix(exterior_derivative_0(fine) * h.accumulated_form(0, 3) -
                                       h.accumulated_form(1, 3) * exterior_derivative_0(base))),
                  1e-13)
            << name;
        EXPECT_LE(max_abs(SparseMatrix(exterior_derivative_1(fine) * h.accumulated_form(1, 3) -
                                       h.accumulated_form(2, 3) * exterior_derivative_1(base))),
                  1e-13)
            << name;
        EXPECT_EQ(h.accumulated_form(2, 3).rows(), fine.num_faces());
        // apply_form carries data step by step: the accumulated product's values up to rounding.
        for (int k = 0; k <= 2; ++k) {
            const Index n = static_cast<Index>(h.accumulated_form(k, 0).rows());
            const Eigen::MatrixXd data = Eigen::MatrixXd::Random(n, 2);
            const Eigen::MatrixXd expected = h.accumulated_form(k, 3) * data;
            const Eigen::MatrixXd carried = h.apply_form(k, 3, data);
            ASSERT_EQ(carried.rows(), expected.rows()) << name << " k = " << k;
            EXPECT_LE((carried - expected).lpNorm<Eigen::Infinity>(), 1e-14 * expected.lpNorm<Eigen::Infinity>())
                << name << " k = " << k;
            EXPECT_EQ(h.apply_form(k, 0, data), data) << name << " k = " << k;
        }
        EXPECT_THROW((void)h.apply_form(1, 3, Eigen::MatrixXd::Zero(base.num_edges() + 1, 1)), InputError) << name;
        EXPECT_THROW((void)h.apply_form(2, 4, Eigen::MatrixXd::Zero(base.num_faces(), 1)), InputError) << name;
    }
    const BuildResult cube = read_mesh(test::find_bundled("cube").path);
    const Hierarchy plain(cube.mesh.topology(), RefineOptions{});
    EXPECT_THROW((void)plain.accumulated_form(1, 1), InputError);
    EXPECT_THROW((void)plain.accumulated_form(3, 0), InputError);
    EXPECT_THROW((void)plain.apply_form(1, 1, Eigen::MatrixXd::Zero(cube.mesh.topology().num_edges(), 1)), InputError);
    EXPECT_THROW((void)plain.apply_form(3, 0, Eigen::MatrixXd::Zero(8, 1)), InputError);
    EXPECT_EQ(plain.apply_form(0, 1, Eigen::MatrixXd::Ones(8, 1)), plain.apply(1, Eigen::MatrixXd::Ones(8, 1)));
}

// --- the rules' values against the reference tables ---------------------------------------------

/// The interior even 1-form row of spoke 0 at vertex v, as weights on spokes x_i (v → u_i).
std::vector<double> spoke_weights(const Topology& parent, const Level& level, Index v) {
    const auto edges = parent.vertex_edges(v);
    const Index m = level.topology.num_vertices() - parent.num_edges() + edges[0];  // edge point of spoke 0
    const Index fine = level.topology.find_edge(v, m);
    const double s_row = v < m ? 1.0 : -1.0;
    std::vector<double> w;
    for (const Index e : edges) {
        const double s_pq = v < parent.other_vertex(e, v) ? 1.0 : -1.0;
        w.push_back(s_row * s_pq * level.S1.coeff(fine, e));
    }
    return w;
}

TEST(FormRules, CatmullClarkValence5SpokesMatchTheReferenceTable) {
    // quad_valence_5: the poles have valence 5; FORMS/SecStencils table: x_0 = 127/400,
    // x_±1 = 29/800, x_±2 = −23/400.
    const BuildResult built = read_mesh(test::find_bundled("quad_valence_5").path);
    const Topology& t = built.mesh.topology();
    const Level level = refine_with_forms(t, SchemeKind::CatmullClark);
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.valence(v) != 5) {
            continue;
        }
        const std::vector<double> w = spoke_weights(t, level, v);
        const std::vector<double> expected{127.0 / 400, 29.0 / 800, -23.0 / 400, -23.0 / 400, 29.0 / 800};
        for (std::size_t i = 0; i < 5; ++i) {
            EXPECT_NEAR(w[i], expected[i], 1e-15) << "vertex " << v << " spoke " << i;
        }
    }
}

TEST(FormRules, LoopValence4And7SpokesMatchTheReferenceTable) {
    // x_i = [3/8 − β/4, 1/8, β/8 on offsets 0, ±1, ±2] − α: compare x_i + α (the tables are printed
    // with Warren's α; ours is Loop's original α, which the rule takes over unchanged).
    for (const auto& [name, n] : {std::pair{"tri_valence_4", 4}, std::pair{"tri_valence_7", 7}}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const Topology& t = built.mesh.topology();
        const Level level = refine_with_forms(t, SchemeKind::Loop);
        const double nd = n;
        const double b = std::cos(2.0 * 3.14159265358979323846 / nd) / 4.0 + 0.375;
        const double alpha = (0.625 - b * b) / nd;
        const double beta = n == 4 ? 0.125 : 0.25;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            if (t.valence(v) != n) {
                continue;
            }
            const std::vector<double> w = spoke_weights(t, level, v);
            std::vector<double> expected(static_cast<std::size_t>(n), 0.0);
            expected[0] = 0.375 - beta / 4;
            expected[1] += 0.125;
            expected[static_cast<std::size_t>(n - 1)] += 0.125;
            expected[2] += beta / 8;
            expected[static_cast<std::size_t>(n - 2)] += beta / 8;
            for (std::size_t i = 0; i < expected.size(); ++i) {
                EXPECT_NEAR(w[i] + alpha, expected[i], 1e-15) << name << " vertex " << v << " spoke " << i;
            }
        }
    }
}

TEST(FormRules, LoopValence5CornerRowHasEigenvalueOneEighth) {
    // The chosen β_5 = 1/(8(1 − cos 72°)) makes the corner 2-form rule a circulant with
    // eigenvalues 1/4 (constants) and 1/8, 1/8 — the regular half-box spline's.
    const BuildResult built = read_mesh(test::find_bundled("icosahedron").path);
    const Topology& t = built.mesh.topology();
    const Level level = refine_with_forms(t, SchemeKind::Loop);
    const Index v = 0;
    const auto fan = t.vertex_faces(v);
    const auto corners = t.vertex_face_corners(v);
    Eigen::MatrixXd circulant(5, 5);
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
            circulant(i, j) =
                level.S2.coeff(4 * fan[static_cast<std::size_t>(i)] + corners[static_cast<std::size_t>(i)],
                               fan[static_cast<std::size_t>(j)]);
        }
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(circulant);
    EXPECT_NEAR(eig.eigenvalues()(4), 0.25, 1e-15);
    EXPECT_NEAR(eig.eigenvalues()(3), 0.125, 1e-15);
    EXPECT_NEAR(eig.eigenvalues()(2), 0.125, 1e-15);
}

TEST(FormRules, CatmullClarkRegularCornerRowIsTheBiquadraticMask) {
    // k = 4: parent 9/64, edge neighbours 3/64, the diagonal face 1/64 (Doo–Sabin regular mask / 4).
    const BuildResult built = read_mesh(test::find_bundled("quad_torus").path);
    const Topology& t = built.mesh.topology();
    const Level level = refine_with_forms(t, SchemeKind::CatmullClark);
    const auto fan = t.vertex_faces(0);
    const auto corners = t.vertex_face_corners(0);
    const Index child = 4 * fan[0] + corners[0];
    EXPECT_DOUBLE_EQ(level.S2.coeff(child, fan[0]), 9.0 / 64);
    EXPECT_DOUBLE_EQ(level.S2.coeff(child, fan[1]), 3.0 / 64);
    EXPECT_DOUBLE_EQ(level.S2.coeff(child, fan[2]), 1.0 / 64);
    EXPECT_DOUBLE_EQ(level.S2.coeff(child, fan[3]), 3.0 / 64);
}

TEST(FormRules, RefusesWhatHasNoRules) {
    const BuildResult creased = read_mesh(test::find_bundled("cube_creases").path);
    EXPECT_THROW((void)refine_with_forms(creased.mesh.topology(), SchemeKind::CatmullClark), UnsupportedError);
    const BuildResult ngons = read_mesh(test::find_bundled("cube_ngons").path);
    EXPECT_THROW((void)refine_with_forms(ngons.mesh.topology(), SchemeKind::CatmullClark), UnsupportedError);
    const BuildResult cube = read_mesh(test::find_bundled("cube").path);
    EXPECT_THROW((void)refine_with_forms(cube.mesh.topology(), SchemeKind::Loop), UnsupportedError);
    EXPECT_THROW((void)refine_with_forms(cube.mesh.topology(), SchemeKind::DooSabin), UnsupportedError);
    try {
        (void)refine_with_forms(creased.mesh.topology(), SchemeKind::CatmullClark);
    } catch (const UnsupportedError& e) {
        EXPECT_NE(std::string(e.what()).find("crease"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace limsurf
