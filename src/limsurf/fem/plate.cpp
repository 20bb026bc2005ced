// Kirchhoff–Love plates with the limit basis (plate.h, docs/fem.md "Plates").
#include "limsurf/fem/plate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include <Eigen/Dense>

#include "element_assembly.h"
#include "limsurf/core/error.h"
#include "limsurf/detail/sparse_cholesky.h"

namespace limsurf {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

void check_material(const PlateMaterial& m) {
    LIMSURF_CHECK(std::isfinite(m.E) && m.E > 0.0, InputError, "plate: E must be > 0, got ", m.E);
    LIMSURF_CHECK(std::isfinite(m.nu) && m.nu > -1.0 && m.nu < 0.5, InputError, "plate: nu must be in (-1, 0.5), got ",
                  m.nu);
    LIMSURF_CHECK(std::isfinite(m.thickness) && m.thickness > 0.0, InputError, "plate: the thickness must be > 0, got ",
                  m.thickness);
}

void check_planar(const Points& X) {
    const double extent = (X.colwise().maxCoeff() - X.colwise().minCoeff()).head<2>().maxCoeff();
    LIMSURF_CHECK(extent > 0.0 && X.col(2).cwiseAbs().maxCoeff() <= 1e-12 * extent, InputError,
                  "plate: the control mesh must lie in the plane z = 0");
}

/// Curvatures (w_xx, w_yy, 2 w_xy) of every basis function at sample s: 3 × k.
Eigen::Matrix<double, 3, Eigen::Dynamic> curvatures(const LimitSampler& sampler, const Points& X, Index s,
                                                    double& area_element) {
    const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
    Eigen::Matrix2d J;  // columns ∂/∂u, ∂/∂v of (x, y)
    J << D(Du, 0), D(Dv, 0), D(Du, 1), D(Dv, 1);
    const double det = J.determinant();
    LIMSURF_CHECK(std::isfinite(det) && std::abs(det) > 1e-14 * J.squaredNorm(), NumericalError,
                  "plate: the map of the plate is degenerate at a quadrature point of ptex face ",
                  sampler.point(s).face);
    area_element = std::abs(det);
    const Eigen::Matrix2d Jinv = J.inverse();
    const auto W = sampler.limit_weights(s);
    const Index k = W.cols();
    Eigen::Matrix<double, 3, Eigen::Dynamic> B(3, k);
    for (Index j = 0; j < k; ++j) {
        const Eigen::Vector2d grad = Jinv.transpose() * Eigen::Vector2d(W(Du, j), W(Dv, j));  // (φ_x, φ_y)
        Eigen::Matrix2d H;
        H << W(Duu, j), W(Duv, j), W(Duv, j), W(Dvv, j);
        for (int c = 0; c < 2; ++c) {  // minus ∂φ/∂x_c times the map's second derivatives
            Eigen::Matrix2d Hx;
            Hx << D(Duu, c), D(Duv, c), D(Duv, c), D(Dvv, c);
            H -= grad(c) * Hx;
        }
        const Eigen::Matrix2d Hxy = Jinv.transpose() * H * Jinv;
        B(0, j) = Hxy(0, 0);
        B(1, j) = Hxy(1, 1);
        B(2, j) = 2.0 * Hxy(0, 1);
    }
    return B;
}

}  // namespace

SparseMatrix assemble_plate_bending(const LimitSampler& sampler, const Points& X, const PlateMaterial& material) {
    check_material(material);
    LIMSURF_CHECK(X.rows() == sampler.num_vertices() && X.cols() == 3, InputError, "plate: X has ", X.rows(),
                  " rows, the control mesh ", sampler.num_vertices(), " vertices");
    check_planar(X);
    const double D = material.bending_rigidity();
    const double nu = material.nu;
    Eigen::Matrix3d C;
    C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
    C *= D;
    return detail::assemble_elements<1>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 1>& Ke) {
            double dA = 0.0;
            const Eigen::Matrix<double, 3, Eigen::Dynamic> B = curvatures(sampler, X, s, dA);
            const Eigen::MatrixXd k = (sampler.weight(s) * dA) * B.transpose() * C * B;
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    Ke[0](local[i], local[j]) += k(static_cast<Index>(i), static_cast<Index>(j));
                }
            }
        })[0];
}

PlateSolution solve_plate(const Topology& topology, const LimitSampler& sampler, const Points& X,
                          const PlateMaterial& material, PlateSupport support, const SurfaceFunction& load) {
    LIMSURF_CHECK(topology.has_boundary(), InputError, "plate: the control mesh is closed: a plate needs a boundary");
    const SparseMatrix K = assemble_plate_bending(sampler, X, material);
    const Eigen::VectorXd b = galerkin_load(sampler, X, load);
    const Index V = topology.num_vertices();
    std::vector<bool> fixed(at(V), false);
    for (Index v = 0; v < V; ++v) {
        if (!topology.is_boundary_vertex(v)) {
            continue;
        }
        fixed[at(v)] = true;
        if (support == PlateSupport::Clamped) {
            // ∂w/∂n on the boundary reads the boundary row and the next one: fix both to zero.
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

double navier_uniform(double a, double b, double D, double p, double x, double y, double tolerance) {
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

double navier_sine(double a, double b, double D, double p, int m, int n, double x, double y) {
    const double pi = std::numbers::pi;
    const double q = static_cast<double>(m * m) / (a * a) + static_cast<double>(n * n) / (b * b);
    return p / (std::pow(pi, 4) * D * q * q) * std::sin(m * pi * x / a) * std::sin(n * pi * y / b);
}

}  // namespace limsurf
