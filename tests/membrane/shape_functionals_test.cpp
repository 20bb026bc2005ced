// Shape functionals (membrane/shape_functionals.h): gradients and Hessians against finite
// differences of the values and gradients, the identities of homogeneity and rigid motions, Gauss–Bonnet, the exact
// volume forms as a witness of the quadrature volume, round spheres against the analytic values (W = 4π, v = m = 1),
// the harmonic energy's bound E >= 2A, determinism across thread counts, and bad input.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/SparseLU>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/membrane/shape_functionals.h"
#include "limsurf/quadrature/integrals.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

constexpr double pi = std::numbers::pi;
constexpr std::array<ShapeFunctional, num_shape_functionals> all_functionals{
    ShapeFunctional::Area,     ShapeFunctional::Volume,   ShapeFunctional::MeanCurvature,
    ShapeFunctional::Willmore, ShapeFunctional::Gaussian, ShapeFunctional::Harmonic};

const char* name_of(ShapeFunctional f) {
    static constexpr std::array<const char*, num_shape_functionals> names{"area",     "volume",   "mean curvature",
                                                                          "Willmore", "Gaussian", "harmonic"};
    return names[static_cast<std::size_t>(f)];
}

ControlMesh bundled(const std::string& name) {
    return read_mesh(test::find_bundled(name).path).mesh;
}

/// The mesh's vertices pushed radially onto the unit sphere.
Points on_unit_sphere(const Points& X) {
    return X.rowwise().normalized();
}

/// A smooth, non-symmetric deformation so that no functional is at a critical point.
Points perturbed(const Points& X, unsigned seed, double amount) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> uniform(-amount, amount);
    Points out = X;
    for (Index v = 0; v < X.rows(); ++v) {
        out(v, 0) *= 1.3;
        out(v, 2) *= 0.8;
        for (int k = 0; k < 3; ++k) {
            out(v, k) += uniform(random);
        }
    }
    return out;
}

Points random_direction(Index rows, unsigned seed) {
    std::mt19937 random(seed);
    std::normal_distribution<double> normal;
    Points d(rows, 3);
    for (Index i = 0; i < d.size(); ++i) {
        d.data()[i] = normal(random);
    }
    return d;
}

double directional(const Points& gradient, const Points& direction) {
    return (gradient.array() * direction.array()).sum();
}

struct Case {
    std::string mesh;
    SchemeKind scheme;
};

class EveryScheme : public ::testing::TestWithParam<Case> {};

/// The degree k of homogeneity of each functional (F(sX) = s^k F(X)), in ShapeFunctional's order.
constexpr std::array<double, num_shape_functionals> homogeneity{2, 3, 1, 0, 0, 2};

/// A case's functionals (degree 6, 2 tile levels) and its mesh perturbed (seed 3) off every symmetry.
struct Perturbed {
    explicit Perturbed(const Case& c)
        : mesh(bundled(c.mesh)), basis(mesh.topology(), c.scheme),
          functionals(basis, ShapeOptions{.degree = 6, .subdivide_near_extraordinary = 2}),
          X(perturbed(mesh.positions(), 3, 0.05)) {}
    ControlMesh mesh;
    LimitBasis basis;
    ShapeFunctionals functionals;
    Points X;
};

// Central differences of the discrete functional agree with the gradient to 1e-6 relative, and the
// one-sided remainder |E(X + hD) − E(X) − h ∇E·D| falls like h² (the gradient is exact, not an
// approximation of the same order as the difference).
TEST_P(EveryScheme, GradientsMatchFiniteDifferences) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    const LimitBasis basis(mesh.topology(), c.scheme);
    ShapeOptions options;
    options.degree = 6;
    options.subdivide_near_extraordinary = 2;
    const ShapeFunctionals functionals(basis, options);
    const Points X = perturbed(mesh.positions(), 7, 0.05);
    const Points D = random_direction(X.rows(), 11);
    const ShapeValues at = functionals.evaluate_all(X);
    for (const ShapeFunctional f : all_functionals) {
        const double slope = directional(at.gradient_of(f), D);
        const double h = 1e-5;
        const double central =
            (functionals.evaluate(X + h * D).value(f) - functionals.evaluate(X - h * D).value(f)) / (2.0 * h);
        const double scale = std::max(std::abs(slope), at.gradient_of(f).norm() * D.norm() * 1e-3);
        EXPECT_NEAR(central, slope, 1e-6 * scale) << name_of(f) << " on " << c.mesh;
        const auto remainder = [&](double step) {
            return std::abs(functionals.evaluate(X + step * D).value(f) - at.value(f) - step * slope);
        };
        const double r1 = remainder(1e-3);
        const double r2 = remainder(0.5e-3);
        if (r1 > 1e-11 * std::abs(at.value(f)) + 1e-13) {
            EXPECT_NEAR(r1 / r2, 4.0, 0.4) << name_of(f) << " on " << c.mesh << ": remainder not O(h^2)";
        }
    }
}

// Scaling X by s multiplies A by s², V by s³, M by s, E by s² and leaves W and ∫K alone: Euler's
// identity ∇F·X = k F for a function homogeneous of degree k. Rigid motions change nothing: the
// gradient sums to zero (translations) and Σ X_v × ∇F_v = 0 (rotations).
TEST_P(EveryScheme, HomogeneityAndRigidMotions) {
    const Case c = GetParam();
    const Perturbed p(c);
    const ShapeFunctionals& functionals = p.functionals;
    const Points& X = p.X;
    const ShapeValues at = functionals.evaluate_all(X);
    for (const ShapeFunctional f : all_functionals) {
        const Points& g = at.gradient_of(f);
        const double k = homogeneity[static_cast<std::size_t>(f)];
        const double size = g.norm() * X.norm();
        EXPECT_NEAR(directional(g, X), k * at.value(f), 1e-10 * size) << name_of(f) << " on " << c.mesh;
        EXPECT_LT(g.colwise().sum().norm(), 1e-10 * g.norm() * std::sqrt(static_cast<double>(X.rows())))
            << name_of(f) << " on " << c.mesh;
        Eigen::Vector3d torque = Eigen::Vector3d::Zero();
        for (Index v = 0; v < X.rows(); ++v) {
            torque += Eigen::Vector3d(X.row(v)).cross(Eigen::Vector3d(g.row(v)));
        }
        EXPECT_LT(torque.norm(), 1e-10 * size) << name_of(f) << " on " << c.mesh;
    }
}

/// The Hessian of one functional alone.
SparseMatrix hessian_of(const ShapeFunctionals& functionals, const Points& X, ShapeFunctional f) {
    ShapeCoefficients coefficients{};
    coefficients[static_cast<std::size_t>(f)] = 1.0;
    return functionals.hessian(X, coefficients);
}

/// H · D for D (#V × 3) in Hessian order (3 v + c), as #V × 3.
Points apply(const SparseMatrix& H, const Points& D) {
    Eigen::VectorXd d(D.size());
    for (Index v = 0; v < D.rows(); ++v) {
        for (int c = 0; c < 3; ++c) {
            d[3 * v + c] = D(v, c);
        }
    }
    const Eigen::VectorXd y = H * d;
    Points out(D.rows(), 3);
    for (Index v = 0; v < D.rows(); ++v) {
        for (int c = 0; c < 3; ++c) {
            out(v, c) = y[3 * v + c];
        }
    }
    return out;
}

// The Hessian along a direction D against central differences of the exact gradients,
// (∇F(X + hD) − ∇F(X − hD)) / 2h: to 1e-6 of |H D| for every functional (measured 1e-11 to 3e-9,
// except where the quadrature's error shows: ∫K dA, whose Hessian vanishes up to it, 4e-8 to 1.2e-7,
// and the quadrature volume along a D that keeps the centroid, which the Hessian holds fixed,
// 1.3e-7 on C2g0). Σ_f c_f H_f is the Hessian of the combination; each is exactly symmetric.
TEST_P(EveryScheme, HessianMatchesFiniteDifferencesOfTheGradients) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    const LimitBasis basis(mesh.topology(), c.scheme);
    const ShapeFunctionals functionals(
        basis, ShapeOptions{.degree = 6, .subdivide_near_extraordinary = 2, .exact_volume = false});
    const Points X = perturbed(mesh.positions(), 7, 0.05);
    Points D = random_direction(X.rows(), 11);
    D.rowwise() -= D.colwise().mean();  // the centroid stays
    const double h = 1e-5;
    const ShapeValues plus = functionals.evaluate_all(X + h * D);
    const ShapeValues minus = functionals.evaluate_all(X - h * D);
    SparseMatrix combined(3 * X.rows(), 3 * X.rows());
    const ShapeCoefficients coefficients{0.5, -1.25, 2.0, 0.75, 0.0, 1.5};
    for (const ShapeFunctional f : all_functionals) {
        const SparseMatrix H = hessian_of(functionals, X, f);
        EXPECT_TRUE(Eigen::MatrixXd(H) == Eigen::MatrixXd(SparseMatrix(H.transpose()))) << "symmetric, " << name_of(f);
        const Points HD = apply(H, D);
        const Points central = (plus.gradient_of(f) - minus.gradient_of(f)) / (2.0 * h);
        EXPECT_LE((HD - central).norm(), 1e-6 * HD.norm()) << name_of(f) << " on " << c.mesh;
        combined += coefficients[static_cast<std::size_t>(f)] * H;
    }
    const SparseMatrix together = functionals.hessian(X, coefficients);
    // Each Hessian's differences round to ~1e-11 of its own terms, the combination's to those of its largest.
    EXPECT_LE((Eigen::MatrixXd(together - combined)).norm(), 1e-10 * Eigen::MatrixXd(together).norm());
}

// The filling overload (a solver's, once per iteration) gives the same bits as a new matrix, into
// a matrix of the right pattern (reused) or of any other shape (reshaped).
TEST(ShapeFunctionals, AFilledHessianEqualsANewOne) {
    const ControlMesh mesh = bundled("tetra_2");
    const LimitBasis basis(mesh.topology(), SchemeKind::C2g0);
    const ShapeFunctionals functionals(basis, ShapeOptions{.degree = 6, .subdivide_near_extraordinary = 2});
    const Points X = perturbed(mesh.positions(), 5, 0.05);
    const ShapeCoefficients first{1.0, 0.5, -0.25, 2.0, 0.0, 0.75};
    const ShapeCoefficients second{0.0, 0.0, 1.0, 1.0, 0.0, 3.0};
    const SparseMatrix fresh = functionals.hessian(X, second);
    SparseMatrix wrong = SparseMatrix(5, 7);
    wrong.insert(1, 2) = 3.0;
    SparseMatrix reused = functionals.hessian(X, first);
    const double* storage = reused.valuePtr();
    for (SparseMatrix* H : {&reused, &wrong}) {
        functionals.hessian(X, second, *H);
        ASSERT_EQ(H->nonZeros(), fresh.nonZeros());
        EXPECT_EQ(std::memcmp(H->innerIndexPtr(), fresh.innerIndexPtr(), sizeof(int) * fresh.nonZeros()), 0);
        EXPECT_EQ(std::memcmp(H->outerIndexPtr(), fresh.outerIndexPtr(), sizeof(int) * (fresh.rows() + 1)), 0);
        EXPECT_EQ(std::memcmp(H->valuePtr(), fresh.valuePtr(), sizeof(double) * fresh.nonZeros()), 0);
    }
    EXPECT_EQ(reused.valuePtr(), storage) << "the storage of a Hessian is reused";

    // The declared pattern (a solver's, before its first iteration) is the Hessian's, with zeros.
    const SparseMatrix pattern = functionals.hessian_pattern();
    ASSERT_EQ(pattern.nonZeros(), fresh.nonZeros());
    EXPECT_EQ(std::memcmp(pattern.innerIndexPtr(), fresh.innerIndexPtr(), sizeof(int) * fresh.nonZeros()), 0);
    EXPECT_EQ(std::memcmp(pattern.outerIndexPtr(), fresh.outerIndexPtr(), sizeof(int) * (fresh.rows() + 1)), 0);
    EXPECT_TRUE(
        std::all_of(pattern.valuePtr(), pattern.valuePtr() + pattern.nonZeros(), [](double x) { return x == 0.0; }));
}

// A matrix of the same size and entry count whose pattern differs (F_tetra,3's with its vertices in
// reverse order; F_tetra,2's pattern is full, so it has no other) is reshaped, not trusted: filled
// through the wrong pattern its values would land in other entries.
TEST(ShapeFunctionals, AHessianOfAnotherPatternIsReshaped) {
    const ControlMesh mesh = bundled("tetra_3");
    const LimitBasis basis(mesh.topology(), SchemeKind::C2g0);
    const ShapeFunctionals functionals(basis, ShapeOptions{.degree = 4, .subdivide_near_extraordinary = 0});
    const ShapeCoefficients coefficients{1.0, 0.5, -0.25, 2.0, 0.0, 0.75};
    const SparseMatrix fresh = functionals.hessian(mesh.positions(), coefficients);
    ASSERT_LT(fresh.nonZeros(), fresh.rows() * fresh.cols());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> reverse(fresh.rows());
    for (Eigen::Index i = 0; i < fresh.rows(); ++i) {
        reverse.indices()(i) = static_cast<int>(fresh.rows() - 3 * (i / 3) - 3 + i % 3);
    }
    SparseMatrix renumbered = reverse * fresh * reverse.inverse();
    renumbered.makeCompressed();
    ASSERT_EQ(renumbered.nonZeros(), fresh.nonZeros());
    ASSERT_NE(std::memcmp(renumbered.innerIndexPtr(), fresh.innerIndexPtr(), sizeof(int) * fresh.nonZeros()), 0);
    functionals.hessian(mesh.positions(), coefficients, renumbered);
    EXPECT_EQ(std::memcmp(renumbered.innerIndexPtr(), fresh.innerIndexPtr(), sizeof(int) * fresh.nonZeros()), 0);
    EXPECT_EQ(std::memcmp(renumbered.outerIndexPtr(), fresh.outerIndexPtr(), sizeof(int) * (fresh.rows() + 1)), 0);
    EXPECT_EQ(std::memcmp(renumbered.valuePtr(), fresh.valuePtr(), sizeof(double) * fresh.nonZeros()), 0);
}

// Euler's identity once more: ∇F homogeneous of degree k − 1 gives H X = (k − 1) ∇F (A, E: ∇F;
// M: 0; W, ∫K: −∇F). Rigid motions: H T = 0 for a translation T, and H (ω × X) = ω × ∇F per
// control point for a rotation (differentiate ∇F(R X) = R ∇F(X)). The volume is left out: its
// Hessian holds the centroid fixed.
TEST_P(EveryScheme, HessianIdentitiesOfHomogeneityAndRigidMotions) {
    const Case c = GetParam();
    const Perturbed p(c);
    const ShapeFunctionals& functionals = p.functionals;
    const Points& X = p.X;
    const ShapeValues at = functionals.evaluate_all(X);
    const Eigen::RowVector3d omega(0.3, -0.7, 0.4);
    Points turn(X.rows(), 3);
    for (Index v = 0; v < X.rows(); ++v) {
        turn.row(v) = omega.cross(X.row(v));
    }
    const Points translation = Points::Ones(X.rows(), 3) * 0.5;
    using enum ShapeFunctional;
    for (const ShapeFunctional f : all_functionals) {
        if (f == Volume) {
            continue;
        }
        const SparseMatrix H = hessian_of(functionals, X, f);
        const Points& g = at.gradient_of(f);
        // ∫K dA's Hessian vanishes up to the quadrature's error: its rounding is that of terms like W's.
        const double size = Eigen::MatrixXd(hessian_of(functionals, X, f == Gaussian ? Willmore : f)).norm() * X.norm();
        Points expected_turn(X.rows(), 3);
        for (Index v = 0; v < X.rows(); ++v) {
            expected_turn.row(v) = omega.cross(g.row(v));
        }
        const double k = homogeneity[static_cast<std::size_t>(f)];
        EXPECT_LE((apply(H, X) - (k - 1.0) * g).norm(), 1e-9 * size) << name_of(f) << " on " << c.mesh;
        EXPECT_LE((apply(H, turn) - expected_turn).norm(), 1e-9 * size) << name_of(f) << " on " << c.mesh;
        EXPECT_LE(apply(H, translation).norm(), 1e-9 * size) << name_of(f) << " on " << c.mesh;
    }
}

// Gauss–Bonnet: ∫K dA = 2π χ = 4π on a sphere for any shape, to quadrature accuracy; the
// harmonic energy is at least twice the area (trace g >= 2 √det g, equality when conformal).
TEST_P(EveryScheme, GaussBonnetAndHarmonicBound) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    const LimitBasis basis(mesh.topology(), c.scheme);
    const ShapeFunctionals functionals(basis);
    const Points X = perturbed(mesh.positions(), 5, 0.03);
    const ShapeValues at = functionals.evaluate(X);
    EXPECT_NEAR(at.gaussian, 2.0 * pi * static_cast<double>(mesh.topology().euler_characteristic()), 2e-3)
        << c.mesh << ": Gauss–Bonnet, 2πχ";
    EXPECT_GT(at.harmonic, 2.0 * at.area) << c.mesh;
    EXPECT_GE(at.willmore, 4.0 * pi) << c.mesh << ": Willmore's inequality W >= 4π";
}

// Bit-identical values, gradients and Hessians for 1, 2 and 3 threads, on the mesh refined until it has
// elements for three threads (parallel_ranges gives a thread 64 at least), so that vertices are
// shared between the threads' ranges.
TEST_P(EveryScheme, DeterministicForAnyThreadCount) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    Topology topology = mesh.topology();
    Points X0 = mesh.positions();
    while (topology.num_faces() < 3 * 64) {
        Level level = refine(topology, c.scheme);
        X0 = level.S0 * X0;
        topology = std::move(level.topology);
    }
    const LimitBasis basis(topology, c.scheme);
    const Points X = perturbed(X0, 13, 0.05);
    ShapeValues reference;
    SparseMatrix reference_hessian;
    const ShapeCoefficients coefficients{0.5, -1.25, 2.0, 0.75, 0.1, 1.5};
    for (const int threads : {1, 2, 3}) {
        const ShapeFunctionals functionals(basis, ShapeOptions{.num_threads = threads});
        const ShapeValues at = functionals.evaluate_all(X);
        const SparseMatrix hessian = functionals.hessian(X, coefficients);
        if (threads == 1) {
            reference = at;
            reference_hessian = hessian;
            continue;
        }
        ASSERT_EQ(hessian.nonZeros(), reference_hessian.nonZeros());
        EXPECT_EQ(std::memcmp(hessian.valuePtr(), reference_hessian.valuePtr(),
                              sizeof(double) * static_cast<std::size_t>(hessian.nonZeros())),
                  0)
            << "Hessian, " << threads << " threads";
        for (const ShapeFunctional f : all_functionals) {
            EXPECT_EQ(at.value(f), reference.value(f)) << name_of(f) << ", " << threads << " threads";
            EXPECT_TRUE(at.gradient_of(f) == reference.gradient_of(f)) << name_of(f) << ", " << threads << " threads";
        }
    }
}

// A value or gradient is the same bits whichever others are asked for (evaluate() computes only
// the local gradients asked for, and the positions at the samples only for the quadrature volume),
// with the exact volume forms and with the quadrature volume: every functional alone, what the
// Canham, Helfrich and (3.12) problems ask for, and the values alone.
TEST_P(EveryScheme, AFunctionalDoesNotDependOnWhichOthersAreAskedFor) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    const LimitBasis basis(mesh.topology(), c.scheme);
    const Points X = perturbed(mesh.positions(), 17, 0.05);
    using enum ShapeFunctional;
    std::vector<std::vector<ShapeFunctional>> subsets{
        {}, {Willmore, Area, Volume}, {Willmore, MeanCurvature, Area, Volume}, {Harmonic, Willmore, Area, Volume}};
    for (const ShapeFunctional f : all_functionals) {
        subsets.push_back({f});
    }
    for (const bool exact_volume : {true, false}) {
        const ShapeFunctionals functionals(basis, ShapeOptions{.exact_volume = exact_volume});
        const ShapeValues all = functionals.evaluate_all(X);
        for (const auto& subset : subsets) {
            const ShapeValues some = functionals.evaluate(X, subset);
            for (const ShapeFunctional f : all_functionals) {
                const bool asked = std::find(subset.begin(), subset.end(), f) != subset.end();
                SCOPED_TRACE(testing::Message() << name_of(f) << (asked ? " (asked)" : "") << " of " << subset.size()
                                                << ", exact volume " << exact_volume);
                EXPECT_EQ(std::bit_cast<std::uint64_t>(some.value(f)), std::bit_cast<std::uint64_t>(all.value(f)));
                if (asked) {
                    const Points& a = some.gradient_of(f);
                    const Points& b = all.gradient_of(f);
                    ASSERT_EQ(a.size(), b.size());
                    EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())), 0);
                } else {
                    EXPECT_EQ(some.gradient_of(f).size(), 0);
                }
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Meshes, EveryScheme,
                         ::testing::Values(Case{"tetra_2", SchemeKind::C2g0}, Case{"icosahedron", SchemeKind::Loop},
                                           Case{"cube", SchemeKind::CatmullClark},
                                           Case{"dodecahedron", SchemeKind::CatmullClark},
                                           Case{"quad_torus", SchemeKind::CatmullClark}),
                         [](const ::testing::TestParamInfo<Case>& param) { return param.param.mesh; });

// Regular Catmull–Clark elements go by sum factorisation (element_products.h's TensorElement): on
// the all-regular torus and on genus 2 refined once (regular faces next to valence-3 and -5
// corners), at the default degree (5 × 5 samples) and at 6 (4 × 4), with the exact and the
// quadrature volume (the latter adds the value rows), every value and gradient equals the dense
// kernels' to rounding. The elements factorised are exactly the faces whose corners all have
// valence 4 (counted here from the topology), and none under Loop.
TEST(ShapeFunctionals, SumFactorisationAgreesWithTheDenseKernels) {
    for (const auto& [name, levels] : {std::pair{"quad_torus", 0}, std::pair{"genus2", 1}}) {
        const ControlMesh mesh = bundled(name);
        Topology topology = mesh.topology();
        Points X0 = mesh.positions();
        for (int l = 0; l < levels; ++l) {
            Level level = refine(topology, SchemeKind::CatmullClark);
            X0 = level.S0 * X0;
            topology = std::move(level.topology);
        }
        Index regular_faces = 0;
        for (Index f = 0; f < topology.num_faces(); ++f) {
            const auto corners = topology.face_vertices(f);
            regular_faces +=
                std::all_of(corners.begin(), corners.end(), [&](Index v) { return topology.valence(v) == 4; }) ? 1 : 0;
        }
        ASSERT_GT(regular_faces, 0) << name;
        const LimitBasis basis(topology, SchemeKind::CatmullClark);
        const Points X = perturbed(X0, 5, 0.03);
        for (const int degree : {8, 6}) {
            for (const bool exact_volume : {true, false}) {
                SCOPED_TRACE(std::string(name) + " degree " + std::to_string(degree) +
                             (exact_volume ? " exact volume" : " quadrature volume"));
                ShapeOptions options{.degree = degree, .subdivide_near_extraordinary = 2, .exact_volume = exact_volume};
                const ShapeFunctionals factorised(basis, options);
                options.sum_factorisation = false;
                const ShapeFunctionals dense(basis, options);
                EXPECT_EQ(factorised.num_sum_factorised_elements(), regular_faces);
                EXPECT_EQ(dense.num_sum_factorised_elements(), 0);
                const ShapeValues a = factorised.evaluate_all(X);
                const ShapeValues b = dense.evaluate_all(X);
                for (const ShapeFunctional f : all_functionals) {
                    SCOPED_TRACE(name_of(f));
                    const double scale = std::max(std::abs(b.value(f)), 1.0);
                    EXPECT_NEAR(a.value(f), b.value(f), 1e-13 * scale);
                    const Points& ga = a.gradient_of(f);
                    const Points& gb = b.gradient_of(f);
                    ASSERT_EQ(ga.rows(), gb.rows());
                    EXPECT_LE((ga - gb).cwiseAbs().maxCoeff(), 1e-13 * std::max(gb.cwiseAbs().maxCoeff(), 1.0));
                }
            }
        }
    }
    const ControlMesh icosahedron = bundled("icosahedron");
    const LimitBasis loop(icosahedron.topology(), SchemeKind::Loop);
    EXPECT_EQ(ShapeFunctionals(loop).num_sum_factorised_elements(), 0);
}

// The quadrature volume 1/3 ∫ x·n dA against the exact trilinear forms (an independent formula);
// C2g0 has no such forms, its quadrature volume is checked through the identities above.
class WithExactVolume : public ::testing::TestWithParam<Case> {};

TEST_P(WithExactVolume, QuadratureVolumeAgreesWithExactForms) {
    const Case c = GetParam();
    const ControlMesh mesh = bundled(c.mesh);
    const LimitBasis basis(mesh.topology(), c.scheme);
    const ShapeFunctionals exact(basis, ShapeOptions{.degree = 10, .subdivide_near_extraordinary = 6});
    const ShapeFunctionals quadrature(
        basis, ShapeOptions{.degree = 10, .subdivide_near_extraordinary = 6, .exact_volume = false});
    ASSERT_TRUE(exact.volume_is_exact());
    ASSERT_FALSE(quadrature.volume_is_exact());
    const Points X = perturbed(mesh.positions(), 9, 0.05);
    const std::array<ShapeFunctional, 1> volume{ShapeFunctional::Volume};
    const ShapeValues e = exact.evaluate(X, volume);
    const ShapeValues q = quadrature.evaluate(X, volume);
    EXPECT_NEAR(q.volume, e.volume, 1e-7 * e.volume) << c.mesh;
    EXPECT_LT((q.gradient_of(ShapeFunctional::Volume) - e.gradient_of(ShapeFunctional::Volume)).norm(),
              1e-6 * e.gradient_of(ShapeFunctional::Volume).norm())
        << c.mesh;
}

INSTANTIATE_TEST_SUITE_P(Meshes, WithExactVolume,
                         ::testing::Values(Case{"icosahedron", SchemeKind::Loop},
                                           Case{"cube", SchemeKind::CatmullClark},
                                           Case{"dodecahedron", SchemeKind::CatmullClark}),
                         [](const ::testing::TestParamInfo<Case>& param) { return param.param.mesh; });

// Elements of bit-identical weights (every regular patch of one rotation) share one kernel of
// dense weights (shape_functionals.cpp): on subdivided meshes with most faces regular, deformed so
// that no two faces carry the same geometry, area, quadrature volume and their gradients equal the
// integrals of quadrature/integrals.h, which apply each sample's own weights (an independent path).
TEST(ShapeFunctionals, SharedKernelsAgreeWithPerSampleIntegrals) {
    for (const auto& [name, scheme] :
         {std::pair{"tetra_2", SchemeKind::C2g0}, std::pair{"icosahedron", SchemeKind::Loop},
          std::pair{"cube", SchemeKind::CatmullClark}}) {
        SCOPED_TRACE(name);
        const ControlMesh mesh = bundled(name);
        const Level level = refine(mesh.topology(), scheme);
        const LimitBasis basis(level.topology, scheme);
        Points X = perturbed(on_unit_sphere(level.S0 * mesh.positions()), 21, 0.04);
        X.rowwise() -= X.colwise().mean();  // the functionals' volume is about this centroid
        const ShapeOptions options{.degree = 6, .subdivide_near_extraordinary = 2, .exact_volume = false};
        const ShapeFunctionals functionals(basis, options);
        const LimitSampler sampler(basis, SamplerOptions{options.degree, options.subdivide_near_extraordinary, 0});
        ASSERT_EQ(functionals.num_samples(), sampler.num_samples());
        const std::array<ShapeFunctional, 2> wanted{ShapeFunctional::Area, ShapeFunctional::Volume};
        const ShapeValues at = functionals.evaluate(X, wanted);
        EXPECT_NEAR(at.area, area(sampler, X), 1e-13 * at.area);
        EXPECT_NEAR(at.volume, enclosed_volume(sampler, X), 1e-13 * at.area);
        const Points area_g = area_gradient(sampler, X);
        EXPECT_LT((at.gradient_of(ShapeFunctional::Area) - area_g).norm(), 1e-12 * area_g.norm());
        // The functionals' volume is about the control points' centroid, which moves with every
        // point: its gradient is integrals.h's less ∫ n dA / 3#V in every row. Translating X by t adds
        // t·∫ n dA / 3 to integrals.h's quadrature volume (n dA does not move), so the sum of its rows
        // is ∫ n dA / 3 and the expected gradient is integrals.h's less its row mean.
        Points volume_g = volume_gradient(sampler, X);
        const Eigen::RowVector3d normal_area_over_3 = volume_g.colwise().sum();
        volume_g.rowwise() -= normal_area_over_3 / static_cast<double>(X.rows());
        EXPECT_LT((at.gradient_of(ShapeFunctional::Volume) - volume_g).norm(), 1e-12 * volume_g.norm());
    }
}

/// W, v and m of the limit surface of a mesh whose vertices lie on the unit sphere.
struct SphereNumbers {
    double willmore_error = 0.0;  // |W − 4π| / 4π
    double reduced_volume_error = 0.0;
    double reduced_mean_error = 0.0;
    double gaussian_error = 0.0;
};

/// Control points whose limit points at the control vertices are @p X pushed onto the unit sphere
/// (P X = X/|X| with P the limit-position masks): a closer sphere than X itself.
Points interpolating_sphere(const LimitBasis& basis, const Points& X) {
    const SparseMatrix P = basis.vertex_limit_matrix();
    const Eigen::SparseMatrix<double> column_major = P;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(column_major);
    const Points target = on_unit_sphere(X);
    Points out(X.rows(), 3);
    for (int k = 0; k < 3; ++k) {
        out.col(k) = lu.solve(target.col(k));
    }
    return out;
}

SphereNumbers sphere_numbers(const Topology& topology, const Points& X, SchemeKind scheme) {
    const LimitBasis basis(topology, scheme);
    const ShapeFunctionals functionals(basis);
    // C2g0's limit masks are too wide for interpolation to help (its interpolant wiggles): the control
    // points themselves go onto the sphere.
    const Points sphere = scheme == SchemeKind::C2g0 ? on_unit_sphere(X) : interpolating_sphere(basis, X);
    const ShapeValues at = functionals.evaluate(sphere);
    return {std::abs(at.willmore - 4.0 * pi) / (4.0 * pi), std::abs(at.reduced_volume() - 1.0),
            std::abs(at.reduced_mean_curvature() - 1.0), std::abs(at.gaussian - 4.0 * pi)};
}

// c2g0 §3 / issue: on round spheres W = 4π, v = 1, m = 1. No subdivision surface is a round
// sphere, but the limit surfaces of F_tetra,j (C2g0, vertices on the unit sphere) and of Loop's
// subdivided icosahedra (limit points of the vertices on the sphere) approach one as j grows:
// every refinement must shrink each error by at least 1.5 (measured: C2g0 W 0.16, 0.081, 0.033,
// 0.016 — first order, the flat spots of projected control meshes at the valence-3 vertices; Loop
// W 4.1e-3, 3.1e-4, 3.2e-5, 1.7e-5), and Gauss–Bonnet holds at every level.
TEST(ShapeFunctionals, RoundSphereLimitsConvergeToAnalyticValues) {
    std::vector<SphereNumbers> c2g0;
    for (const char* name : {"tetra_1", "tetra_2", "tetra_3", "tetra_4"}) {
        const ControlMesh mesh = bundled(name);
        c2g0.push_back(sphere_numbers(mesh.topology(), mesh.positions(), SchemeKind::C2g0));
    }
    std::vector<SphereNumbers> loop;
    Topology topology = bundled("icosahedron").topology();
    Points X = bundled("icosahedron").positions();
    for (int j = 0; j < 4; ++j) {
        loop.push_back(sphere_numbers(topology, X, SchemeKind::Loop));
        Level level = refine(topology, SchemeKind::Loop);
        X = on_unit_sphere(level.S0 * X);
        topology = std::move(level.topology);
    }
    for (const auto* series : {&c2g0, &loop}) {
        for (std::size_t j = 0; j < series->size(); ++j) {
            const SphereNumbers& n = (*series)[j];
            EXPECT_LT(n.gaussian_error, 2e-4) << "Gauss-Bonnet at level " << j;
            if (j == 0) {
                continue;
            }
            const SphereNumbers& coarser = (*series)[j - 1];
            EXPECT_LT(n.willmore_error, coarser.willmore_error / 1.5) << "level " << j;
            EXPECT_LT(n.reduced_volume_error, coarser.reduced_volume_error / 1.5) << "level " << j;
            EXPECT_LT(n.reduced_mean_error, coarser.reduced_mean_error / 1.5) << "level " << j;
        }
    }
    EXPECT_LT(c2g0.back().willmore_error, 0.02);
    EXPECT_LT(c2g0.back().reduced_volume_error, 1e-3);
    EXPECT_LT(loop.back().willmore_error, 1e-4);
    EXPECT_LT(loop.back().reduced_volume_error, 1e-6);
}

TEST(ShapeFunctionals, HelfrichIsWillmoreShiftedBySpontaneousCurvature) {
    const ControlMesh mesh = bundled("tetra_2");
    const LimitBasis basis(mesh.topology(), SchemeKind::C2g0);
    const ShapeFunctionals functionals(basis, ShapeOptions{.degree = 6, .subdivide_near_extraordinary = 2});
    const Points X = perturbed(mesh.positions(), 1, 0.05);
    const ShapeValues at = functionals.evaluate_all(X);
    const double h0 = 0.7;
    const Points D = random_direction(X.rows(), 2);
    const double h = 1e-5;
    const double central =
        (functionals.evaluate(X + h * D).helfrich(h0) - functionals.evaluate(X - h * D).helfrich(h0)) / (2.0 * h);
    EXPECT_NEAR(central, directional(at.helfrich_gradient(h0), D), 1e-6 * at.helfrich_gradient(h0).norm() * D.norm());
    EXPECT_DOUBLE_EQ(at.helfrich(0.0), at.willmore);
    const ShapeValues without = functionals.evaluate(X);
    EXPECT_THROW((void)without.helfrich_gradient(h0), InputError);
}

TEST(ShapeFunctionals, RefusesWhatItCannotMeasure) {
    const ControlMesh open = bundled("cylinder_open");
    const LimitBasis open_basis(open.topology(), SchemeKind::CatmullClark);
    EXPECT_THROW(ShapeFunctionals{open_basis}, InputError);
    const ControlMesh cube = bundled("cube");
    const LimitBasis doo_sabin(cube.topology(), SchemeKind::DooSabin);
    EXPECT_THROW(ShapeFunctionals{doo_sabin}, UnsupportedError);
    const LimitBasis basis(cube.topology(), SchemeKind::CatmullClark);
    const ShapeFunctionals functionals(basis);
    EXPECT_THROW((void)functionals.evaluate(Points::Zero(3, 3)), InputError);
    Points X = cube.positions();
    X(2, 1) = std::nan("");
    EXPECT_THROW((void)functionals.evaluate(X), InputError);
    // Every control point in one place: no tangent plane anywhere.
    EXPECT_THROW((void)functionals.evaluate(Points::Zero(cube.positions().rows(), 3)), NumericalError);
    // The Hessian refuses alike, and a coefficient that is not finite.
    const ShapeCoefficients willmore{0, 0, 0, 1, 0, 0};
    EXPECT_THROW((void)functionals.hessian(Points::Zero(3, 3), willmore), InputError);
    EXPECT_THROW((void)functionals.hessian(X, willmore), InputError);
    EXPECT_THROW((void)functionals.hessian(Points::Zero(cube.positions().rows(), 3), willmore), NumericalError);
    EXPECT_THROW((void)functionals.hessian(cube.positions(), ShapeCoefficients{0, 0, 0, std::nan(""), 0, 0}),
                 InputError);
}

}  // namespace
}  // namespace limsurf
