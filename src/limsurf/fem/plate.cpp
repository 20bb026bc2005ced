// Kirchhoff–Love plates with the limit basis (plate.h, docs/fem.md "Plates").
#include "limsurf/fem/plate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "boundary_samples.h"
#include "element_assembly.h"
#include "limsurf/core/error.h"
#include "limsurf/detail/sparse_cholesky.h"
#include "material.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

void check_material(const PlateMaterial& m) {
    detail::check_thin_material("plate", m.E, m.nu, m.thickness);
}

void check_planar(const Points& X) {
    const double extent = (X.colwise().maxCoeff() - X.colwise().minCoeff()).head<2>().maxCoeff();
    LIMSURF_CHECK(extent > 0.0 && X.col(2).cwiseAbs().maxCoeff() <= 1e-12 * extent, InputError,
                  "plate: the control mesh must lie in the plane z = 0");
}

/// Derivatives in x, y of the basis functions at one point of the plate.
struct PlanarDerivatives {
    Eigen::Matrix<double, 2, Eigen::Dynamic> gradient;   ///< (φ_x, φ_y), 2 × k
    Eigen::Matrix<double, 3, Eigen::Dynamic> curvature;  ///< (φ_xx, φ_yy, 2 φ_xy), 3 × k
    Eigen::Matrix2d J;                                   ///< columns ∂/∂u, ∂/∂v of (x, y)
};

/// The basis functions with ptex weights @p W (6 × k) where the map has derivatives @p D (rows as
/// LimitWeights): ∇φ = J⁻ᵀ ∇_uv φ and ∇²φ = J⁻ᵀ (∇²_uv φ − Σ_c ∂φ/∂x_c ∇²_uv x_c) J⁻¹.
PlanarDerivatives planar_derivatives(const Eigen::Matrix<double, 6, 3>& D,
                                     const Eigen::Ref<const Eigen::Matrix<double, 6, Eigen::Dynamic>>& W,
                                     Index ptex_face) {
    PlanarDerivatives out;
    Eigen::Matrix2d& J = out.J;
    J << D(Du, 0), D(Dv, 0), D(Du, 1), D(Dv, 1);
    const double det = J.determinant();
    LIMSURF_CHECK(std::isfinite(det) && std::abs(det) > 1e-14 * J.squaredNorm(), NumericalError,
                  "plate: the map of the plate is degenerate at a quadrature point of ptex face ", ptex_face);
    const Eigen::Matrix2d Jinv = J.inverse();
    const Index k = W.cols();
    out.gradient.resize(2, k);
    out.curvature.resize(3, k);
    for (Index j = 0; j < k; ++j) {
        const Eigen::Vector2d grad = Jinv.transpose() * Eigen::Vector2d(W(Du, j), W(Dv, j));
        out.gradient.col(j) = grad;
        Eigen::Matrix2d H;
        H << W(Duu, j), W(Duv, j), W(Duv, j), W(Dvv, j);
        for (int c = 0; c < 2; ++c) {  // minus ∂φ/∂x_c times the map's second derivatives
            Eigen::Matrix2d Hx;
            Hx << D(Duu, c), D(Duv, c), D(Duv, c), D(Dvv, c);
            H -= grad(c) * Hx;
        }
        const Eigen::Matrix2d Hxy = Jinv.transpose() * H * Jinv;
        out.curvature(0, j) = Hxy(0, 0);
        out.curvature(1, j) = Hxy(1, 1);
        out.curvature(2, j) = 2.0 * Hxy(0, 1);
    }
    return out;
}

void check_points(const Points& X, Index num_vertices) {
    LIMSURF_CHECK(X.rows() == num_vertices && X.cols() == 3, InputError, "plate: X has ", X.rows(), " rows and ",
                  X.cols(), " columns, the control mesh ", num_vertices, " vertices");
    check_planar(X);
}

/// The Nitsche terms at one boundary sample, added to @p entries over the vertices of @p W.
void add_clamping_sample(const detail::BoundarySample& b, const LimitWeights& W, const Points& X,
                         const PlateMaterial& material, double penalty, std::vector<Eigen::Triplet<double>>& entries) {
    const Eigen::Matrix<double, 6, 3> D = W.apply(X);
    const PlanarDerivatives d = planar_derivatives(D, W.w, b.point.face);
    const Eigen::Vector2d along = d.J.col(b.along_u ? 0 : 1);
    const Eigen::Vector2d across = b.inward * d.J.col(b.along_u ? 1 : 0);  // points into the face
    Eigen::Vector2d n(along.y(), -along.x());
    n /= along.norm();
    if (n.dot(across) > 0.0) {  // outward whatever the orientation of the control mesh
        n = -n;
    }
    const double ds = b.weight * along.norm();
    const double h = std::abs(n.dot(across));  // = |det J| / |∂x/∂t|, the extent across the edge
    const double Dr = material.bending_rigidity();
    const Eigen::VectorXd dn = d.gradient.transpose() * n;
    const Eigen::Vector3d moment_row =
        Dr * Eigen::Vector3d((1.0 - material.nu) * n.x() * n.x() + material.nu,
                             (1.0 - material.nu) * n.y() * n.y() + material.nu, (1.0 - material.nu) * n.x() * n.y());
    const Eigen::VectorXd Mnn = d.curvature.transpose() * moment_row;  // D[(1−ν) n·∇²φ·n + ν Δφ]
    const double c = penalty * Dr / h;
    for (Index i = 0; i < W.size(); ++i) {
        for (Index j = 0; j < W.size(); ++j) {
            const double value = ds * (c * dn(i) * dn(j) - (Mnn(i) * dn(j) + dn(i) * Mnn(j)));
            entries.emplace_back(W.vertices[at(i)], W.vertices[at(j)], value);
        }
    }
}

/// The sampler's first sample evaluated by @p basis: a sampler of another basis (scheme, options,
/// topology) is caught here, before the edge integrals mix two surfaces.
void check_sampler_matches(const LimitBasis& basis, const LimitSampler& sampler) {
    LIMSURF_CHECK(basis.topology().num_vertices() == sampler.num_vertices() && basis.domain() == sampler.domain(),
                  InputError, "plate: the sampler was built on another basis");
    if (sampler.num_samples() == 0) {
        return;
    }
    const LimitWeights W = basis.evaluate(sampler.point(0), DerivativeOrder::Second);
    const auto vertices = sampler.vertices(0);
    const auto weights = sampler.limit_weights(0);
    bool same = W.size() == static_cast<Index>(vertices.size());
    for (Index j = 0; same && j < W.size(); ++j) {
        same = W.vertices[at(j)] == vertices[at(j)] && (W.w.col(j) - weights.col(j)).cwiseAbs().maxCoeff() <=
                                                           1e-9 * (1.0 + weights.col(j).cwiseAbs().maxCoeff());
    }
    LIMSURF_CHECK(same, InputError, "plate: the sampler was built on another basis");
}

/// The reduced solve: K (+ the Nitsche terms @p clamping when not empty) with w = 0 on the boundary
/// control values, and on their neighbours for Clamped.
PlateSolution solve_with_supports(const Topology& topology, const LimitSampler& sampler, const Points& X,
                                  const PlateMaterial& material, PlateSupport support, const Eigen::VectorXd& b,
                                  const SparseMatrix& clamping) {
    LIMSURF_CHECK(topology.num_vertices() == sampler.num_vertices(), InputError, "plate: the topology has ",
                  topology.num_vertices(), " vertices, the sampler ", sampler.num_vertices());
    SparseMatrix K = assemble_plate_bending(sampler, X, material);
    if (clamping.size() > 0) {
        K += clamping;
    }
    const Index V = topology.num_vertices();
    std::vector<bool> fixed(at(V), false);
    for (Index v = 0; v < V; ++v) {
        if (!topology.is_boundary_vertex(v)) {
            continue;
        }
        fixed[at(v)] = true;
        if (support == PlateSupport::Clamped) {
            // ∂w/∂n on the boundary reads the boundary row and the next one: with w = 0 there, ∂w/∂n = 0
            // on the whole edge is the next row zero.
            for (const Index e : topology.vertex_edges(v)) {
                fixed[at(topology.other_vertex(e, v))] = true;
            }
        }
    }
    PlateSolution out;
    out.solver = detail::SparseCholesky::name();
    auto [w, residual] =
        detail::solve_with_fixed_values(K, b, fixed, Eigen::VectorXd::Zero(V), "the plate's bending stiffness");
    LIMSURF_CHECK(w.allFinite(), NumericalError, "plate: the deflection is not finite");
    out.w = std::move(w);
    out.residual = residual;
    out.energy = b.dot(out.w);
    return out;
}

}  // namespace

SparseMatrix assemble_plate_bending(const LimitSampler& sampler, const Points& X, const PlateMaterial& material) {
    check_material(material);
    check_points(X, sampler.num_vertices());
    const double D = material.bending_rigidity();
    const double nu = material.nu;
    Eigen::Matrix3d C;
    C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
    C *= D;
    return detail::assemble_elements<1>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 1>& Ke) {
            const PlanarDerivatives d =
                planar_derivatives(sampler.evaluate(X, s), sampler.limit_weights(s), sampler.point(s).face);
            const double dA = std::abs(d.J.determinant());
            const Eigen::MatrixXd k = (sampler.weight(s) * dA) * d.curvature.transpose() * C * d.curvature;
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    Ke[0](local[i], local[j]) += k(static_cast<Index>(i), static_cast<Index>(j));
                }
            }
        })[0];
}

SparseMatrix assemble_plate_clamping(const LimitBasis& basis, const Points& X, const PlateMaterial& material,
                                     const SamplerOptions& rule, double penalty) {
    check_material(material);
    check_points(X, basis.topology().num_vertices());
    LIMSURF_CHECK(std::isfinite(penalty) && penalty > 0.0, InputError, "plate: the Nitsche penalty must be > 0, got ",
                  penalty);
    std::vector<Eigen::Triplet<double>> entries;
    LimitWeights W;
    for (const detail::BoundarySample& b : detail::boundary_samples(basis, rule)) {
        basis.evaluate(b.point, W, DerivativeOrder::Second);
        add_clamping_sample(b, W, X, material, penalty, entries);
    }
    const Index V = basis.topology().num_vertices();
    SparseMatrix N(V, V);
    N.setFromTriplets(entries.begin(), entries.end());
    return SparseMatrix(0.5 * (N + SparseMatrix(N.transpose())));
}

PlateSolution solve_plate(const LimitBasis& basis, const LimitSampler& sampler, const Points& X,
                          const PlateMaterial& material, PlateSupport support, const SurfaceFunction& load,
                          double penalty) {
    LIMSURF_CHECK(basis.topology().has_boundary(), InputError,
                  "plate: the control mesh is closed: a plate needs a boundary");
    check_sampler_matches(basis, sampler);
    SparseMatrix clamping;
    if (support == PlateSupport::ClampedNitsche) {
        clamping = assemble_plate_clamping(basis, X, material, sampler.options(), penalty);
    }
    return solve_with_supports(basis.topology(), sampler, X, material, support, galerkin_load(sampler, X, load),
                               clamping);
}

PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                          const PlateMaterial& material, PlateSupport support, const SurfaceFunction& load) {
    LIMSURF_CHECK(topology.has_boundary(), InputError, "plate: the control mesh is closed: a plate needs a boundary");
    if (support == PlateSupport::ClampedNitsche) {
        const LimitBasis basis(topology, SchemeKind::CatmullClark);
        return solve_plate(basis, sampler, X, material, support, load, default_clamping_penalty);
    }
    return solve_with_supports(topology, sampler, X, material, support, galerkin_load(sampler, X, load),
                               SparseMatrix());
}

PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                          const PlateMaterial& material, PlateSupport support, const Eigen::VectorXd& load_values) {
    LIMSURF_CHECK(topology.has_boundary(), InputError, "plate: the control mesh is closed: a plate needs a boundary");
    LIMSURF_CHECK(load_values.size() == topology.num_vertices() && load_values.allFinite(), InputError,
                  "plate: ", load_values.size(), " load values for ", topology.num_vertices(),
                  " control vertices, or not finite");
    const Eigen::VectorXd b = assemble_laplace_beltrami(sampler, X).mass * load_values;
    SparseMatrix clamping;
    if (support == PlateSupport::ClampedNitsche) {
        const LimitBasis basis(topology, SchemeKind::CatmullClark);
        check_sampler_matches(basis, sampler);
        clamping = assemble_plate_clamping(basis, X, material, sampler.options(), default_clamping_penalty);
    }
    return solve_with_supports(topology, sampler, X, material, support, b, clamping);
}

bool locate_planar_point(const LimitBasis& basis, const Points& X, double x, double y, SurfacePoint& out) {
    const Eigen::Vector2d target(x, y);
    const bool triangle = basis.domain() == ParameterDomain::Triangle;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        SurfacePoint point{p, triangle ? 1.0 / 3.0 : 0.5, triangle ? 1.0 / 3.0 : 0.5};
        LimitWeights w = basis.evaluate(point, DerivativeOrder::First);
        // The convex hull test: skip faces whose support's bounding box misses the point.
        Eigen::Vector2d lo = X.row(w.vertices.front()).head<2>().transpose(), hi = lo;
        for (const Index v : w.vertices) {
            lo = lo.cwiseMin(X.row(v).head<2>().transpose());
            hi = hi.cwiseMax(X.row(v).head<2>().transpose());
        }
        if ((target.array() < lo.array() - 1e-12).any() || (target.array() > hi.array() + 1e-12).any()) {
            continue;
        }
        for (int iteration = 0; iteration < 50; ++iteration) {
            const Eigen::Matrix<double, 6, 3> D = w.apply(X);
            Eigen::Matrix2d J;
            J << D(Du, 0), D(Dv, 0), D(Du, 1), D(Dv, 1);
            const Eigen::Vector2d residual = target - D.row(Value).head<2>().transpose();
            if (residual.norm() <= 1e-13 * (hi - lo).norm()) {
                const double tol = 1e-9;
                const bool inside =
                    triangle ? (point.u >= -tol && point.v >= -tol && point.u + point.v <= 1 + tol)
                             : (point.u >= -tol && point.v >= -tol && point.u <= 1 + tol && point.v <= 1 + tol);
                if (inside) {
                    point.u = std::clamp(point.u, 0.0, 1.0);
                    point.v = std::clamp(point.v, 0.0, triangle ? 1.0 - point.u : 1.0);
                    out = point;
                    return true;
                }
                break;
            }
            if (std::abs(J.determinant()) < 1e-300) {
                break;
            }
            const Eigen::Vector2d step = J.inverse() * residual;
            // Newton in the parameter domain, kept within a margin of it (the map extends smoothly a little).
            point.u = std::clamp(point.u + step.x(), -0.5, 1.5);
            point.v = std::clamp(point.v + step.y(), -0.5, 1.5);
            const double cu = std::clamp(point.u, 0.0, 1.0);
            const double cv = std::clamp(point.v, 0.0, triangle ? 1.0 - cu : 1.0);
            if (std::abs(cu - point.u) > 0.25 || std::abs(cv - point.v) > 0.25) {
                break;  // heading out of this face
            }
            point.u = cu;
            point.v = cv;
            w = basis.evaluate(point, DerivativeOrder::First);
        }
    }
    return false;
}

namespace {

/// The rectangle and point of an exact deflection: sides positive and finite, the rest finite.
void check_rectangle(const char* name, double a, double b, double D, double p, double x, double y) {
    LIMSURF_CHECK(a > 0.0 && b > 0.0 && std::isfinite(a) && std::isfinite(b), InputError, name,
                  ": the sides must be positive and finite, got ", a, " and ", b);
    LIMSURF_CHECK(D > 0.0 && std::isfinite(D) && std::isfinite(p), InputError, name,
                  ": D must be positive and finite and p finite, got D = ", D, ", p = ", p);
    LIMSURF_CHECK(std::isfinite(x) && std::isfinite(y), InputError, name, ": the point must be finite, got (", x, ", ",
                  y, ")");
}

/// The tolerance checked, and raised to 1e-17: a smaller one gains nothing in doubles and would sum
/// 10⁷⁵ terms at 1e-300.
double checked_tolerance(const char* name, double tolerance) {
    LIMSURF_CHECK(tolerance > 0.0 && tolerance < 1.0, InputError, name, ": the tolerance must be in (0, 1), got ",
                  tolerance);
    return std::max(tolerance, 1e-17);
}

}  // namespace

double navier_uniform(double a, double b, double D, double p, double x, double y, double tolerance) {
    check_rectangle("navier_uniform", a, b, D, p, x, y);
    tolerance = checked_tolerance("navier_uniform", tolerance);
    const double pi = std::numbers::pi;
    // Terms are bounded by 1/(m n q²) with q ≥ m²/a², n²/b²: rows beyond m with a⁴/m⁵ below the
    // tolerance times the first term, and columns beyond n with b⁴/(m n⁵) likewise, are dropped.
    const double first = 1.0 / std::pow(1.0 / (a * a) + 1.0 / (b * b), 2);
    const double cut = tolerance * first;
    double sum = 0.0;
    for (int m = 1; std::pow(a, 4) / std::pow(m, 5) >= cut || m == 1; m += 2) {
        const double sx = std::sin(m * pi * x / a);
        for (int n = 1; std::pow(b, 4) / (m * std::pow(n, 5)) >= cut || n == 1; n += 2) {
            const double q = static_cast<double>(m) * m / (a * a) + static_cast<double>(n) * n / (b * b);
            sum += sx * std::sin(n * pi * y / b) / (static_cast<double>(m) * n * q * q);
        }
    }
    return 16.0 * p / (std::pow(pi, 6) * D) * sum;
}

double levy_uniform(double a, double b, double D, double p, double x, double y, double tolerance) {
    check_rectangle("levy_uniform", a, b, D, p, x, y);
    tolerance = checked_tolerance("levy_uniform", tolerance);
    const double pi = std::numbers::pi;
    if (a > b) {  // the series along the shorter side: its terms then fall like 1/m⁵ from the first
        std::swap(a, b);
        std::swap(x, y);
    }
    const double eta = 2.0 * y / b - 1.0;
    const double e_eta = std::abs(eta);
    const double alpha1 = pi * b / (2.0 * a);
    // cosh(αη)/cosh α = (e^{α(|η|−1)} + e^{−α(|η|+1)}) / (1 + e^{−2α}), sinh likewise with a minus
    // and η's sign: each exponential is a power m of its value at m = 1, advanced by its square.
    const double near1 = std::exp(alpha1 * (e_eta - 1.0)), far1 = std::exp(-alpha1 * (e_eta + 1.0));
    const double damp1 = std::exp(-2.0 * alpha1);
    const double near_step = near1 * near1, far_step = far1 * far1, damp_step = damp1 * damp1;
    double near = near1, far = far1, damp = damp1;
    // sin(mπx/a) as the imaginary part of e^{imθ}, advanced by e^{2iθ} (error growing like m ε).
    const double theta = pi * x / a;
    double wave_cos = std::cos(theta), wave_sin = std::sin(theta);
    const double step_cos = std::cos(2.0 * theta), step_sin = std::sin(2.0 * theta);
    // Σ_{m > M odd} 1/m⁵ < 1/(8 (M − 1)⁴): stop once that is below the tolerance.
    const double last = 1.0 + std::pow(8.0 * tolerance, -0.25);
    double sum = 0.0;
    for (int m = 1;; m += 2) {
        const double alpha = m * alpha1;
        const double C = (near + far) / (1.0 + damp);
        const double S = std::copysign((near - far) / (1.0 + damp), eta);
        const double tanh_alpha = (1.0 - damp) / (1.0 + damp);
        const double bracket = 1.0 - (alpha * tanh_alpha + 2.0) / 2.0 * C + alpha * eta / 2.0 * S;
        const double mm = static_cast<double>(m);
        sum += wave_sin * bracket / (mm * mm * mm * mm * mm);
        if (m >= last) {
            break;
        }
        near *= near_step;
        far *= far_step;
        damp *= damp_step;
        const double next_cos = wave_cos * step_cos - wave_sin * step_sin;
        wave_sin = wave_sin * step_cos + wave_cos * step_sin;
        wave_cos = next_cos;
    }
    return 4.0 * p * std::pow(a, 4) / (std::pow(pi, 5) * D) * sum;
}

double navier_sine(double a, double b, double D, double p, int m, int n, double x, double y) {
    check_rectangle("navier_sine", a, b, D, p, x, y);
    LIMSURF_CHECK(m >= 1 && n >= 1, InputError, "navier_sine: the wave numbers must be at least 1, got ", m, " and ",
                  n);
    const double pi = std::numbers::pi;
    const double q = static_cast<double>(m * m) / (a * a) + static_cast<double>(n * n) / (b * b);
    return p / (std::pow(pi, 4) * D * q * q) * std::sin(m * pi * x / a) * std::sin(n * pi * y / b);
}

}  // namespace limsurf
