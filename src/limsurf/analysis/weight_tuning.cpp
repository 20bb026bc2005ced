// IGA-tuned Catmull–Clark weights (weight_tuning.h, docs/tuning.md).
#include "limsurf/analysis/weight_tuning.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Dense>

#include "limsurf/core/error.h"
#include "limsurf/core/parallel.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/quadrature/rules.h"
#include "local_subdivision.h"

namespace limsurf {
namespace {

using Complex = std::complex<double>;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Two eigenvalues closer than this are one; constraints hold to it.
constexpr double eigen_tolerance = 1e-9;

/// A decomposition's k below this times the one-ring's scale (its size, or its distance from the
/// origin where larger) is rounding, not shape: planes in any position gave at most 6e-17 (6 000
/// random ones, classical and tuned weights; ShapeDecomposition.AFlatOneRingHasNoQuadraticPart
/// runs 200 of them), so 2e-15 leaves a margin of 30.
constexpr double quadratic_rounding_floor = 2e-15;

/// C_k = |1 + ω^k|² = 2 + 2 cos(2πk/n): how frequency k couples the edge and face neighbours.
double coupling(int valence, int k) {
    return 2.0 + 2.0 * std::cos(2.0 * std::numbers::pi * k / valence);
}

/// The frequency of the quadratic saddle, 2 mod n.
int saddle_frequency(int valence) {
    return 2 % valence;
}

/// At valence 3, frequency 2 is frequency −1: the saddle is the smaller eigenvalue of that block.
bool saddle_is_small_root(int valence) {
    const int k = saddle_frequency(valence);
    return k == 1 || k == valence - 1;
}

/// The roots of x² − s x + p, larger first; NaN when they are complex.
std::array<double, 2> real_roots(double s, double p) {
    const double disc = s * s - 4.0 * p;
    if (disc < 0.0) {
        return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    }
    const double r = std::sqrt(disc);
    return {(s + r) / 2.0, (s - r) / 2.0};
}

/// The one-ring's frequency-0 block on (centre, edge neighbours, face neighbours): rows the new
/// centre, edge point and face point (docs/tuning.md).
Eigen::Matrix3d block_zero(int n, const VertexRuleWeights& w) {
    const double a = 1.0 / (w.beta + 3.0);
    const double b = 1.0 / (w.gamma + 3.0);
    const double d = 1.0 / (w.alpha + 2.0 * n);
    Eigen::Matrix3d M;
    M << d * (w.alpha + n * b * w.gamma), d * n * (1.0 + 2.0 * b), d * n * b,  //
        a * w.beta + 2.0 * a * b * w.gamma, a + 4.0 * a * b, 2.0 * a * b,      //
        b * w.gamma, 2.0 * b, b;
    return M;
}

/// The two eigenvalues of block 0 besides 1: roots of x² − (tr − 1) x + det.
std::array<double, 2> block_zero_roots(int n, const VertexRuleWeights& w) {
    const Eigen::Matrix3d M = block_zero(n, w);
    return real_roots(M.trace() - 1.0, M.determinant());
}

/// The two eigenvalues of block k ≠ 0 (on edge and face neighbours): trace a + b + ab C_k, det ab.
std::array<double, 2> block_roots(int n, int k, const VertexRuleWeights& w) {
    const double a = 1.0 / (w.beta + 3.0);
    const double b = 1.0 / (w.gamma + 3.0);
    return real_roots(a + b + a * b * coupling(n, k), a * b);
}

void check_valence(int valence, bool allow_regular) {
    LIMSURF_CHECK(valence >= 3 && valence <= max_limit_size, InputError, "weight tuning: valence ", valence,
                  " is outside 3..", max_limit_size);
    LIMSURF_CHECK(allow_regular || valence != 4, InputError,
                  "weight tuning: valence 4 is the regular bicubic B-spline; tuning it would change every regular "
                  "patch (tune valences 3 and 5..",
                  max_limit_size, ")");
}

void check_weights(const VertexRuleWeights& w) {
    LIMSURF_CHECK(std::isfinite(w.alpha) && std::isfinite(w.beta) && std::isfinite(w.gamma) && w.alpha > 0.0 &&
                      w.beta >= 0.0 && w.gamma >= 0.0,
                  InputError, "weight tuning: weights must have alpha > 0 and beta, gamma >= 0, all finite, got ",
                  w.alpha, ", ", w.beta, ", ", w.gamma);
}

/// α such that λ² is an eigenvalue of block 0 (β, γ given): the characteristic polynomial at λ²
/// is affine in d = 1/(α + 2n) (only the centre's row depends on α), so d is one division.
double alpha_for(int n, double lambda, double beta, double gamma) {
    const double target = lambda * lambda;
    const auto residual = [&](double d) {
        // Block 0 with the centre row written through d (α = 1/d − 2n, so d α = 1 − 2 n d).
        const double a = 1.0 / (beta + 3.0);
        const double b = 1.0 / (gamma + 3.0);
        Eigen::Matrix3d M;
        M << 1.0 - 2.0 * n * d + d * n * b * gamma, d * n * (1.0 + 2.0 * b), d * n * b,  //
            a * beta + 2.0 * a * b * gamma, a + 4.0 * a * b, 2.0 * a * b,                //
            b * gamma, 2.0 * b, b;
        return target * target - (M.trace() - 1.0) * target + M.determinant();
    };
    const double f0 = residual(0.0);
    const double f1 = residual(1.0);
    if (f1 == f0) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const double d = -f0 / (f1 - f0);
    return d > 0.0 ? 1.0 / d - 2.0 * n : std::numeric_limits<double>::quiet_NaN();
}

/// A candidate is kept when its weights are admissible and its one-ring spectrum is what the
/// constraints ask: λ₁ = λ dominant, λ₃ = λ² the largest after it in block 0, and (Exact) λ₄ = λ².
bool admissible(const TunedVertex& v) {
    const VertexRuleWeights& w = v.weights;
    if (!(std::isfinite(w.alpha) && std::isfinite(w.beta) && std::isfinite(w.gamma) && w.alpha > 0.0 &&
          w.beta >= -1e-12 && w.gamma >= -1e-12)) {
        return false;
    }
    const int n = v.valence;
    const auto one = block_roots(n, 1, w);
    const auto zero = block_zero_roots(n, w);
    const auto two = block_roots(n, saddle_frequency(n), w);
    const double square = v.lambda * v.lambda;
    const bool ok = std::abs(one[0] - v.lambda) <= eigen_tolerance && std::isfinite(zero[0]) &&
                    std::abs(zero[0] - square) <= eigen_tolerance && zero[1] <= square + eigen_tolerance &&
                    std::isfinite(two[0]) && std::abs(two[1]) < v.lambda - eigen_tolerance &&
                    // at valence 3 block 2 is block 1's conjugate: its larger root is λ itself
                    (saddle_is_small_root(n) || std::abs(two[0]) < v.lambda - eigen_tolerance);
    if (!ok) {
        return false;
    }
    return v.constraint != TuningConstraint::Exact || std::abs(v.lambda4 - square) <= eigen_tolerance;
}

TunedVertex make_vertex(int n, double lambda, VertexRuleWeights w, TuningConstraint constraint) {
    // β = 0 ends the feasible range: its round-off below zero is zero.
    for (double* x : {&w.beta, &w.gamma}) {
        if (*x < 0.0 && *x > -1e-10) {
            *x = 0.0;
        }
    }
    TunedVertex v;
    v.valence = n;
    v.lambda = lambda;
    v.weights = w;
    v.constraint = constraint;
    const auto zero = block_zero_roots(n, w);
    const auto two = block_roots(n, saddle_frequency(n), w);
    v.lambda3 = zero[0];
    v.lambda4 = saddle_is_small_root(n) ? two[1] : two[0];
    return v;
}

/// (31): β = γ = 1/a − 3 with a = λ / (1 + √(λ C₁)) (the larger root of block 1 is λ).
std::optional<TunedVertex> relaxed_weights(int n, double lambda) {
    const double a = lambda / (1.0 + std::sqrt(lambda * coupling(n, 1)));
    const double beta = 1.0 / a - 3.0;
    VertexRuleWeights w{alpha_for(n, lambda, beta, beta), beta, beta};
    TunedVertex v = make_vertex(n, lambda, w, TuningConstraint::Relaxed);
    if (!admissible(v)) {
        return std::nullopt;
    }
    return v;
}

/// (30): with s = a + b, p = ab, "λ is a root of block 1" and "λ² is a root of block 2" are two
/// linear equations in (s, p); a, b are then the roots of x² − s x + p.
std::vector<TunedVertex> exact_weights(int n, double lambda) {
    const double c1 = coupling(n, 1);
    const double c2 = coupling(n, saddle_frequency(n));
    const double l2 = lambda * lambda;
    // p (1 − λ C₁) − λ s = −λ²;  p (1 − λ² C₂) − λ² s = −λ⁴.
    Eigen::Matrix2d A;
    A << 1.0 - lambda * c1, -lambda, 1.0 - l2 * c2, -l2;
    if (std::abs(A.determinant()) < 1e-14) {
        return {};
    }
    const Eigen::Vector2d ps = A.partialPivLu().solve(Eigen::Vector2d(-l2, -l2 * l2));
    const auto ab = real_roots(ps(1), ps(0));
    std::vector<TunedVertex> out;
    if (!std::isfinite(ab[0]) || ab[1] <= 0.0) {
        return out;
    }
    for (const auto& [a, b] : {std::pair{ab[0], ab[1]}, std::pair{ab[1], ab[0]}}) {
        const double beta = 1.0 / a - 3.0;
        const double gamma = 1.0 / b - 3.0;
        VertexRuleWeights w{alpha_for(n, lambda, beta, gamma), beta, gamma};
        TunedVertex v = make_vertex(n, lambda, w, TuningConstraint::Exact);
        if (admissible(v)) {
            out.push_back(v);
        }
        if (a == b) {
            break;
        }
    }
    return out;
}

// ---- the energy norm (28) over the characteristic map's 2-neighbourhood -------------------------

/// P_μ y: the spectral projection of block coordinates @p y onto the eigenvalue @p mu of @p B
/// (its kernel Q along the range of B − μ: Q (Lᴴ Q)⁻¹ Lᴴ y, L the left kernel).
Eigen::VectorXcd project_onto_eigenvalue(const Eigen::MatrixXcd& B, double mu, const Eigen::VectorXcd& y,
                                         int frequency) {
    const Index d = B.rows();
    const Eigen::MatrixXcd K = B - Complex(mu) * Eigen::MatrixXcd::Identity(d, d);
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(K, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    const double tolerance = 1e-9 * std::max(1.0, sigma(0));
    const Index m = static_cast<Index>((sigma.array() <= tolerance).count());
    LIMSURF_CHECK(m > 0, NumericalError, "weight tuning: ", mu, " is not an eigenvalue of the frequency-", frequency,
                  " block (smallest singular value ", sigma(d - 1), ")");
    const Eigen::MatrixXcd Q = svd.matrixV().rightCols(m);
    const Eigen::MatrixXcd L = svd.matrixU().rightCols(m);
    const Eigen::MatrixXcd G = L.adjoint() * Q;
    const Eigen::JacobiSVD<Eigen::MatrixXcd> check(G);
    LIMSURF_CHECK(check.singularValues()(m - 1) > 1e-8, NumericalError, "weight tuning: the eigenvalue ", mu,
                  " of the frequency-", frequency, " block is defective");
    return Q * G.partialPivLu().solve(L.adjoint() * y);
}

/// The eigenvector of the simple eigenvalue @p mu of @p B (the kernel of B − μ).
Eigen::VectorXcd eigenvector(const Eigen::MatrixXcd& B, double mu, int frequency) {
    const Index d = B.rows();
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(B - Complex(mu) * Eigen::MatrixXcd::Identity(d, d),
                                                 Eigen::ComputeFullV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    LIMSURF_CHECK(sigma(d - 1) <= 1e-9 * std::max(1.0, sigma(0)) && (d < 2 || sigma(d - 2) > 1e-6), NumericalError,
                  "weight tuning: ", mu, " is not a simple eigenvalue of the frequency-", frequency, " block");
    return svd.matrixV().col(d - 1);
}

/// The shapes' control values on the neighbourhood, and the characteristic map (ξ₁, ξ₂).
struct CharacteristicShapes {
    detail::LocalSubdivision local;
    Eigen::VectorXd xi1, xi2;  ///< r₁, r₂ (neighbourhood order), the first spoke along +ξ₁
    Eigen::VectorXd cup;       ///< r₃ ⟨l₃, u₃(r₁, r₂)⟩
    Eigen::VectorXd saddle;    ///< the frequency-±2 projection of u₄(r₁, r₂)
};

/// The real part of the neighbourhood vector of block coordinates @p y at frequency @p k, counting
/// the conjugate block n − k when it is another one.
Eigen::VectorXd real_field(const detail::Neighbourhood& nb, int k, const Eigen::VectorXcd& y) {
    const Eigen::VectorXcd x = detail::fourier_expand(nb, k, y);
    const bool self_conjugate = k == 0 || 2 * k == nb.sectors;
    return self_conjugate ? Eigen::VectorXd(x.real()) : Eigen::VectorXd(2.0 * x.real());
}

CharacteristicShapes characteristic_shapes(int n, const VertexRuleWeights& w, const TunedVertex& spectrum) {
    EigenRequest request;
    request.scheme = SchemeKind::CatmullClark;
    request.valence = n;
    if (n != 4) {
        request.weights = w;
    }
    CharacteristicShapes out;
    out.local = detail::local_subdivision(request, 3);
    const detail::Neighbourhood& nb = out.local.neighbourhood;
    // r₁ + i r₂: the frequency-1 eigenvector of λ, turned so that the first spoke's vertex (complex
    // vertex 1, lattice point (0, 1, 0)) lies on the positive ξ₁ axis.
    const Eigen::MatrixXcd B1 = detail::fourier_block(out.local.S, nb, 1);
    Eigen::VectorXcd z = detail::fourier_expand(nb, 1, eigenvector(B1, spectrum.lambda, 1));
    const auto spoke = std::find(nb.order.begin(), nb.order.end(), Index{1});
    LIMSURF_CHECK(spoke != nb.order.end(), NumericalError,
                  "weight tuning: the first spoke is not in the neighbourhood");
    const Complex first = z(static_cast<Index>(spoke - nb.order.begin()));
    LIMSURF_CHECK(std::abs(first) > 1e-12, NumericalError, "weight tuning: the characteristic map is degenerate");
    z /= first;  // the first spoke at ξ = (1, 0)
    out.xi1 = z.real();
    out.xi2 = z.imag();

    const Eigen::VectorXd u3 = (out.xi1.array().square() + out.xi2.array().square()).matrix();
    const Eigen::VectorXd u4 = (out.xi1.array().square() - out.xi2.array().square()).matrix();
    const Eigen::MatrixXcd B0 = detail::fourier_block(out.local.S, nb, 0);
    out.cup =
        real_field(nb, 0, project_onto_eigenvalue(B0, spectrum.lambda3, detail::fourier_coefficients(nb, 0, u3), 0));
    const int k = saddle_frequency(n);
    const Eigen::MatrixXcd B2 = detail::fourier_block(out.local.S, nb, k);
    out.saddle =
        real_field(nb, k, project_onto_eigenvalue(B2, spectrum.lambda4, detail::fourier_coefficients(nb, k, u4), k));
    return out;
}

/// Hessian in (ξ₁, ξ₂) of the scalar with limit rows @p f (value, ∂u, ∂v, ∂uu, ∂uv, ∂vv) over the
/// planar map with rows @p x, @p y: J⁻ᵀ (∇²_uv f − Σ_k ∂f/∂ξ_k ∇²_uv ξ_k) J⁻¹.
Eigen::Matrix2d xi_hessian(const Eigen::Matrix<double, 6, 1>& x, const Eigen::Matrix<double, 6, 1>& y,
                           const Eigen::Matrix<double, 6, 1>& f, const Eigen::Matrix2d& Jinv) {
    const auto hess = [](const Eigen::Matrix<double, 6, 1>& g) {
        Eigen::Matrix2d H;
        H << g(Duu), g(Duv), g(Duv), g(Dvv);
        return H;
    };
    const Eigen::Vector2d grad = Jinv.transpose() * Eigen::Vector2d(f(Du), f(Dv));
    const Eigen::Matrix2d H = hess(f) - grad(0) * hess(x) - grad(1) * hess(y);
    return Jinv.transpose() * H * Jinv;
}

/// (28)'s integrand for the Hessian @p H.
double plate_density(const Eigen::Matrix2d& H, double mu) {
    const double trace = H(0, 0) + H(1, 1);
    return trace * trace - 2.0 * (1.0 - mu) * (H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0));
}

/// A square of the unit square: its corner nearest the origin and its side.
struct Tile {
    Eigen::Vector2d origin;
    double size = 1.0;
};

/// The unit square in tiles, @p levels deep towards corner @p c (-1: none). Each tile but the one
/// at the corner is one regular patch of the limit surface, so a quadrature rule on it is exact
/// for the patch's polynomials and its points share the patch's control points
/// (LimitBasis::patch). The squares are quartered: with own β, γ the patches next to the vertex
/// are bicubic only on the quarters (the vertex stays in the support one level further).
std::vector<Tile> corner_tiles(int c, int levels) {
    static const std::array<Eigen::Vector2d, 4> corners{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0),
                                                        Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 1)};
    std::vector<Tile> out;
    const auto place = [&](const Eigen::Vector2d& origin, double size) {
        const double half = size / 2.0;
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) {
                out.push_back({origin + Eigen::Vector2d(i * half, j * half), half});
            }
        }
    };
    if (c < 0) {
        place({0, 0}, 1.0);
        return out;
    }
    const Eigen::Vector2d corner = corners[at(c)];
    double size = 1.0;
    for (int level = 0; level < levels; ++level) {
        const double half = size / 2.0;
        // The cell of side `size` at the corner, split in four: the three away from it integrated here.
        const Eigen::Vector2d cell = corner.cwiseProduct(Eigen::Vector2d(1.0 - size, 1.0 - size));
        for (int i = 0; i < 2; ++i) {
            for (int j = 0; j < 2; ++j) {
                const Eigen::Vector2d origin = cell + Eigen::Vector2d(i * half, j * half);
                const Eigen::Vector2d centre = origin + Eigen::Vector2d(half / 2, half / 2);
                if ((centre - corner).cwiseAbs().maxCoeff() > half) {
                    place(origin, half);
                }
            }
        }
        size = half;
    }
    place(corner.cwiseProduct(Eigen::Vector2d(1.0 - size, 1.0 - size)), size);
    return out;
}

/// What one thread reuses from point to point.
struct Scratch {
    LimitPatch patch;
    Eigen::MatrixXd data;
    Eigen::Matrix<double, 6, Eigen::Dynamic> rows;
    LimitWeights weights;
};

void check_options(const TuningOptions& o) {
    LIMSURF_CHECK(o.quadrature_points >= 1 && o.quadrature_points <= 10, InputError,
                  "weight tuning: quadrature points per direction must be 1..10, got ", o.quadrature_points);
    LIMSURF_CHECK(o.tile_levels >= 0 && o.tile_levels <= 20, InputError,
                  "weight tuning: tile levels must be 0..20, got ", o.tile_levels);
    LIMSURF_CHECK(o.poisson_ratio > -1.0 && o.poisson_ratio <= 0.5, InputError,
                  "weight tuning: Poisson's ratio must be in (-1, 0.5], got ", o.poisson_ratio);
    LIMSURF_CHECK(o.num_threads >= 0, InputError, "weight tuning: the thread count must be >= 0, not ", o.num_threads);
}

}  // namespace

const char* to_string(QuadraticShape shape) noexcept {
    return shape == QuadraticShape::Cup ? "cup" : "saddle";
}

QuadraticShape parse_quadratic_shape(const std::string& name) {
    if (name == "cup") {
        return QuadraticShape::Cup;
    }
    if (name == "saddle") {
        return QuadraticShape::Saddle;
    }
    throw InputError(detail::concat("unknown shape '", name, "' (cup, saddle)"));
}

const char* to_string(TuningConstraint constraint) noexcept {
    switch (constraint) {
    case TuningConstraint::Exact:
        return "exact";
    case TuningConstraint::Relaxed:
        return "relaxed";
    case TuningConstraint::None:
        break;
    }
    return "none";
}

TunedVertex one_ring_spectrum(int valence, const VertexRuleWeights& weights) {
    check_valence(valence, true);
    check_weights(weights);
    const auto one = block_roots(valence, 1, weights);
    TunedVertex v = make_vertex(valence, one[0], weights, TuningConstraint::None);
    LIMSURF_CHECK(std::isfinite(v.lambda) && std::isfinite(v.lambda3) && std::isfinite(v.lambda4), NumericalError,
                  "weight tuning: the weights ", weights.alpha, ", ", weights.beta, ", ", weights.gamma,
                  " give complex eigenvalues at valence ", valence);
    return v;
}

LambdaRange feasible_subdominant_range(int valence) {
    check_valence(valence, false);
    // (31) at β = 0 gives the largest λ; scan below it for the interval around Catmull–Clark's λ.
    const double top = (1.0 / 3.0) * (1.0 + std::sqrt(coupling(valence, 1)));  // a = 1/3 bound, λ ≤ top
    const int steps = 4000;
    const auto feasible = [&](double l) { return relaxed_weights(valence, l).has_value(); };
    const double cc = one_ring_spectrum(valence, catmull_clark_weights(valence)).lambda;
    LIMSURF_CHECK(feasible(cc), NumericalError, "weight tuning: Catmull–Clark's own lambda ", cc, " at valence ",
                  valence, " has no relaxed weights");
    const auto edge = [&](double inside, double outside) {
        for (int i = 0; i < 60; ++i) {
            const double mid = (inside + outside) / 2.0;
            (feasible(mid) ? inside : outside) = mid;
        }
        return inside;
    };
    LambdaRange r{cc, cc};
    const double step = std::min(top, 1.0) / steps;
    double l = cc;
    while (l - step > 0.0 && feasible(l - step)) {
        l -= step;
    }
    r.low = l - step > 0.0 ? edge(l, l - step) : l;
    l = cc;
    while (l + step < 1.0 && feasible(l + step)) {
        l += step;
    }
    r.high = edge(l, std::min(l + step, 1.0));
    return r;
}

std::vector<TunedVertex> weights_for_subdominant(int valence, double lambda) {
    const LambdaRange range = feasible_subdominant_range(valence);
    LIMSURF_CHECK(std::isfinite(lambda) && lambda >= range.low && lambda <= range.high, InputError,
                  "weight tuning: lambda ", lambda, " is outside the feasible range [", range.low, ", ", range.high,
                  "] at valence ", valence);
    std::vector<TunedVertex> out = exact_weights(valence, lambda);
    if (out.empty()) {
        const auto relaxed = relaxed_weights(valence, lambda);
        LIMSURF_CHECK(relaxed.has_value(), InputError, "weight tuning: no weights for lambda ", lambda, " at valence ",
                      valence);
        out.push_back(*relaxed);
    }
    return out;
}

ShapeErrors quadratic_shape_errors(int valence, const VertexRuleWeights& weights, const TuningOptions& options) {
    check_valence(valence, true);
    check_options(options);
    const VertexRuleWeights classical = catmull_clark_weights(valence);
    LIMSURF_CHECK(valence != 4 || (weights.alpha == classical.alpha && weights.beta == classical.beta &&
                                   weights.gamma == classical.gamma),
                  InputError, "weight tuning: valence 4 takes Catmull–Clark's own weights only");
    const TunedVertex spectrum = one_ring_spectrum(valence, weights);
    const CharacteristicShapes shapes = characteristic_shapes(valence, weights, spectrum);
    const detail::LocalSubdivision& local = shapes.local;
    const Topology& t = local.complex.topology;
    const Index centre = local.complex.centre[0];

    // Control values on the whole complex (its outermost ring is not read by the 2-neighbourhood).
    const detail::Neighbourhood& nb = local.neighbourhood;
    Eigen::VectorXd x = Eigen::VectorXd::Zero(t.num_vertices());
    Eigen::VectorXd y = x, cup = x, saddle = x;
    for (std::size_t i = 0; i < nb.order.size(); ++i) {
        const Index v = nb.order[i];
        const Index j = static_cast<Index>(i);
        x(v) = shapes.xi1(j);
        y(v) = shapes.xi2(j);
        cup(v) = shapes.cup(j);
        saddle(v) = shapes.saddle(j);
    }
    const LimitBasis basis(t, SchemeKind::CatmullClark, SchemeOptions{}, local.weights);
    const QuadratureRule rule = square_rule(2 * options.quadrature_points - 1);
    const double mu = options.poisson_ratio;
    Eigen::Matrix2d cup_exact, saddle_exact;
    cup_exact << 2, 0, 0, 2;
    saddle_exact << 2, 0, 0, -2;
    // The four fields side by side, contracted once per tile with its patch's control points.
    Eigen::MatrixXd fields(t.num_vertices(), 4);
    fields << x, y, cup, saddle;
    // (area, cup error, saddle error) of face f: (28) over its tiles; 0 outside the 2-neighbourhood.
    const auto face_integrals = [&](Index f, Scratch& scratch) -> std::array<double, 3> {
        std::array<double, 3> sum{0.0, 0.0, 0.0};
        const auto verts = t.face_vertices(f);
        if (std::any_of(verts.begin(), verts.end(),
                        [&](Index v) { return local.ring[at(v)] < 0 || local.ring[at(v)] > 2; })) {
            return sum;
        }
        const auto found = std::find(verts.begin(), verts.end(), centre);
        const int corner = found == verts.end() ? -1 : static_cast<int>(found - verts.begin());
        const Index p = basis.first_ptex_face(f);
        for (const Tile& tile : corner_tiles(corner, options.tile_levels)) {
            const Eigen::Vector2d middle = tile.origin + Eigen::Vector2d::Constant(tile.size / 2);
            const Eigen::Vector2d far = tile.origin + Eigen::Vector2d::Constant(tile.size);
            const bool one_patch =
                basis.patch_data(SurfacePoint{p, middle.x(), middle.y()}, fields, scratch.patch, scratch.data) &&
                scratch.patch.contains(tile.origin.x(), tile.origin.y(), 1e-9) &&
                scratch.patch.contains(far.x(), far.y(), 1e-9);
            bool patched = one_patch;  // scratch.patch and scratch.data hold the point's patch
            for (std::size_t q = 0; q < rule.weight.size(); ++q) {
                const Eigen::Vector2d uv = tile.origin + tile.size * Eigen::Vector2d(rule.u[q], rule.v[q]);
                if (!one_patch && !(patched && scratch.patch.contains(uv.x(), uv.y(), 0.0))) {
                    // The quarter at the vertex: its patches shrink towards it without end, so each
                    // point takes the patch that holds it, the previous point's where that holds it too.
                    patched = basis.patch_data(SurfacePoint{p, uv.x(), uv.y()}, fields, scratch.patch, scratch.data);
                }
                if (patched) {
                    scratch.patch.evaluate(scratch.data, uv.x(), uv.y(), scratch.rows);
                } else {  // within 2^-60 of the vertex: no patch
                    basis.evaluate(SurfacePoint{p, uv.x(), uv.y()}, scratch.weights, DerivativeOrder::Second);
                    scratch.rows.setZero(6, 4);
                    for (Index i = 0; i < scratch.weights.size(); ++i) {
                        scratch.rows += scratch.weights.w.col(i) * fields.row(scratch.weights.vertices[at(i)]);
                    }
                }
                const Eigen::Matrix<double, 6, 1> gx = scratch.rows.col(0), gy = scratch.rows.col(1);
                Eigen::Matrix2d J;
                J << gx(Du), gx(Dv), gy(Du), gy(Dv);
                const double det = J.determinant();
                LIMSURF_CHECK(std::abs(det) > 0.0, NumericalError,
                              "weight tuning: the characteristic map is singular at a quadrature point");
                const Eigen::Matrix2d Jinv = J.inverse();
                const double dA = rule.weight[q] * tile.size * tile.size * std::abs(det);
                sum[0] += dA;
                sum[1] += dA * plate_density(xi_hessian(gx, gy, scratch.rows.col(2), Jinv) - cup_exact, mu);
                sum[2] += dA * plate_density(xi_hessian(gx, gy, scratch.rows.col(3), Jinv) - saddle_exact, mu);
            }
        }
        return sum;
    };
    // The faces on several threads, their integrals summed in face order: the same for any count.
    std::vector<std::array<double, 3>> sums(static_cast<std::size_t>(t.num_faces()));
    run_ranges(t.num_faces(), thread_count(options.num_threads, t.num_faces(), 1), [&](Index begin, Index end) {
        Scratch scratch;
        for (Index f = begin; f < end; ++f) {
            sums[at(f)] = face_integrals(f, scratch);
        }
    });
    double area = 0.0, cup_error = 0.0, saddle_error = 0.0;
    for (const auto& [a, c, d] : sums) {
        area += a;
        cup_error += c;
        saddle_error += d;
    }
    ShapeErrors out;
    out.cup = std::sqrt(std::max(0.0, cup_error) / (area * plate_density(cup_exact, mu)));
    out.saddle = std::sqrt(std::max(0.0, saddle_error) / (area * plate_density(saddle_exact, mu)));
    return out;
}

TuningResult tune_weights(const TuningRequest& request) {
    check_options(request.options);
    const int n = request.valence;
    const LambdaRange feasible = feasible_subdominant_range(n);
    TuningResult out;
    out.request = request;
    out.classical = one_ring_spectrum(n, catmull_clark_weights(n));
    out.classical_errors = quadratic_shape_errors(n, out.classical.weights, request.options);
    double low = request.lambda_low, high = request.lambda_high;
    if (low == 0.0 && high == 0.0) {
        low = feasible.low;
        high = feasible.high;
    }
    LIMSURF_CHECK(std::isfinite(low) && std::isfinite(high) && low < high && low >= feasible.low &&
                      high <= feasible.high,
                  InputError, "weight tuning: the lambda interval [", low, ", ", high,
                  "] is not inside the feasible range [", feasible.low, ", ", feasible.high, "] at valence ", n);
    out.feasible = feasible;
    out.searched = {low, high};
    LIMSURF_CHECK(request.curve_samples >= 3 && request.curve_samples <= 10000, InputError,
                  "weight tuning: the curve needs 3..10000 samples, got ", request.curve_samples);
    LIMSURF_CHECK(request.lambda_tolerance > 0.0, InputError, "weight tuning: the lambda tolerance must be > 0");

    const bool cup = request.shape == QuadraticShape::Cup;
    const auto error_of = [&](const ShapeErrors& e) { return cup ? e.cup : e.saddle; };
    const auto other_of = [&](const ShapeErrors& e) { return cup ? e.saddle : e.cup; };
    const double other_limit = other_of(out.classical_errors);
    // The better candidate at λ for the requested shape.
    const auto sample_with = [&](double lambda, const TuningOptions& options) {
        TuningSample best;
        bool first = true;
        for (const TunedVertex& v : weights_for_subdominant(n, lambda)) {
            const ShapeErrors e = quadratic_shape_errors(n, v.weights, options);
            if (first || error_of(e) < error_of(best.errors)) {
                best = {v, e};
                first = false;
            }
        }
        return best;
    };
    const auto sample = [&](double lambda) { return sample_with(lambda, request.options); };
    // The curve's samples are independent: several λ at once, each evaluated on one thread, so that
    // the building of each λ's local complex and tables runs in parallel too (an evaluation's
    // numbers do not depend on its thread count). The golden-section search after it is
    // sequential (its evaluations share the threads over faces); the protection's bisections of
    // several crossings run at once.
    const int m = request.curve_samples;
    TuningOptions one_thread = request.options;
    one_thread.num_threads = 1;
    out.curve.resize(static_cast<std::size_t>(m));
    run_ranges(m, thread_count(request.options.num_threads, m, 1), [&](Index begin, Index end) {
        for (Index i = begin; i < end; ++i) {
            out.curve[at(i)] = sample_with(low + (high - low) * static_cast<double>(i) / (m - 1), one_thread);
        }
    });
    std::size_t best = 0;
    for (std::size_t i = 1; i < out.curve.size(); ++i) {
        if (error_of(out.curve[i].errors) < error_of(out.curve[best].errors)) {
            best = i;
        }
    }
    // Golden-section search on the grid intervals around the best sample.
    double a = out.curve[best > 0 ? best - 1 : 0].vertex.lambda;
    double b = out.curve[std::min(best + 1, out.curve.size() - 1)].vertex.lambda;
    TuningSample winner = out.curve[best];
    const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
    double c = b - ratio * (b - a), d = a + ratio * (b - a);
    TuningSample sc = sample(c), sd = sample(d);
    while (b - a > request.lambda_tolerance) {
        if (error_of(sc.errors) < error_of(sd.errors)) {
            b = d;
            d = c;
            sd = sc;
            c = b - ratio * (b - a);
            sc = sample(c);
        } else {
            a = c;
            c = d;
            sc = sd;
            d = a + ratio * (b - a);
            sd = sample(d);
        }
    }
    for (const TuningSample* s : {&sc, &sd}) {
        if (error_of(s->errors) < error_of(winner.errors)) {
            winner = *s;
        }
    }
    out.unconstrained = winner;
    if (request.protect_other_shape && other_of(winner.errors) > other_limit) {
        // The protected optimum lies where the other error meets Catmull–Clark's: bisect every grid
        // interval where it crosses, keep the crossing with the smallest error of the shape.
        std::vector<std::size_t> crossings;
        for (std::size_t i = 0; i + 1 < out.curve.size(); ++i) {
            if ((other_of(out.curve[i].errors) <= other_limit) != (other_of(out.curve[i + 1].errors) <= other_limit)) {
                crossings.push_back(i);
            }
        }
        const auto bisect = [&](std::size_t i, const TuningOptions& options) {
            const TuningSample& left = out.curve[i];
            const TuningSample& right = out.curve[i + 1];
            const bool left_ok = other_of(left.errors) <= other_limit;
            double ok = left_ok ? left.vertex.lambda : right.vertex.lambda;
            double bad = left_ok ? right.vertex.lambda : left.vertex.lambda;
            TuningSample kept = left_ok ? left : right;
            while (std::abs(bad - ok) > request.lambda_tolerance) {
                const double mid = (ok + bad) / 2.0;
                const TuningSample s = sample_with(mid, options);
                if (other_of(s.errors) <= other_limit) {
                    ok = mid;
                    kept = s;
                } else {
                    bad = mid;
                }
            }
            return kept;
        };
        // Several crossings are bisected at once, one thread each, as the curve's λ are; one alone
        // shares the threads over faces. Either way each evaluation gives the same numbers.
        std::vector<TuningSample> kept(crossings.size());
        const auto count = static_cast<Index>(crossings.size());
        if (count > 1) {
            run_ranges(count, thread_count(request.options.num_threads, count, 1), [&](Index begin, Index end) {
                for (Index k = begin; k < end; ++k) {
                    kept[at(k)] = bisect(crossings[at(k)], one_thread);
                }
            });
        } else if (count == 1) {
            kept[0] = bisect(crossings[0], request.options);
        }
        bool found = false;
        for (const TuningSample& s : kept) {  // in λ order, as the intervals were bisected before
            if (!found || error_of(s.errors) < error_of(winner.errors)) {
                winner = s;
                found = true;
            }
        }
        for (const TuningSample& s : out.curve) {  // a grid point inside the allowed set may be better
            if (other_of(s.errors) <= other_limit && (!found || error_of(s.errors) < error_of(winner.errors))) {
                winner = s;
                found = true;
            }
        }
        LIMSURF_CHECK(found, NumericalError, "weight tuning: no lambda in [", low, ", ", high, "] keeps the ",
                      cup ? "saddle" : "cup", " error at or below Catmull–Clark's at valence ", n);
        out.protection_binds = true;
    }
    out.tuned = winner.vertex;
    out.tuned_errors = winner.errors;
    return out;
}

std::vector<TuningSample> candidates_at(int valence, double lambda, const TuningOptions& options) {
    std::vector<TuningSample> out;
    for (const TunedVertex& v : weights_for_subdominant(valence, lambda)) {
        out.push_back({v, quadratic_shape_errors(valence, v.weights, options)});
    }
    return out;
}

TunedVertex tuned_vertex_weights(int valence, QuadraticShape shape, const TuningOptions& options) {
    TuningRequest request;
    request.valence = valence;
    request.shape = shape;
    request.options = options;
    const TuningResult result = tune_weights(request);
    const double lambda = std::round(result.tuned.lambda * 1000.0) / 1000.0;
    const auto error = [&](const TuningSample& s) {
        return shape == QuadraticShape::Cup ? s.errors.cup : s.errors.saddle;
    };
    const std::vector<TuningSample> candidates = candidates_at(valence, lambda, options);
    return std::min_element(candidates.begin(), candidates.end(),
                            [&](const TuningSample& a, const TuningSample& b) { return error(a) < error(b); })
        ->vertex;
}

double cup_saddle_ratio(double k3, double k4, double k5, double poisson_ratio) {
    const double saddle = k4 * k4 + k5 * k5;
    return saddle > 0.0 ? k3 * k3 / saddle * (1.0 + poisson_ratio) / (1.0 - poisson_ratio)
                        : std::numeric_limits<double>::infinity();
}

std::vector<ShapeDecomposition> decompose_shapes(const Topology& topology, const Points& P, const TunedWeights& weights,
                                                 int min_valence, double poisson_ratio) {
    LIMSURF_CHECK(P.rows() == topology.num_vertices() && P.allFinite(), InputError, "shape decomposition: expected ",
                  topology.num_vertices(), " finite rows of points, got ", P.rows());
    LIMSURF_CHECK(poisson_ratio > -1.0 && poisson_ratio < 1.0, InputError,
                  "shape decomposition: Poisson's ratio must be in (-1, 1), got ", poisson_ratio);
    std::vector<ShapeDecomposition> out;
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        const int n = static_cast<int>(topology.valence(v));
        if (n < std::max(3, min_valence) || n == 4 || n > max_limit_size || topology.is_boundary_vertex(v)) {
            continue;
        }
        const auto faces = topology.vertex_faces(v);
        if (std::any_of(faces.begin(), faces.end(), [&](Index f) { return topology.face_vertices(f).size() != 4; })) {
            continue;
        }
        const VertexRuleWeights w = weights.at(v, n);
        for (const Index f : faces) {
            for (const Index u : topology.face_vertices(f)) {
                const VertexRuleWeights other = weights.at(u, static_cast<int>(topology.valence(u)));
                LIMSURF_CHECK(u == v || (other.beta == 1.0 && other.gamma == 1.0), InputError,
                              "shape decomposition: the one-ring of vertex ", v, " holds vertex ", u,
                              " with its own weights (refine once: tuned vertices are then apart)");
            }
        }
        const TunedVertex s = one_ring_spectrum(n, w);
        // The one-ring in the closed form's order: centre, edge neighbours e_j, face neighbours f_j
        // (f_j opposite v in the face between e_j and e_{j+1}), walked as the vertex's edges go.
        const auto edges = topology.vertex_edges(v);
        std::vector<Index> e(at(n)), fv(at(n));
        for (int j = 0; j < n; ++j) {
            e[at(j)] = topology.other_vertex(edges[at(j)], v);
        }
        for (int j = 0; j < n; ++j) {
            const Index a = e[at(j)], b = e[at((j + 1) % n)];
            Index opposite = invalid_index;
            for (const Index f : faces) {
                const auto fvs = topology.face_vertices(f);
                if (std::find(fvs.begin(), fvs.end(), a) != fvs.end() &&
                    std::find(fvs.begin(), fvs.end(), b) != fvs.end()) {
                    for (const Index c : fvs) {
                        if (c != v && c != a && c != b) {
                            opposite = c;
                        }
                    }
                }
            }
            LIMSURF_CHECK(opposite != invalid_index, NumericalError, "shape decomposition: vertex ", v,
                          " has no face between its neighbours ", a, " and ", b);
            fv[at(j)] = opposite;
        }
        // Left eigenvectors of the one-ring blocks: frequency k ≠ 0 on (ê, f̂), frequency 0 on (c, ē, f̄).
        const double a = 1.0 / (w.beta + 3.0);
        const double b = 1.0 / (w.gamma + 3.0);
        const auto block = [&](int k) {
            const Complex omega = std::polar(1.0, 2.0 * std::numbers::pi * k / n);
            Eigen::Matrix2cd M;
            M << a + a * b * coupling(n, k), a * b * (1.0 + std::conj(omega)), b * (1.0 + omega), b;
            return M;
        };
        // l with lᴴ M = μ lᴴ (μ real): the eigenvector of Mᴴ.
        const auto left = [](const Eigen::MatrixXcd& M, double mu, int k) { return eigenvector(M.adjoint(), mu, k); };
        // Fourier coefficient of one-ring data g at frequency k: Σ_j g_j ω^{−jk} / n (per ring part).
        const auto coefficients = [&](const std::vector<Complex>& edge_values, const std::vector<Complex>& face_values,
                                      int k) {
            Eigen::Vector2cd c = Eigen::Vector2cd::Zero();
            for (int j = 0; j < n; ++j) {
                const Complex phase = std::polar(1.0, -2.0 * std::numbers::pi * j * k / n);
                c(0) += edge_values[at(j)] * phase / static_cast<double>(n);
                c(1) += face_values[at(j)] * phase / static_cast<double>(n);
            }
            return c;
        };
        // Characteristic map on the one-ring: z_e, z_f (frequency 1), the first spoke on +ξ₁.
        const Eigen::Matrix2cd B1 = block(1);
        Eigen::Vector2cd r1 = eigenvector(B1, s.lambda, 1);
        r1 /= r1(0);
        std::vector<Complex> ze(at(n)), zf(at(n));
        for (int j = 0; j < n; ++j) {
            const Complex phase = std::polar(1.0, 2.0 * std::numbers::pi * j / n);
            ze[at(j)] = r1(0) * phase;
            zf[at(j)] = r1(1) * phase;
        }
        // Tangents ⟨l₁, P⟩, ⟨l₂, P⟩ through the complex coefficient at frequency 1, and the normal (34).
        const Eigen::Vector2cd l1 = left(B1, s.lambda, 1);
        const auto ring_coefficients = [&](int column, int k) {
            std::vector<Complex> ev(at(n)), fvv(at(n));
            for (int j = 0; j < n; ++j) {
                ev[at(j)] = P(e[at(j)], column);
                fvv[at(j)] = P(fv[at(j)], column);
            }
            return coefficients(ev, fvv, k);
        };
        Eigen::Vector3cd t;
        for (int c = 0; c < 3; ++c) {
            t(c) = l1.dot(ring_coefficients(c, 1));  // l1ᴴ ĉ
        }
        // One-ring data a ξ₁ + b ξ₂ = Re(W z), W = a − i b, has frequency-1 coefficient W r₁ / 2
        // (z̄ sits at frequency −1), so l₁ᴴ ĉ = W (l₁ᴴ r₁) / 2.
        const Eigen::Vector3cd W = 2.0 * t / Complex(l1.dot(r1));
        const Eigen::Vector3d t1 = t.real(), t2 = t.imag();
        Eigen::Vector3d normal = t1.cross(t2);
        LIMSURF_CHECK(normal.norm() > 1e-14 * std::max(1.0, t1.norm() * t2.norm()), NumericalError,
                      "shape decomposition: the tangents at vertex ", v, " are parallel");
        normal.normalize();
        // Orient the normal by the faces' order around v (the one-ring's area vector): k₃ > 0 for a
        // cup that opens towards the side the faces face.
        Eigen::Vector3d area = Eigen::Vector3d::Zero();
        for (const Index f : faces) {
            const auto fvs = topology.face_vertices(f);
            for (std::size_t i = 0; i < fvs.size(); ++i) {
                area += Eigen::Vector3d(P.row(fvs[i])).cross(Eigen::Vector3d(P.row(fvs[(i + 1) % fvs.size()])));
            }
        }
        if (area.dot(normal) < 0.0) {
            normal = -normal;
        }
        // Out-of-plane control values g = (P − P_v) n and the model shapes on the one-ring. The left
        // eigenvectors of λ₃ and λ₄ annihilate constants, so measuring from P_v changes nothing but
        // the rounding: it no longer grows with the mesh's distance from the origin.
        std::vector<Complex> ge(at(n)), gf(at(n)), u3e(at(n)), u3f(at(n)), z2e(at(n)), z2f(at(n));
        // The scale of g's rounding: the one-ring's size, or its distance from the origin where that
        // is larger (the points themselves are rounded to it).
        double scale = P.row(v).stableNorm();  // stable: squares of coordinates near 1e300 overflow
        for (int j = 0; j < n; ++j) {
            const Eigen::RowVector3d de = P.row(e[at(j)]) - P.row(v), df = P.row(fv[at(j)]) - P.row(v);
            scale = std::max(
                {scale, de.stableNorm(), df.stableNorm(), P.row(e[at(j)]).stableNorm(), P.row(fv[at(j)]).stableNorm()});
            ge[at(j)] = de.dot(normal);
            gf[at(j)] = df.dot(normal);
            u3e[at(j)] = std::norm(ze[at(j)]);
            u3f[at(j)] = std::norm(zf[at(j)]);
            z2e[at(j)] = ze[at(j)] * ze[at(j)];
            z2f[at(j)] = zf[at(j)] * zf[at(j)];
        }
        const double gc = 0.0;
        // Cup: frequency 0 on (c, ē, f̄), the left eigenvector of λ₃.
        const Eigen::Matrix3cd B0 = block_zero(n, w).cast<Complex>();
        const Eigen::VectorXcd l3 = left(B0, s.lambda3, 0);
        const auto cup_coefficient = [&](Complex centre, const std::vector<Complex>& ev,
                                         const std::vector<Complex>& fvv) {
            const Eigen::Vector2cd c = coefficients(ev, fvv, 0);
            return Complex(l3.dot(Eigen::Vector3cd(centre, c(0), c(1))));
        };
        ShapeDecomposition d;
        d.vertex = v;
        d.valence = n;
        d.normal = normal;
        d.tangent1 = W.real();
        d.tangent2 = -W.imag();
        // The limit point: block 0's left eigenvector of 1, scaled so that a constant comes back.
        const Eigen::VectorXcd l0 = left(B0, 1.0, 0);
        for (int c = 0; c < 3; ++c) {
            const Eigen::Vector2cd mean = ring_coefficients(c, 0);
            d.position(c) =
                (l0.dot(Eigen::Vector3cd(P(v, c), mean(0), mean(1))) / l0.dot(Eigen::Vector3cd::Ones())).real();
        }
        d.k3 = (cup_coefficient(gc, ge, gf) / cup_coefficient(0.0, u3e, u3f)).real();
        // Saddle: the frequency-2 coefficient against that of z² = u₄ + i u₅, κ = 2 α_g / α_z²
        // (docs/tuning.md); g's saddle part is Re(κ z²) = Re κ u₄ − Im κ u₅.
        const int k = saddle_frequency(n);
        const Eigen::Matrix2cd B2 = block(k);
        const Eigen::Vector2cd l4 = left(B2, s.lambda4, k);
        const Complex alpha_g = l4.dot(coefficients(ge, gf, k));
        const Complex alpha_z = l4.dot(coefficients(z2e, z2f, k));
        const Complex kappa = (2 * k == n ? 1.0 : 2.0) * alpha_g / alpha_z;
        d.k4 = kappa.real();
        d.k5 = -kappa.imag();
        // What rounding alone makes of a plane is no shape: such a part is 0, and a vertex with
        // neither part has no ratio.
        const double floor = quadratic_rounding_floor * scale;
        if (std::abs(d.k3) <= floor) {
            d.k3 = 0.0;
        }
        if (std::hypot(d.k4, d.k5) <= floor) {
            d.k4 = d.k5 = 0.0;
        }
        d.has_quadratic_part = d.k3 != 0.0 || d.k4 != 0.0 || d.k5 != 0.0;
        d.ratio = d.has_quadratic_part ? cup_saddle_ratio(d.k3, d.k4, d.k5, poisson_ratio)
                                       : std::numeric_limits<double>::quiet_NaN();
        out.push_back(d);
    }
    return out;
}

}  // namespace limsurf
