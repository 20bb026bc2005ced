// Inner products of discrete forms.
// Polygonal (Alexa–Wardetzky): symmetric positive definite on every bundled mesh, scale as
// s^{2(1−k)}, exact for constant forms on planar meshes, the cotan Laplacian on triangles (against
// an independent cotangent formula), the circumcentric DEC Hodge star on regular polygons.
// Subdivision (SEC Eq. 12): SPD, Laplacian kills constants and (away from the boundary) linear
// functions on planar meshes, the area-gradient identity (Eq. 15) against finite differences,
// divergence consistency across levels (Eq. 14), dim ker(Hodge–Laplacian on 1-forms) = 2·genus,
// and convergence of M0 to the Galerkin mass matrix of the exact limit basis.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/exterior_derivative.h"
#include "limsurf/sec/inner_products.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

Eigen::MatrixXd dense(const SparseMatrix& m) {
    return Eigen::MatrixXd(m);
}

double smallest_eigenvalue(const SparseMatrix& m) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(dense(m), Eigen::EigenvaluesOnly);
    return eig.eigenvalues()(0);
}

double asymmetry(const SparseMatrix& m) {
    return (dense(m) - dense(m).transpose()).cwiseAbs().maxCoeff();
}

/// Sum of |vector area| over the faces: the polygonal area.
double polygonal_area(const Topology& t, const Points& X) {
    double area = 0.0;
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto verts = t.face_vertices(f);
        Eigen::Vector3d a = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < verts.size(); ++i) {
            a += 0.5 * Eigen::Vector3d(X.row(verts[i])).cross(Eigen::Vector3d(X.row(verts[(i + 1) % verts.size()])));
        }
        area += a.norm();
    }
    return area;
}

class EveryMesh : public ::testing::TestWithParam<test::BundledMesh> {};

TEST_P(EveryMesh, PolygonalInnerProductsAreSymmetricPositiveDefinite) {
    const BuildResult built = read_mesh(GetParam().path);
    const InnerProducts m = polygonal_inner_products(built.mesh.topology(), built.mesh.positions());
    for (const SparseMatrix* M : {&m.M0, &m.M1, &m.M2}) {
        EXPECT_LE(asymmetry(*M), 1e-15);
        EXPECT_GT(smallest_eigenvalue(*M), 0.0);
    }
}

TEST_P(EveryMesh, PolygonalInnerProductsScaleAsS2To1MinusK) {
    const BuildResult built = read_mesh(GetParam().path);
    const Topology& t = built.mesh.topology();
    const double s = 2.5;
    const InnerProducts m = polygonal_inner_products(t, built.mesh.positions());
    const InnerProducts ms = polygonal_inner_products(t, s * built.mesh.positions());
    // M0 holds areas: relative to its size where that exceeds 1 (the pinched cylinder's are near 1e4).
    EXPECT_LE((dense(ms.M0) - s * s * dense(m.M0)).cwiseAbs().maxCoeff(),
              1e-13 * s * s * std::max(1.0, dense(m.M0).cwiseAbs().maxCoeff()));
    EXPECT_LE((dense(ms.M1) - dense(m.M1)).cwiseAbs().maxCoeff(), 1e-13);
    // M2 = 1/area: relative to its size (a fine mesh such as tetra_4 has entries near 100).
    EXPECT_LE((dense(ms.M2) - dense(m.M2) / (s * s)).cwiseAbs().maxCoeff(), 1e-13 * dense(m.M2).cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(Sec, EveryMesh, ::testing::ValuesIn(test::bundled_meshes()),
                         [](const ::testing::TestParamInfo<test::BundledMesh>& param) { return param.param.name; });

TEST(PolygonalInnerProducts, ConstantFormsAreExactOnPlanarMeshes) {
    for (const char* name : {"quad_grid", "tri_grid", "disk_ev5_quads", "disk_ev7_tris", "annulus", "pentagon",
                             "hexagon_fan", "single_triangle"}) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        const InnerProducts m = polygonal_inner_products(t, X);
        const double area = polygonal_area(t, X);
        const SparseMatrix d0 = exterior_derivative_0(t);
        // 1-forms of the constant fields g = (1, 0.3), h = (−0.4, 2): ⟨dg·x, dh·x⟩ = area · g·h.
        const Eigen::VectorXd a = d0 * (X.col(0) + 0.3 * X.col(1));
        const Eigen::VectorXd b = d0 * (-0.4 * X.col(0) + 2.0 * X.col(1));
        EXPECT_NEAR(a.dot(m.M1 * b), area * (1.0 * -0.4 + 0.3 * 2.0), 1e-13) << name;
        EXPECT_NEAR(a.dot(m.M1 * a), area * (1.0 + 0.09), 1e-13) << name;
        // Constant 0- and 2-forms: 1ᵀ M0 1 = area, and c·A_f integrated values give c² area.
        EXPECT_NEAR(Eigen::VectorXd::Ones(t.num_vertices()).dot(m.M0 * Eigen::VectorXd::Ones(t.num_vertices())), area,
                    1e-13)
            << name;
        const Eigen::VectorXd face_areas = m.M2.diagonal().cwiseInverse();
        EXPECT_NEAR((3.0 * face_areas).dot(m.M2 * (3.0 * face_areas)), 9.0 * area, 1e-12) << name;
    }
}

/// The cotangent stiffness matrix, written out independently: K_ij = −½(cot α_ij + cot β_ij).
Eigen::MatrixXd cotan_stiffness(const Topology& t, const Points& X) {
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(t.num_vertices(), t.num_vertices());
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto v = t.face_vertices(f);
        for (int k = 0; k < 3; ++k) {
            const Index i = v[static_cast<std::size_t>(k)];
            const Index j = v[static_cast<std::size_t>((k + 1) % 3)];
            const Index o = v[static_cast<std::size_t>((k + 2) % 3)];
            const Eigen::Vector3d a = X.row(i) - X.row(o);
            const Eigen::Vector3d b = X.row(j) - X.row(o);
            const double cot = a.dot(b) / a.cross(b).norm();
            K(i, j) -= 0.5 * cot;
            K(j, i) -= 0.5 * cot;
            K(i, i) += 0.5 * cot;
            K(j, j) += 0.5 * cot;
        }
    }
    return K;
}

TEST(PolygonalInnerProducts, LaplacianIsTheCotanLaplacianOnTriangles) {
    for (const auto& mesh : test::triangle_meshes()) {
        const BuildResult built = read_mesh(mesh.path);
        const Topology& t = built.mesh.topology();
        const InnerProducts m = polygonal_inner_products(t, built.mesh.positions());
        const SparseMatrix d0 = exterior_derivative_0(t);
        const Eigen::MatrixXd L = dense(SparseMatrix(SparseMatrix(d0.transpose()) * m.M1 * d0));
        EXPECT_LE((L - cotan_stiffness(t, built.mesh.positions())).cwiseAbs().maxCoeff(), 1e-13) << mesh.name;
    }
}

TEST(PolygonalInnerProducts, RegularPolygonsGetTheCircumcentricHodgeStar) {
    // A regular n-gon of edge ℓ and inradius r: M_f = (r/ℓ)·I. hexagon_fan: equilateral triangles,
    // r/ℓ = cot(60°)/2 per face, so M1 is diagonal with that times the number of faces at the edge.
    const BuildResult fan = read_mesh(test::find_bundled("hexagon_fan").path);
    const Topology& t = fan.mesh.topology();
    const SparseMatrix M1 = polygonal_inner_products(t, fan.mesh.positions()).M1;
    const double star = 0.5 / std::tan(std::numbers::pi / 3.0);
    for (Index e = 0; e < t.num_edges(); ++e) {
        for (Index f = 0; f < t.num_edges(); ++f) {
            const double expected = e == f ? star * static_cast<double>(t.edge_faces(e).size()) : 0.0;
            EXPECT_NEAR(M1.coeff(e, f), expected, 1e-12) << e << " " << f;  // coordinates have 12 decimals
        }
    }
    const BuildResult pentagon = read_mesh(test::find_bundled("pentagon").path);
    const SparseMatrix P1 = polygonal_inner_products(pentagon.mesh.topology(), pentagon.mesh.positions()).M1;
    const double ratio = 0.5 / std::tan(std::numbers::pi / 5.0);  // r/ℓ = cot(π/n)/2
    EXPECT_LE((dense(P1) - ratio * Eigen::MatrixXd::Identity(5, 5)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(PolygonalInnerProducts, RefusesDegenerateFaces) {
    const Topology t = Topology::from_polygons(3, {{0, 1, 2}});
    Points X(3, 3);
    X << 0, 0, 0, 1, 0, 0, 2, 0, 0;
    EXPECT_THROW((void)polygonal_inner_products(t, X), NumericalError);
    EXPECT_THROW((void)polygonal_inner_products(t, Points(2, 3)), InputError);
}

// --- subdivision inner products --------------------------------------------------------------

struct SecCase {
    const char* mesh;
    SchemeKind scheme;
};

const SecCase sec_cases[] = {{"genus2", SchemeKind::CatmullClark},         {"quad_valence_5", SchemeKind::CatmullClark},
                             {"disk_ev5_quads", SchemeKind::CatmullClark}, {"icosahedron", SchemeKind::Loop},
                             {"disk_ev7_tris", SchemeKind::Loop},          {"tri_torus", SchemeKind::Loop}};

InnerProductOptions sec_options(int level) {
    InnerProductOptions o;
    o.method = InnerProductMethod::Sec;
    o.level = level;
    return o;
}

TEST(SecInnerProducts, SymmetricPositiveDefiniteAndKillConstants) {
    for (const auto& c : sec_cases) {
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        const Topology& t = built.mesh.topology();
        const InnerProducts m = control_inner_products(t, built.mesh.positions(), c.scheme, sec_options(2));
        for (const SparseMatrix* M : {&m.M0, &m.M1, &m.M2}) {
            const double scale = dense(*M).cwiseAbs().maxCoeff();
            EXPECT_LE(asymmetry(*M), 1e-15 * scale) << c.mesh;
            EXPECT_GT(smallest_eigenvalue(*M), 1e-10 * scale) << c.mesh;
        }
        const SparseMatrix d0 = exterior_derivative_0(t);
        const Eigen::VectorXd L1 =
            SparseMatrix(d0.transpose()) * (m.M1 * (d0 * Eigen::VectorXd::Ones(t.num_vertices())));
        EXPECT_EQ(L1.cwiseAbs().maxCoeff(), 0.0) << c.mesh;
    }
}

TEST(SecInnerProducts, LaplacianKillsLinearFunctionsAwayFromTheBoundaryOfPlanarMeshes) {
    for (const auto& c : {SecCase{"disk_ev5_quads", SchemeKind::CatmullClark},
                          SecCase{"disk_ev7_tris", SchemeKind::Loop}, SecCase{"quad_grid", SchemeKind::CatmullClark}}) {
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        const int L = 3;
        const InnerProducts m = control_inner_products(t, X, c.scheme, sec_options(L));
        const SparseMatrix d0 = exterior_derivative_0(t);
        const Eigen::VectorXd Lx =
            SparseMatrix(d0.transpose()) * (m.M1 * (d0 * Eigen::VectorXd(X.col(0) + 0.5 * X.col(1))));
        // Control vertices whose basis function does not reach the boundary of level L.
        RefineOptions refine;
        refine.scheme = c.scheme;
        refine.levels = L;
        const Hierarchy h(t, refine);
        const SparseMatrix AT = h.accumulated(L).transpose();
        int interior = 0;
        for (Index v = 0; v < t.num_vertices(); ++v) {
            bool reaches_boundary = false;
            for (SparseMatrix::InnerIterator it(AT, v); it; ++it) {
                reaches_boundary = reaches_boundary || h.topology(L).is_boundary_vertex(static_cast<Index>(it.col()));
            }
            if (!reaches_boundary) {
                ++interior;
                EXPECT_NEAR(Lx(v), 0.0, 1e-13) << c.mesh << " vertex " << v;
            }
        }
        EXPECT_GT(interior, 0) << c.mesh;
    }
}

TEST(SecInnerProducts, AreaGradientIsTheLaplacianOfThePositions) {
    // Eq. 15: ∇_{X⁰} A^L = L_0^0 X⁰ with A^L the polygonal area of level L; triangles (Loop) have
    // planar faces, where the polygonal Laplacian is exactly the area gradient.
    const BuildResult built = read_mesh(test::find_bundled("tri_valence_7").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const int L = 2;
    RefineOptions refine;
    refine.scheme = SchemeKind::Loop;
    refine.levels = L;
    const Hierarchy h(t, refine);
    const auto area = [&](const Points& P) { return polygonal_area(h.topology(L), h.positions(L, P)); };
    const InnerProducts m = control_inner_products(t, X, SchemeKind::Loop, sec_options(L));
    const SparseMatrix d0 = exterior_derivative_0(t);
    const Points gradient = SparseMatrix(d0.transpose()) * (m.M1 * (d0 * X));
    const double step = 1e-6;
    double worst = 0.0;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        for (int k = 0; k < 3; ++k) {
            Points plus = X;
            Points minus = X;
            plus(v, k) += step;
            minus(v, k) -= step;
            const double fd = (area(plus) - area(minus)) / (2.0 * step);
            worst = std::max(worst, std::abs(fd - gradient(v, k)));
        }
    }
    EXPECT_LE(worst, 1e-8);
}

TEST(SecInnerProducts, DivergenceIsConsistentAcrossLevels) {
    // Eq. 14: d0ᵀ M1^0 w = S0ᵀ d0'ᵀ M1^1 (S1 w), M1^0 and M1^1 from the same finest level.
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    RefineOptions refine;
    refine.scheme = SchemeKind::CatmullClark;
    refine.levels = 3;
    refine.forms = true;
    const Hierarchy h(t, refine);
    const Points X3 = h.positions(3, built.mesh.positions());
    const InnerProducts m0 = pulled_back_inner_products(h, 3, X3);
    // M1 on level 1: pull back from level 3 to level 1 only.
    InnerProducts fine = polygonal_inner_products(h.topology(3), X3);
    SparseMatrix M1 = fine.M1;
    for (int l = 3; l >= 2; --l) {
        M1 = SparseMatrix(SparseMatrix(h.step(l).S1.transpose()) * M1 * h.step(l).S1);
    }
    const Eigen::VectorXd w = Eigen::VectorXd::LinSpaced(t.num_edges(), -1.0, 2.0).array().sin();
    const Eigen::VectorXd coarse = SparseMatrix(exterior_derivative_0(t).transpose()) * (m0.M1 * w);
    const Eigen::VectorXd via_fine =
        SparseMatrix(h.step(1).S0.transpose()) *
        (SparseMatrix(exterior_derivative_0(h.topology(1)).transpose()) * (M1 * (h.step(1).S1 * w)));
    EXPECT_LE((coarse - via_fine).cwiseAbs().maxCoeff(), 1e-12 * coarse.cwiseAbs().maxCoeff());
}

TEST(SecInnerProducts, HarmonicOneFormsSpanTwiceTheGenus) {
    for (const auto& c : {SecCase{"quad_torus", SchemeKind::CatmullClark}, SecCase{"genus2", SchemeKind::CatmullClark},
                          SecCase{"tri_torus", SchemeKind::Loop}, SecCase{"icosahedron", SchemeKind::Loop}}) {
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        const Topology& t = built.mesh.topology();
        const InnerProducts m = control_inner_products(t, built.mesh.positions(), c.scheme, sec_options(2));
        const Eigen::MatrixXd d0 = dense(exterior_derivative_0(t));
        const Eigen::MatrixXd d1 = dense(exterior_derivative_1(t));
        const Eigen::MatrixXd M1 = dense(m.M1);
        const Eigen::MatrixXd L1 =
            M1 * d0 * dense(m.M0).ldlt().solve(d0.transpose() * M1) + d1.transpose() * dense(m.M2) * d1;
        const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (L1 + L1.transpose()), Eigen::EigenvaluesOnly);
        const double scale = eig.eigenvalues().cwiseAbs().maxCoeff();
        int kernel = 0;
        for (Eigen::Index i = 0; i < eig.eigenvalues().size(); ++i) {
            kernel += std::abs(eig.eigenvalues()(i)) < 1e-10 * scale ? 1 : 0;
        }
        EXPECT_EQ(kernel, 2 * t.genus()) << c.mesh;
        EXPECT_GT(eig.eigenvalues()(2 * t.genus()), 1e-6 * scale) << c.mesh;
    }
}

TEST(SecInnerProducts, MassMatrixConvergesToTheGalerkinMassOfTheLimitBasis) {
    // Independent witness: ∫ φ_i φ_j dA by Gauss quadrature on the exact limit surface (Stam tiles
    // near the extraordinary vertices); the SEC M0 at levels 1..4 approaches it, each level cutting
    // the difference by about 4 (the O(h²) of the polygonal mass at level L).
    for (const auto& c :
         {SecCase{"quad_valence_5", SchemeKind::CatmullClark}, SecCase{"icosahedron", SchemeKind::Loop}}) {
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        const LimitBasis basis(t, c.scheme);
        const LimitSampler sampler(basis, 8, 10);
        const Eigen::MatrixXd galerkin = dense(galerkin_mass_matrix(sampler, X));
        std::vector<double> error;
        for (int L = 1; L <= 4; ++L) {
            const InnerProducts m = control_inner_products(t, X, c.scheme, sec_options(L));
            error.push_back((dense(m.M0) - galerkin).norm() / galerkin.norm());
            ::testing::Test::RecordProperty(std::string(c.mesh) + "_level_" + std::to_string(L),
                                            std::to_string(error.back()));
        }
        for (std::size_t i = 1; i < error.size(); ++i) {
            const double ratio = error[i - 1] / error[i];
            EXPECT_GT(ratio, 3.0) << c.mesh << " level " << i + 1 << " errors " << error[i - 1] << " " << error[i];
            EXPECT_LT(ratio, 5.0) << c.mesh << " level " << i + 1;
        }
        EXPECT_LT(error.back(), 2e-2) << c.mesh;
    }
}

}  // namespace
}  // namespace limsurf
