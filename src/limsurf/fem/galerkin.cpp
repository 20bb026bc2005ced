// Galerkin assembly on the exact limit surface (galerkin.h, docs/fem.md).
#include "limsurf/fem/galerkin.h"

#include <algorithm>
#include <cmath>
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

/// The metric of one quadrature point: tangents J (3 × 2), g⁻¹ and √det g.
struct Metric {
    Eigen::Matrix<double, 3, 2> J;
    Eigen::Matrix2d inverse;
    double area_element = 0.0;
};

Metric metric_at(const LimitSampler& sampler, const Points& X, Index s) {
    const Eigen::Matrix<double, 6, 3> D = sampler.evaluate(X, s);
    Metric m;
    m.J.col(0) = D.row(Du).transpose();
    m.J.col(1) = D.row(Dv).transpose();
    const Eigen::Matrix2d g = m.J.transpose() * m.J;
    const double det = g.determinant();
    LIMSURF_CHECK(std::isfinite(det) && det > 1e-28 * g.trace() * g.trace(), NumericalError,
                  "Galerkin assembly: the limit surface is degenerate (parallel tangents) at a quadrature point of "
                  "ptex face ",
                  sampler.point(s).face);
    m.inverse = g.inverse();
    m.area_element = std::sqrt(det);
    return m;
}

void require_size(const LimitSampler& sampler, const Points& X) {
    LIMSURF_CHECK(X.rows() == sampler.num_vertices() && X.cols() == 3, InputError, "Galerkin assembly: X has ",
                  X.rows(), " rows, the control mesh ", sampler.num_vertices(), " vertices");
}

}  // namespace

GalerkinMatrices assemble_laplace_beltrami(const LimitSampler& sampler, const Points& X) {
    require_size(sampler, X);
    // One pass: the metric of each quadrature point serves both matrices.
    auto [mass, stiffness] = detail::assemble_elements<2>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 2>& Ke) {
            const Metric m = metric_at(sampler, X, s);
            const double w = sampler.weight(s) * m.area_element;
            const auto W = sampler.limit_weights(s);
            const Eigen::Matrix<double, 2, Eigen::Dynamic> d = W.middleRows<2>(Du);
            const Eigen::MatrixXd local_k = w * d.transpose() * m.inverse * d;
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    const auto ii = static_cast<Index>(i), jj = static_cast<Index>(j);
                    Ke[0](local[i], local[j]) += w * W(Value, ii) * W(Value, jj);
                    Ke[1](local[i], local[j]) += local_k(ii, jj);
                }
            }
        });
    GalerkinMatrices out;
    out.mass.swap(mass);  // swapped: Eigen 3.4's SparseMatrix has no move assignment (std::move copied)
    out.stiffness.swap(stiffness);
    return out;
}

SparseMatrix assemble_area_form(const LimitSampler& sampler) {
    // Two unknowns per vertex (u, v) during assembly; restacked as (u; v) below.
    auto [interleaved] = detail::assemble_elements<1, 2>(
        sampler, [&](Index s, std::span<const Index> local, std::array<Eigen::MatrixXd, 1>& Ke) {
            const double w = sampler.weight(s);
            const auto W = sampler.limit_weights(s);
            for (std::size_t i = 0; i < local.size(); ++i) {
                for (std::size_t j = 0; j < local.size(); ++j) {
                    const auto ii = static_cast<Index>(i), jj = static_cast<Index>(j);
                    const double wedge = w * (W(Du, ii) * W(Dv, jj) - W(Dv, ii) * W(Du, jj));
                    Ke[0](2 * local[i], 2 * local[j] + 1) += wedge;  // u_i v_j, and its mirror
                    Ke[0](2 * local[j] + 1, 2 * local[i]) += wedge;
                }
            }
        });
    const Index n = sampler.num_vertices();
    const auto stacked = [n](Index r) { return (r % 2) * n + r / 2; };
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(at(interleaved.nonZeros()));
    for (Index r = 0; r < interleaved.outerSize(); ++r) {
        for (SparseMatrix::InnerIterator it(interleaved, r); it; ++it) {
            triplets.emplace_back(stacked(static_cast<Index>(it.row())), stacked(static_cast<Index>(it.col())),
                                  it.value());
        }
    }
    SparseMatrix out(2 * n, 2 * n);
    out.setFromTriplets(triplets.begin(), triplets.end());
    return out;
}

Eigen::VectorXd galerkin_load(const LimitSampler& sampler, const Points& X, const SurfaceFunction& f) {
    require_size(sampler, X);
    const Index n = sampler.num_samples();
    Points P(n, 3);
    std::vector<double> dA(at(n));
    for (Index s = 0; s < n; ++s) {
        P.row(s) = sampler.evaluate(X, s).row(Value);
        dA[at(s)] = sampler.weight(s) * metric_at(sampler, X, s).area_element;
    }
    const Eigen::VectorXd values = f(P);
    LIMSURF_CHECK(values.size() == n, InputError, "load: the function returned ", values.size(), " values for ", n,
                  " points");
    Eigen::VectorXd b = Eigen::VectorXd::Zero(sampler.num_vertices());
    for (Index s = 0; s < n; ++s) {
        LIMSURF_CHECK(std::isfinite(values(s)), InputError, "load: the function is not finite at (", P(s, 0), ", ",
                      P(s, 1), ", ", P(s, 2), ")");
        const auto W = sampler.limit_weights(s);
        const auto verts = sampler.vertices(s);
        for (std::size_t j = 0; j < verts.size(); ++j) {
            b(verts[j]) += dA[at(s)] * values(s) * W(Value, static_cast<Index>(j));
        }
    }
    return b;
}

GalerkinErrors galerkin_errors(const LimitSampler& sampler, const Points& X, const Eigen::VectorXd& u,
                               const SurfaceFunction& exact, const std::function<Points(const Points&)>& exact_gradient,
                               bool subtract_mean) {
    require_size(sampler, X);
    LIMSURF_CHECK(u.size() == sampler.num_vertices(), InputError, "errors: u has ", u.size(), " values for ",
                  sampler.num_vertices(), " vertices");
    const Index n = sampler.num_samples();
    Points P(n, 3);
    std::vector<Metric> metrics;
    metrics.reserve(at(n));
    Eigen::VectorXd uh(n);
    Points grad_h(n, 3);
    for (Index s = 0; s < n; ++s) {
        P.row(s) = sampler.evaluate(X, s).row(Value);
        metrics.push_back(metric_at(sampler, X, s));
        const auto W = sampler.limit_weights(s);
        const auto verts = sampler.vertices(s);
        Eigen::Vector3d d = Eigen::Vector3d::Zero();  // value, ∂u, ∂v of u_h
        for (std::size_t j = 0; j < verts.size(); ++j) {
            d += W.block<3, 1>(0, static_cast<Index>(j)) * u(verts[j]);
        }
        uh(s) = d(0);
        const Metric& m = metrics.back();
        grad_h.row(s) = (m.J * (m.inverse * d.tail<2>())).transpose();
    }
    const Eigen::VectorXd ue = exact(P);
    const Points ge = exact_gradient(P);
    LIMSURF_CHECK(ue.size() == n && ge.rows() == n && ge.cols() == 3, InputError,
                  "errors: the exact solution returned the wrong number of values");
    GalerkinErrors out;
    double mean_h = 0.0;
    double mean_e = 0.0;
    for (Index s = 0; s < n; ++s) {
        const double w = sampler.weight(s) * metrics[at(s)].area_element;
        out.area += w;
        mean_h += w * uh(s);
        mean_e += w * ue(s);
    }
    if (!subtract_mean) {
        mean_h = mean_e = 0.0;
    } else {
        mean_h /= out.area;
        mean_e /= out.area;
    }
    double l2 = 0.0, h1 = 0.0, l2n = 0.0, h1n = 0.0;
    for (Index s = 0; s < n; ++s) {
        const Metric& m = metrics[at(s)];
        const double w = sampler.weight(s) * m.area_element;
        const Eigen::Vector3d normal = m.J.col(0).cross(m.J.col(1)).normalized();
        Eigen::Vector3d g = ge.row(s).transpose();
        g -= g.dot(normal) * normal;  // the surface gradient: the tangential part
        const double e0 = (uh(s) - mean_h) - (ue(s) - mean_e);
        l2 += w * e0 * e0;
        l2n += w * (ue(s) - mean_e) * (ue(s) - mean_e);
        h1 += w * (grad_h.row(s).transpose() - g).squaredNorm();
        h1n += w * g.squaredNorm();
    }
    out.l2 = std::sqrt(l2);
    out.h1 = std::sqrt(h1);
    out.l2_norm = std::sqrt(l2n);
    out.h1_norm = std::sqrt(h1n);
    return out;
}

GalerkinPoissonSolution solve_galerkin_poisson(const Topology& topology, const GalerkinMatrices& matrices,
                                               const Eigen::VectorXd& load,
                                               const std::optional<Eigen::VectorXd>& boundary_values) {
    const Index V = topology.num_vertices();
    LIMSURF_CHECK(matrices.stiffness.rows() == V && matrices.mass.rows() == V && load.size() == V, InputError,
                  "Galerkin Poisson: the matrices and the load must have one row per vertex (", V, ")");
    const bool closed = topology.is_closed();
    LIMSURF_CHECK(closed || (boundary_values && boundary_values->size() == V), InputError,
                  "Galerkin Poisson: an open mesh needs boundary values (one per vertex)");
    GalerkinPoissonSolution out;
    out.solver = detail::SparseCholesky::name();
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(V);
    const Eigen::VectorXd mass_of_one = matrices.mass * ones;  // ∫ φ_i dA
    const double area = mass_of_one.sum();
    Eigen::VectorXd b = load;
    Eigen::VectorXd u = Eigen::VectorXd::Zero(V);
    std::vector<bool> fixed(at(V), false);
    if (closed) {
        out.mean_removed = b.sum() / area;  // Σ φ_i = 1: Σ b_i = ∫ f dA
        b -= out.mean_removed * mass_of_one;
        fixed[0] = true;  // the constants: pin one vertex, shift afterwards
    } else {
        for (Index v = 0; v < V; ++v) {
            if (topology.is_boundary_vertex(v)) {
                fixed[at(v)] = true;
                u(v) = (*boundary_values)(v);
            }
        }
    }
    auto [solved, residual] =
        detail::solve_with_fixed_values(matrices.stiffness, b, fixed, u, "the Galerkin stiffness matrix");
    u = std::move(solved);
    out.residual = residual;
    if (closed) {
        u.array() -= mass_of_one.dot(u) / area;  // ∫ u_h dA = 0
    }
    LIMSURF_CHECK(u.allFinite(), NumericalError, "Galerkin Poisson: the solution is not finite");
    out.u = std::move(u);
    return out;
}

namespace detail {

std::vector<Index> element_offsets(const LimitSampler& sampler) {
    std::vector<Index> offsets{0};
    for (Index s = 1; s < sampler.num_samples(); ++s) {
        if (sampler.point(s).face != sampler.point(s - 1).face) {
            offsets.push_back(s);
        }
    }
    offsets.push_back(sampler.num_samples());
    return offsets;
}

std::pair<Eigen::VectorXd, double> solve_with_fixed_values(const SparseMatrix& A, const Eigen::VectorXd& b,
                                                           const std::vector<bool>& fixed,
                                                           const Eigen::VectorXd& values, const char* what) {
    const Index V = A.rows();
    Eigen::VectorXd u = values;
    std::vector<Index> free_index(at(V), invalid_index);
    Index num_free = 0;
    for (Index v = 0; v < V; ++v) {
        if (!fixed[at(v)]) {
            free_index[at(v)] = num_free++;
        }
    }
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::VectorXd rhs(num_free);
    for (Index v = 0; v < V; ++v) {
        if (!fixed[at(v)]) {
            rhs(free_index[at(v)]) = b(v);
        }
    }
    for (Index r = 0; r < V; ++r) {
        if (fixed[at(r)]) {
            continue;
        }
        for (SparseMatrix::InnerIterator it(A, r); it; ++it) {
            if (fixed[at(it.col())]) {
                rhs(free_index[at(r)]) -= it.value() * values(it.col());
            } else {
                entries.emplace_back(free_index[at(r)], free_index[at(it.col())], it.value());
            }
        }
    }
    SparseMatrix K(num_free, num_free);
    K.setFromTriplets(entries.begin(), entries.end());
    const SparseCholesky solver(K, what);
    const Eigen::VectorXd x = solver.solve(rhs);
    const double scale = rhs.norm();
    const double residual = scale > 0.0 ? (K * x - rhs).norm() / scale : (K * x - rhs).norm();
    for (Index v = 0; v < V; ++v) {
        if (!fixed[at(v)]) {
            u(v) = x(free_index[at(v)]);
        }
    }
    return {u, residual};
}

}  // namespace detail
}  // namespace limsurf
