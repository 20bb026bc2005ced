#include "limsurf/limit/surface_frame.h"

#include <cmath>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"

namespace limsurf {

bool has_tangent_plane(const Eigen::Matrix<double, 6, 3>& derivatives) {
    const Eigen::Matrix<double, 2, 3> t =
        times_power_of_two(derivatives.middleRows<2>(1), -magnitude_exponent(derivatives.middleRows<2>(1)));
    const Eigen::Vector3d xu = t.row(0).transpose();
    const Eigen::Vector3d xv = t.row(1).transpose();
    return t.allFinite() && xu.cross(xv).norm() > 1e-14 * xu.norm() * xv.norm();
}

SurfaceFrame surface_frame(const Eigen::Matrix<double, 6, 3>& unscaled) {
    LIMSURF_CHECK(unscaled.allFinite(), NumericalError, "surface_frame: the derivatives are not finite");
    // Derivatives brought to order one by 2^-e (exact): the products below neither overflow nor
    // underflow for a surface of any size; lengths are scaled back at the end.
    const int e = magnitude_exponent(unscaled.bottomRows<5>());
    const Eigen::Matrix<double, 6, 3> derivatives = times_power_of_two(unscaled, -e);
    const Eigen::Vector3d xu = derivatives.row(1).transpose();
    const Eigen::Vector3d xv = derivatives.row(2).transpose();
    const Eigen::Vector3d xuu = derivatives.row(3).transpose();
    const Eigen::Vector3d xuv = derivatives.row(4).transpose();
    const Eigen::Vector3d xvv = derivatives.row(5).transpose();

    const Eigen::Vector3d cross = xu.cross(xv);
    const double area = cross.norm();
    const double norm_u = xu.norm();
    const double norm_v = xv.norm();
    LIMSURF_CHECK(area > 1e-14 * norm_u * norm_v, NumericalError,
                  "surface_frame: degenerate tangents (|xu x xv| = ", area, ", |xu| = ", norm_u, ", |xv| = ", norm_v,
                  ")");

    SurfaceFrame frame;
    frame.normal = cross / area;
    frame.E = xu.dot(xu);
    frame.F = xu.dot(xv);
    frame.G = xv.dot(xv);
    frame.L = xuu.dot(frame.normal);
    frame.M = xuv.dot(frame.normal);
    frame.N = xvv.dot(frame.normal);

    // The shape operator in the orthonormal tangent basis (e1, e2), e1 = xu/|xu|,
    // e2 = n × e1: with the Jacobian [xu xv] = [e1 e2] A, W = -A⁻ᵀ II A⁻¹ is symmetric,
    // so its eigenvectors are orthonormal and map to orthonormal 3D directions.
    const Eigen::Vector3d e1 = xu / norm_u;
    const Eigen::Vector3d e2 = frame.normal.cross(e1);
    Eigen::Matrix2d A;
    A << norm_u, e1.dot(xv), 0.0, e2.dot(xv);
    Eigen::Matrix2d II;
    II << frame.L, frame.M, frame.M, frame.N;
    const Eigen::Matrix2d jacobian_inverse = A.inverse();
    Eigen::Matrix2d W = -jacobian_inverse.transpose() * II * jacobian_inverse;
    W(0, 1) = W(1, 0) = 0.5 * (W(0, 1) + W(1, 0));

    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
    solver.computeDirect(W);
    const Eigen::Vector2d k = solver.eigenvalues();  // ascending
    const Eigen::Matrix2d X = solver.eigenvectors();
    frame.k1 = k(1);
    frame.k2 = k(0);
    frame.gaussian_curvature = frame.k1 * frame.k2;
    frame.mean_curvature = 0.5 * (frame.k1 + frame.k2);
    frame.d1 = (X(0, 1) * e1 + X(1, 1) * e2).normalized();
    frame.d2 = frame.normal.cross(frame.d1);
    // Back to the surface's size: E, F, G scale with length², L, M, N with length, κ with 1/length.
    frame.E = std::ldexp(frame.E, 2 * e);
    frame.F = std::ldexp(frame.F, 2 * e);
    frame.G = std::ldexp(frame.G, 2 * e);
    frame.L = std::ldexp(frame.L, e);
    frame.M = std::ldexp(frame.M, e);
    frame.N = std::ldexp(frame.N, e);
    frame.k1 = std::ldexp(frame.k1, -e);
    frame.k2 = std::ldexp(frame.k2, -e);
    frame.gaussian_curvature = std::ldexp(frame.gaussian_curvature, -2 * e);
    frame.mean_curvature = std::ldexp(frame.mean_curvature, -e);
    LIMSURF_CHECK(frame.normal.allFinite() && std::isfinite(frame.k1) && std::isfinite(frame.k2) &&
                      std::isfinite(frame.gaussian_curvature) && std::isfinite(frame.mean_curvature),
                  NumericalError, "the curvatures overflow a double (they grow as 1/size², and the surface is ",
                  "about 2^", e, " across): rescale the mesh");
    return frame;
}

}  // namespace limsurf
