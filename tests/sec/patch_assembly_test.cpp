// The patch assembly of the subdivision inner products (SecAssembly::Patches: per control face,
// from ring stencils refined on their own) against the reference assembly from the whole
// hierarchy (SecAssembly::Hierarchy: Eq. 10 level by level). Both compute SEC Eq. 12 / 16 by
// different routes — different refinements, different summation orders — so they must agree to
// rounding on every mesh form subdivision supports, closed and open, both boundary rules,
// Sec and SecSnap, and on random carvings (many boundary configurations). The load vector
// (load_vector) is assembled both ways too.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/inner_products.h"
#include "limsurf/sec/operators.h"
#include "support/mesh_zoo.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

InnerProductOptions options_of(InnerProductMethod method, int level, SecAssembly assembly, int threads) {
    InnerProductOptions options;
    options.method = method;
    options.level = level;
    options.assembly = assembly;
    options.num_threads = threads;
    return options;
}

SchemeOptions rules_of(BoundaryInterpolation boundary) {
    SchemeOptions scheme_options;
    scheme_options.boundary = boundary;
    return scheme_options;
}

InnerProducts assembled(const Topology& t, const Points& X, SchemeKind scheme, InnerProductMethod method, int level,
                        SecAssembly assembly, BoundaryInterpolation boundary, int threads = 0) {
    return control_inner_products(t, X, scheme, options_of(method, level, assembly, threads), rules_of(boundary));
}

/// max |P − H| / max |H| over the three matrices (and the same sparsity is not required: an
/// entry that one assembly stores as an exact zero counts as a difference of zero).
double relative_difference(const InnerProducts& p, const InnerProducts& h) {
    double worst = 0.0;
    for (const auto& [a, b] : {std::pair{&p.M0, &h.M0}, std::pair{&p.M1, &h.M1}, std::pair{&p.M2, &h.M2}}) {
        const SparseMatrix diff = *a - *b;
        const double scale = SparseMatrix(b->cwiseAbs()).coeffs().maxCoeff();
        worst = std::max(worst, SparseMatrix(diff.cwiseAbs()).coeffs().maxCoeff() / scale);
    }
    return worst;
}

/// A smooth right-hand side that is no polynomial of the position (a sum of its samples would
/// not hide a wrong point or weight).
Eigen::VectorXd smooth_rhs(const Points& P) {
    Eigen::VectorXd v(P.rows());
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
        v(i) = std::sin(2.0 * P(i, 0)) + P(i, 1) * P(i, 2) + std::exp(0.3 * P(i, 2));
    }
    return v;
}

Eigen::VectorXd load(const Topology& t, const Points& X, SchemeKind scheme, InnerProductMethod method, int level,
                     SecAssembly assembly, BoundaryInterpolation boundary, int threads = 0, int* calls = nullptr) {
    const auto f = [calls](const Points& P) {
        if (calls != nullptr) {
            ++*calls;
        }
        return smooth_rhs(P);
    };
    return load_vector(t, X, scheme, options_of(method, level, assembly, threads), f, rules_of(boundary));
}

double relative_difference(const Eigen::VectorXd& p, const Eigen::VectorXd& h) {
    return (p - h).cwiseAbs().maxCoeff() / h.cwiseAbs().maxCoeff();
}

using Case = test::SchemeCase;

class PatchAssembly : public ::testing::TestWithParam<Case> {};

TEST_P(PatchAssembly, EqualsTheHierarchyAssembly) {
    // The inner products, and the load vector: the hierarchy route samples f once per level-L vertex
    // of the whole refined mesh and carries the weighted values back by S0ᵀ; the patch route samples
    // it per control face (a vertex on a control edge or corner once per face around it) and pulls
    // back through the ring stencils.
    const BuildResult built = read_mesh(test::find_bundled(GetParam().name).path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const SchemeKind scheme = GetParam().scheme;
    for (const auto boundary : {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly}) {
        for (const auto method : {InnerProductMethod::Sec, InnerProductMethod::SecSnap}) {
            for (const int level : {1, 2}) {
                SCOPED_TRACE(std::string(to_string(method)) + " L=" + std::to_string(level) + " boundary " +
                             std::to_string(static_cast<int>(boundary)));
                // 1e-12, not 1e-13: on tetra_4 at L = 2, M2 (sums of 1/|a| over level-2 faces, up to 123
                // here) differs by 5.0e-13 of its largest entry between the two routes; M0 and M1 by at
                // most 5e-15. (Until 2026-12-07 a misplaced break checked closed meshes at L = 1 only.)
                EXPECT_LE(relative_difference(assembled(t, X, scheme, method, level, SecAssembly::Patches, boundary),
                                              assembled(t, X, scheme, method, level, SecAssembly::Hierarchy, boundary)),
                          1e-12);
                EXPECT_LE(relative_difference(load(t, X, scheme, method, level, SecAssembly::Patches, boundary),
                                              load(t, X, scheme, method, level, SecAssembly::Hierarchy, boundary)),
                          1e-13);
            }
        }
        if (t.is_closed()) {
            break;  // the boundary rule changes nothing
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Sec, PatchAssembly, ::testing::ValuesIn(test::form_subdivision_cases()),
                         [](const ::testing::TestParamInfo<Case>& param) { return param.param.name; });

TEST(PatchAssemblyAtLevel3, EqualsTheHierarchyAssembly) {
    for (const Case& c : {Case{"genus2", SchemeKind::CatmullClark}, Case{"icosahedron", SchemeKind::Loop},
                          Case{"disk_ev5_quads", SchemeKind::CatmullClark}}) {
        const BuildResult built = read_mesh(test::find_bundled(c.name).path);
        const auto& t = built.mesh.topology();
        const auto& X = built.mesh.positions();
        const auto patches = assembled(t, X, c.scheme, InnerProductMethod::Sec, 3, SecAssembly::Patches,
                                       BoundaryInterpolation::EdgeAndCorner);
        const auto reference = assembled(t, X, c.scheme, InnerProductMethod::Sec, 3, SecAssembly::Hierarchy,
                                         BoundaryInterpolation::EdgeAndCorner);
        EXPECT_LE(relative_difference(patches, reference), 1e-13) << c.name;
        for (const auto method : {InnerProductMethod::Sec, InnerProductMethod::SecSnap}) {
            EXPECT_LE(
                relative_difference(
                    load(t, X, c.scheme, method, 3, SecAssembly::Patches, BoundaryInterpolation::EdgeAndCorner),
                    load(t, X, c.scheme, method, 3, SecAssembly::Hierarchy, BoundaryInterpolation::EdgeAndCorner)),
                1e-13)
                << c.name << " " << to_string(method) << " load";
        }
    }
}

TEST(PatchAssemblyOnCarvings, EqualsTheHierarchyAssembly) {
    // Random sub-meshes: boundary vertices with every fan size, ears, several loops (inner products
    // and load vector).
    std::mt19937 rng(7);
    int checked = 0;
    for (const Case& c : {Case{"quad_valence_8", SchemeKind::CatmullClark}, Case{"tri_valence_7", SchemeKind::Loop},
                          Case{"genus2", SchemeKind::CatmullClark}}) {
        const BuildResult built = read_mesh(test::find_bundled(c.name).path);
        const Topology& t = built.mesh.topology();
        for (int attempt = 0; attempt < 6; ++attempt) {
            std::bernoulli_distribution kept(attempt < 3 ? 0.8 : 0.93);
            std::vector<bool> keep(static_cast<std::size_t>(t.num_faces()));
            std::generate(keep.begin(), keep.end(), [&] { return kept(rng); });
            const auto carved = test::carve(t, keep);
            if (!carved) {
                continue;
            }
            Points X(static_cast<Eigen::Index>(carved->original_vertex.size()), 3);
            for (std::size_t v = 0; v < carved->original_vertex.size(); ++v) {
                X.row(static_cast<Eigen::Index>(v)) = built.mesh.positions().row(carved->original_vertex[v]);
            }
            for (const auto boundary : {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly}) {
                const auto reference = assembled(carved->topology, X, c.scheme, InnerProductMethod::Sec, 2,
                                                 SecAssembly::Hierarchy, boundary);
                const auto patches = assembled(carved->topology, X, c.scheme, InnerProductMethod::Sec, 2,
                                               SecAssembly::Patches, boundary);
                EXPECT_LE(relative_difference(patches, reference), 1e-13) << c.name << " carving " << attempt;
                EXPECT_LE(relative_difference(load(carved->topology, X, c.scheme, InnerProductMethod::Sec, 2,
                                                   SecAssembly::Patches, boundary),
                                              load(carved->topology, X, c.scheme, InnerProductMethod::Sec, 2,
                                                   SecAssembly::Hierarchy, boundary)),
                          1e-13)
                    << c.name << " carving " << attempt << " load";
                ++checked;
            }
        }
    }
    EXPECT_GE(checked, 12);
}

TEST(PatchAssembly, IsTheSameOnAnyNumberOfThreads) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const auto& t = built.mesh.topology();
    const auto& X = built.mesh.positions();
    const auto one = assembled(t, X, SchemeKind::CatmullClark, InnerProductMethod::Sec, 2, SecAssembly::Patches,
                               BoundaryInterpolation::EdgeAndCorner, 1);
    const auto three = assembled(t, X, SchemeKind::CatmullClark, InnerProductMethod::Sec, 2, SecAssembly::Patches,
                                 BoundaryInterpolation::EdgeAndCorner, 3);
    EXPECT_EQ(relative_difference(one, three), 0.0);
    for (const SparseMatrix* M : {&one.M0, &one.M1, &one.M2}) {
        EXPECT_EQ(SparseMatrix(*M - SparseMatrix(M->transpose())).coeffs().cwiseAbs().maxCoeff(), 0.0)
            << "exactly symmetric";
    }
}

TEST(PatchAssembly, NamesTheControlFaceAroundADegenerateRefinedFace) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const auto& t = built.mesh.topology();
    Points X = built.mesh.positions();
    // Collapse face 5 and its ring to one point: every level-2 face inside face 5 has zero area.
    for (const Index c : t.face_vertices(5)) {
        for (const Index h : t.vertex_faces(c)) {
            for (const Index v : t.face_vertices(h)) {
                X.row(v) = X.row(t.face_vertices(5)[0]);
            }
        }
    }
    try {
        (void)assembled(t, X, SchemeKind::CatmullClark, InnerProductMethod::Sec, 2, SecAssembly::Patches,
                        BoundaryInterpolation::EdgeAndCorner);
        FAIL() << "no error";
    } catch (const NumericalError& e) {
        EXPECT_NE(std::string(e.what()).find("inside control face "), std::string::npos) << e.what();
    }
}

TEST(PatchLoad, CallsTheRightHandSideInBlocksAndIsTheSameOnAnyNumberOfThreads) {
    // genus2 refined four times (12 800 quads): more control faces than one block of points holds.
    const FinestLevel fine = test::refined_bundled("genus2", SchemeKind::CatmullClark, 4);
    ASSERT_GT(fine.topology.num_faces(), 8192);
    int calls = 0;
    const auto one = load(fine.topology, fine.positions, SchemeKind::CatmullClark, InnerProductMethod::Sec, 1,
                          SecAssembly::Patches, BoundaryInterpolation::EdgeAndCorner, 1, &calls);
    EXPECT_GE(calls, 2);
    const auto three = load(fine.topology, fine.positions, SchemeKind::CatmullClark, InnerProductMethod::Sec, 1,
                            SecAssembly::Patches, BoundaryInterpolation::EdgeAndCorner, 3);
    EXPECT_EQ((one - three).cwiseAbs().maxCoeff(), 0.0) << "the same bits";
    const auto reference = load(fine.topology, fine.positions, SchemeKind::CatmullClark, InnerProductMethod::Sec, 1,
                                SecAssembly::Hierarchy, BoundaryInterpolation::EdgeAndCorner);
    EXPECT_LE(relative_difference(one, reference), 1e-13);
}

TEST(PatchLoad, MeshesWithoutFormRulesTakeTheHierarchy) {
    // Catmull–Clark on a mesh with n-gons and on one with creases: no form rules, so no ring
    // stencils; the load still integrates f at level L (Σ_i b_i = Σ f m over level L).
    for (const char* name : {"cube_ngons", "cube_creases"}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const auto& t = built.mesh.topology();
        const auto& X = built.mesh.positions();
        InnerProductOptions options;
        options.level = 2;
        const auto ones = [](const Points& P) { return Eigen::VectorXd::Ones(P.rows()).eval(); };
        const Eigen::VectorXd b = load_vector(t, X, SchemeKind::CatmullClark, options, ones);
        const FinestLevel fine = test::refined_bundled(name, SchemeKind::CatmullClark, 2);
        EXPECT_NEAR(b.sum(), polygonal_vertex_masses(fine.topology, fine.positions).sum(), 1e-12) << name;
    }
}

}  // namespace
}  // namespace limsurf
