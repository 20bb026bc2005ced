// Control points interpolating given limit positions (interpolation.h).
#include "limsurf/limit/interpolation.h"

#include <cmath>

#include <Eigen/SparseLU>

#include "limsurf/core/error.h"

namespace limsurf {

Points interpolating_control_points(const LimitBasis& basis, const Points& targets) {
    const Index n = basis.topology().num_vertices();
    LIMSURF_CHECK(targets.rows() == n, InputError, "interpolation: ", targets.rows(), " targets for ", n,
                  " control vertices");
    LIMSURF_CHECK(targets.allFinite(), InputError, "interpolation: the targets are not finite");
    // Column-major for SparseLU; P is as sparse as the one-rings and well conditioned away from
    // linearly dependent bases, so a sparse LU is the simple, exact choice.
    const Eigen::SparseMatrix<double> P = basis.vertex_limit_matrix();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(P);
    LIMSURF_CHECK(lu.info() == Eigen::Success, NumericalError,
                  "interpolation: the limit positions of this control mesh do not determine its control points "
                  "(the limit basis is linearly dependent)");
    Points X = lu.solve(targets);
    const double residual = (P * X - targets).norm() / std::max(targets.norm(), 1e-300);
    LIMSURF_CHECK(X.allFinite() && residual <= 1e-10, NumericalError,
                  "interpolation: the limit position matrix is singular or ill-conditioned (relative residual ",
                  residual, ")");
    return X;
}

Points project_onto_zero_set(const std::function<Eigen::VectorXd(const Points&)>& F, Points P) {
    if (P.rows() == 0) {
        return P;
    }
    const double extent = std::max((P.colwise().maxCoeff() - P.colwise().minCoeff()).norm(), 1e-300);
    const double h = 1e-7 * extent;
    const auto values = [&](const Points& Q) {
        Eigen::VectorXd v = F(Q);
        LIMSURF_CHECK(v.size() == Q.rows(), InputError, "projection: the surface function returned ", v.size(),
                      " values for ", Q.rows(), " points");
        return v;
    };
    for (int step = 0; step <= 50; ++step) {
        const Eigen::VectorXd f = values(P);
        Points gradient(P.rows(), 3);
        for (int c = 0; c < 3; ++c) {
            Points plus = P, minus = P;
            plus.col(c).array() += h;
            minus.col(c).array() -= h;
            gradient.col(c) = (values(plus) - values(minus)) / (2.0 * h);
        }
        bool done = true;
        for (Index v = 0; v < P.rows(); ++v) {
            const double g2 = gradient.row(v).squaredNorm();
            LIMSURF_CHECK(std::isfinite(f(v)) && std::isfinite(g2) && g2 > 0.0, InputError,
                          "projection: the surface function is not finite or has no gradient at (", P(v, 0), ", ",
                          P(v, 1), ", ", P(v, 2), ")");
            const double distance = std::abs(f(v)) / std::sqrt(g2);
            if (distance > 1e-12 * extent) {
                LIMSURF_CHECK(step < 50, InputError, "projection: point ", v, " (", P(v, 0), ", ", P(v, 1), ", ",
                              P(v, 2), ") does not reach the surface (still ", distance, " away after 50 steps)");
                P.row(v) -= (f(v) / g2) * gradient.row(v);
                done = false;
            }
        }
        if (done) {
            break;
        }
    }
    return P;
}

}  // namespace limsurf
