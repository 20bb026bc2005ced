// Helmholtz–Hodge decomposition (apps/hodge.h; SEC §2.3, §4.3).
// Identities: the parts sum to the input, are mutually M1-orthogonal, dα is curl-free, δβ
// divergence-free, h closed and co-closed — for dec and sec on every bundled closed mesh and on meshes
// with boundary. Published/analytic: the harmonic space has dimension b1 = 2g + b − 1 (2g closed; the
// Betti numbers from tests/data/bundled_meshes.csv, written by tools/make_meshes.py). Peers: the kernel
// of the anti-holomorphic (Hodge–Laplace) matrix by a dense eigen-decomposition gives the same harmonic
// space; exact, co-exact and harmonic inputs (built with dense solves) are returned as themselves.
// Analytic: dθ on the planar annulus is harmonic (closed, co-closed, tangent to both boundary circles).
#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/apps/hodge.h"
#include "limsurf/apps/vector_field.h"
#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/sec/exterior_derivative.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

InnerProductOptions method(InnerProductMethod m, int level = 3) {
    InnerProductOptions o;
    o.method = m;
    o.level = level;
    return o;
}

struct Case {
    std::string name;
    SchemeKind scheme;
};

double inf(const Eigen::VectorXd& v) {
    return v.lpNorm<Eigen::Infinity>();
}

void expect_decomposition(const HodgeResult& r, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_LT(r.exact_coexact, 1e-12);
    EXPECT_LT(r.exact_harmonic, 1e-12);
    EXPECT_LT(r.coexact_harmonic, 1e-12);
    EXPECT_LT(r.sum_residual, 1e-14);
    EXPECT_LT(r.curl_of_exact, 1e-13);
    EXPECT_LT(r.divergence_of_coexact, 1e-11);
    EXPECT_LT(r.harmonic_curl, 1e-11);
    EXPECT_LT(r.harmonic_divergence, 1e-11);
    EXPECT_GT(r.exact_norm, 0.0);
    EXPECT_GT(r.coexact_norm, 0.0);
    // Pythagoras in M1: the parts are orthogonal, so their squared norms add up.
    const double sum =
        r.exact_norm * r.exact_norm + r.coexact_norm * r.coexact_norm + r.harmonic_norm * r.harmonic_norm;
    EXPECT_NEAR(sum, r.norm * r.norm, 1e-11 * r.norm * r.norm);
}

TEST(HodgeTest, PartsAndHarmonicDimensionOnEveryClosedMesh) {
    const Case cases[] = {{"genus2", SchemeKind::CatmullClark}, {"torus_4x5", SchemeKind::Loop},
                          {"torus_8x10", SchemeKind::Loop},     {"quad_torus", SchemeKind::CatmullClark},
                          {"tri_torus", SchemeKind::Loop},      {"sphere_quads", SchemeKind::CatmullClark},
                          {"sphere_tris", SchemeKind::Loop},    {"icosahedron", SchemeKind::Loop},
                          {"cube", SchemeKind::CatmullClark}};
    for (const Case& c : cases) {
        const test::BundledMesh& zoo = test::find_bundled(c.name);
        const BuildResult built = read_mesh(zoo.path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        for (const InnerProductMethod m : {InnerProductMethod::Dec, InnerProductMethod::Sec}) {
            HodgeOptions o;
            o.inner_products = method(m, 2);
            const HodgeResult r = hodge_decomposition(t, X, c.scheme, random_one_form(t, X, 7), o);
            const std::string what = c.name + " " + to_string(m);
            expect_decomposition(r, what);
            ASSERT_TRUE(r.basis.has_value());
            EXPECT_EQ(r.basis->dimension, 2 * zoo.genus) << what;  // Betti number from the mesh generator
            EXPECT_EQ(r.basis->expected, 2 * zoo.genus) << what;
            EXPECT_EQ(r.genus, zoo.genus) << what;
            if (zoo.genus > 0) {
                EXPECT_GT(r.basis->gap, 1e6) << what;
                EXPECT_GT(r.harmonic_norm, 1e-3 * r.norm) << what;
            } else {
                // Nothing harmonic on a sphere. 1e-7, not rounding: SEC's M1 of the cube (Catmull–Clark, six
                // faces) has an eigenvalue 1e-16 of its largest, so the split along that direction is
                // ill-determined (its M1-norm is what is measured here: tiny either way).
                EXPECT_LT(r.harmonic_norm, 1e-7 * r.norm) << what;
            }
        }
    }
}

TEST(HodgeTest, MeshesWithBoundaryUseNaturalConditions) {
    // b1 = 2g + b − 1: disk 0, annulus and open cylinder 1.
    const Case cases[] = {{"annulus", SchemeKind::CatmullClark},
                          {"cylinder_open", SchemeKind::CatmullClark},
                          {"disk_ev5_quads", SchemeKind::CatmullClark},
                          {"tri_grid", SchemeKind::Loop}};
    for (const Case& c : cases) {
        const test::BundledMesh& zoo = test::find_bundled(c.name);
        const BuildResult built = read_mesh(zoo.path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        for (const InnerProductMethod m : {InnerProductMethod::Dec, InnerProductMethod::SecSnap}) {
            HodgeOptions o;
            o.inner_products = method(m, 2);
            const HodgeResult r = hodge_decomposition(t, X, c.scheme, random_one_form(t, X, 3), o);
            expect_decomposition(r, c.name);
            EXPECT_EQ(r.basis->dimension, 2 * zoo.genus + zoo.num_boundary_loops - 1) << c.name;
            EXPECT_EQ(r.basis->dimension, r.basis->expected) << c.name;
        }
    }
}

TEST(HodgeTest, HarmonicBasisIsOrthonormalClosedAndCoClosed) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const HodgeDecomposer dec(t, control_inner_products(t, built.mesh.positions(), SchemeKind::CatmullClark,
                                                        method(InnerProductMethod::Sec, 2)));
    const HarmonicBasis b = harmonic_basis(dec, 11);
    ASSERT_EQ(b.dimension, 4);
    const SparseMatrix& M1 = dec.inner_products().M1;
    const Eigen::MatrixXd G = b.forms.transpose() * (M1 * b.forms);
    EXPECT_LT((G - Eigen::MatrixXd::Identity(4, 4)).lpNorm<Eigen::Infinity>(), 1e-12);
    EXPECT_LT((dec.d1() * b.forms).lpNorm<Eigen::Infinity>(), 1e-11);
    EXPECT_LT((SparseMatrix(dec.d0().transpose()) * (M1 * b.forms)).lpNorm<Eigen::Infinity>(), 1e-11);
    // Another seed spans the same space: the M1-projector B Bᵀ M1 is the same.
    const HarmonicBasis b2 = harmonic_basis(dec, 12345);
    const Eigen::MatrixXd P1 = b.forms * b.forms.transpose() * M1;
    const Eigen::MatrixXd P2 = b2.forms * b2.forms.transpose() * M1;
    EXPECT_LT((P1 - P2).lpNorm<Eigen::Infinity>(), 1e-10);
}

TEST(HodgeTest, HarmonicSpaceIsTheKernelOfTheHodgeLaplacian) {
    // Peer: a dense eigen-decomposition of L1 (SEC Eq. 4) finds a 2g-dimensional kernel, and the harmonic
    // part of a form is its M1-projection onto that kernel.
    const BuildResult built = read_mesh(test::find_bundled("torus_4x5").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const InnerProducts ip = control_inner_products(t, X, SchemeKind::Loop, method(InnerProductMethod::Sec, 2));
    const Eigen::MatrixXd L1 = Eigen::MatrixXd(anti_holomorphic_matrix(t, ip));
    const Eigen::MatrixXd M1 = Eigen::MatrixXd(ip.M1);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(L1, M1);
    const Eigen::VectorXd lambda = eig.eigenvalues();
    int kernel = 0;
    while (kernel < lambda.size() && std::abs(lambda[kernel]) < 1e-9 * lambda.maxCoeff()) {
        ++kernel;
    }
    ASSERT_EQ(kernel, 2);
    EXPECT_GT(lambda[2], 1e-4 * lambda.maxCoeff());            // a clear gap
    const Eigen::MatrixXd B = eig.eigenvectors().leftCols(2);  // M1-orthonormal
    const Eigen::VectorXd w = random_one_form(t, X, 5);
    const HodgeDecomposer dec(t, ip);
    const Eigen::VectorXd h = dec.decompose(w).harmonic;
    const Eigen::VectorXd projected = B * (B.transpose() * (M1 * w));
    EXPECT_LT(inf(h - projected), 1e-9 * inf(projected));
}

TEST(HodgeTest, GammaIsTheCoexactPartsPotentialAndTheTreeCotreeSplitEqualsTheSaddleSystem) {
    // Every surface: d1ᵀ γ = M1 δβ, mean(γ) = 0 when closed. δβ = w − dα − h (h on a harmonic basis from
    // tree–cotree generators) and γ from the dual graph's Laplacian, without the saddle-point system:
    // compared with that system [[M1, d1ᵀ], [d1, 0]] (face 0 pinned when closed) solved densely by
    // full-pivot LU, on closed surfaces of genus 0, 1, 2 and on surfaces with one and two boundary loops.
    const Case cases[] = {{"icosahedron", SchemeKind::Loop},           {"cube", SchemeKind::CatmullClark},
                          {"sphere_quads", SchemeKind::CatmullClark},  {"genus2", SchemeKind::CatmullClark},
                          {"annulus", SchemeKind::CatmullClark},       {"tri_torus", SchemeKind::Loop},
                          {"cylinder_open", SchemeKind::CatmullClark}, {"tri_grid", SchemeKind::Loop},
                          {"disk_ev5_quads", SchemeKind::CatmullClark}};
    for (const Case& c : cases) {
        const BuildResult built = read_mesh(test::find_bundled(c.name).path);
        const Topology& t = built.mesh.topology();
        const Points& X = built.mesh.positions();
        for (const InnerProductMethod m : {InnerProductMethod::Dec, InnerProductMethod::Sec}) {
            const std::string what = c.name + " " + to_string(m);
            const InnerProducts ip = control_inner_products(t, X, c.scheme, method(m, 2));
            const HodgeDecomposer dec(t, ip);
            const Eigen::VectorXd w = random_one_form(t, X, 11);
            const HodgeParts p = dec.decompose(w);
            const SparseMatrix d1 = exterior_derivative_1(t);
            const Eigen::VectorXd flux = ip.M1 * p.coexact;
            ASSERT_EQ(p.gamma.size(), t.num_faces()) << what;
            EXPECT_LT(inf(SparseMatrix(d1.transpose()) * p.gamma - flux), 1e-11 * inf(flux)) << what;
            if (t.is_closed()) {
                EXPECT_LT(std::abs(p.gamma.mean()), 1e-12 * inf(p.gamma)) << what;
            }
            const Index E = t.num_edges(), F = t.num_faces(), kept = t.is_closed() ? F - 1 : F;
            Eigen::MatrixXd S = Eigen::MatrixXd::Zero(E + kept, E + kept);
            S.topLeftCorner(E, E) = Eigen::MatrixXd(ip.M1);
            const Eigen::MatrixXd D1 = Eigen::MatrixXd(d1).bottomRows(kept);
            S.bottomLeftCorner(kept, E) = D1;
            S.topRightCorner(E, kept) = D1.transpose();
            Eigen::VectorXd rhs = Eigen::VectorXd::Zero(E + kept);
            rhs.tail(kept) = D1 * w;
            const Eigen::VectorXd x = S.fullPivLu().solve(rhs);
            // In M1's norm, to 1e-9 plus what M1's condition allows the dense solve: SEC's M1 of the
            // six-face cube has an eigenvalue 1e-16 of its largest (measured: 2.4e-8 apart there, 1.2 in
            // the max norm; below 1e-12 on the other meshes). The saddle system's equations themselves
            // hold to rounding: d1 δβ = d1 w (here) and d1ᵀ γ = M1 δβ (above).
            const Eigen::VectorXd eigenvalues =
                Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(ip.M1), Eigen::EigenvaluesOnly)
                    .eigenvalues();
            const double condition = eigenvalues.maxCoeff() / eigenvalues.minCoeff();
            const Eigen::VectorXd difference = p.coexact - x.head(E);
            EXPECT_LT(std::sqrt(difference.dot(ip.M1 * difference)),
                      (1e-9 + 1e-16 * condition) * std::sqrt(w.dot(ip.M1 * w)))
                << what << ", condition " << condition;
            EXPECT_LT(inf(d1 * Eigen::VectorXd(p.coexact - w)), 1e-12 * inf(d1 * w)) << what;
            // The harmonic part: w less the saddle system's co-exact part and dα, in M1's norm.
            const Eigen::VectorXd h = w - x.head(E) - p.exact;
            const Eigen::VectorXd h_difference = p.harmonic - h;
            EXPECT_LT(std::sqrt(h_difference.dot(ip.M1 * h_difference)),
                      (1e-9 + 1e-16 * condition) * std::sqrt(w.dot(ip.M1 * w)))
                << what;
        }
    }
}

TEST(HodgeTest, PureInputsAreReturnedAsThemselves) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const InnerProducts ip = control_inner_products(t, X, SchemeKind::CatmullClark, method(InnerProductMethod::Sec, 2));
    const HodgeDecomposer dec(t, ip);
    const SparseMatrix d0 = exterior_derivative_0(t);
    const SparseMatrix d1 = exterior_derivative_1(t);
    // Exact: d0 of the vertex heights.
    const Eigen::VectorXd exact = d0 * Eigen::VectorXd(X.col(2));
    const HodgeParts pe = dec.decompose(exact);
    EXPECT_LT(inf(pe.exact - exact), 1e-12 * inf(exact));
    EXPECT_LT(inf(pe.coexact) + inf(pe.harmonic), 1e-12 * inf(exact));
    // Co-exact: M1⁻¹ d1ᵀ g by a dense solve (independent of the saddle-point system).
    Eigen::VectorXd g = Eigen::VectorXd::LinSpaced(t.num_faces(), -1.0, 2.0);
    const Eigen::VectorXd coexact =
        Eigen::MatrixXd(ip.M1).ldlt().solve(Eigen::VectorXd(SparseMatrix(d1.transpose()) * g));
    const HodgeParts pc = dec.decompose(coexact);
    EXPECT_LT(inf(pc.coexact - coexact), 1e-11 * inf(coexact));
    EXPECT_LT(inf(pc.exact) + inf(pc.harmonic), 1e-11 * inf(coexact));
    // Harmonic: a basis form.
    const HarmonicBasis b = harmonic_basis(dec);
    const Eigen::VectorXd h = b.forms.col(0);
    const HodgeParts ph = dec.decompose(h);
    EXPECT_LT(inf(ph.harmonic - h), 1e-11 * inf(h));
}

TEST(HodgeTest, AngleFormOnThePlanarAnnulusIsHarmonic) {
    // dθ (θ the polar angle about the annulus's centre) is closed, co-closed and tangent to both
    // boundary circles: the harmonic form of the annulus. Its edge integrals are exact (θ differences).
    const BuildResult built = read_mesh(test::find_bundled("annulus").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    Eigen::VectorXd w(t.num_edges());
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ev = t.edge_vertices(e);
        const double a0 = std::atan2(X(ev[0], 1), X(ev[0], 0));
        const double a1 = std::atan2(X(ev[1], 1), X(ev[1], 0));
        w[e] = std::remainder(a1 - a0, 2.0 * M_PI);
    }
    double dec_error = 0.0;
    double sec_error = 0.0;
    for (const InnerProductMethod m : {InnerProductMethod::Dec, InnerProductMethod::Sec}) {
        HodgeOptions o;
        o.inner_products = method(m, 3);
        const HodgeResult r = hodge_decomposition(t, X, SchemeKind::CatmullClark, w, o);
        EXPECT_LT(r.coexact_norm, 1e-10 * r.norm);  // d1 w = 0 exactly: nothing co-exact
        (m == InnerProductMethod::Dec ? dec_error : sec_error) = r.exact_norm / r.norm;
        EXPECT_EQ(r.basis->dimension, 1);
    }
    // The discrete harmonic part is close to dθ: the exact remainder is a discretisation error, small.
    EXPECT_LT(dec_error, 0.1);
    EXPECT_LT(sec_error, 0.1);
}

TEST(HodgeTest, ReferenceOnTheSubdividedMesh) {
    // SEC §4.3, Fig. 8: SEC's parts are closer to the reference (DEC on the 3-times subdivided mesh) than DEC's.
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    const Eigen::VectorXd w = integrate_one_form(t, X, [](const Points& P) {
        Points V(P.rows(), 3);
        V.col(0) = -P.col(1);
        V.col(1) = P.col(0);
        V.col(2) = P.col(0).array().sin();
        return V;
    });
    HodgeOptions o;
    o.basis = false;
    o.reference_level = 3;
    o.inner_products = method(InnerProductMethod::Dec);
    const HodgeResult dec = hodge_decomposition(t, X, SchemeKind::CatmullClark, w, o);
    o.inner_products = method(InnerProductMethod::Sec, 3);
    const HodgeResult sec = hodge_decomposition(t, X, SchemeKind::CatmullClark, w, o);
    ASSERT_TRUE(dec.reference && sec.reference);
    EXPECT_EQ(dec.reference->edges, 6400);  // E → 2E + 4F per Catmull–Clark step from 100 edges, 50 quads
    EXPECT_LT(sec.reference->total, 0.5 * dec.reference->total);
}

TEST(HodgeTest, BadInput) {
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    const Topology& t = built.mesh.topology();
    const Points& X = built.mesh.positions();
    HodgeOptions o;
    o.inner_products = method(InnerProductMethod::Dec);
    EXPECT_THROW((void)hodge_decomposition(t, X, SchemeKind::CatmullClark, Eigen::VectorXd::Zero(3), o), InputError);
    Eigen::VectorXd w = Eigen::VectorXd::Ones(t.num_edges());
    w[5] = std::nan("");
    EXPECT_THROW((void)hodge_decomposition(t, X, SchemeKind::CatmullClark, w, o), InputError);
    // Two disjoint triangles: refused as disconnected.
    const Topology two = Topology::from_polygons(6, {{0, 1, 2}, {3, 4, 5}});
    Points P(6, 3);
    P << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0;
    EXPECT_THROW((void)hodge_decomposition(two, P, SchemeKind::Loop, Eigen::VectorXd::Zero(two.num_edges()), o),
                 InputError);
}

}  // namespace
}  // namespace limsurf
