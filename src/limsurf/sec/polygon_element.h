// The per-polygon pieces of the Alexa–Wardetzky inner products (inner_products.h): one face's
// area and its n × n 1-form matrix. Private to the sec layer; shared by the whole-mesh assembly
// (polygonal_inner_products) and the patch assembly of the subdivision inner products
// (patch_inner_products.h), so both compute the same numbers.
//
// Templated on the corner count N (3, 4, or Eigen::Dynamic): the patch assembly evaluates close
// to a million level-3 faces, and fixed sizes keep those evaluations off the heap.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Dense>

namespace limsurf::detail {

/// One polygon's contribution: M0 gets area / n at each corner, M2 gets 1 / area, and M1 gets
/// one_form on the polygon's edges (edge i runs from corner i to corner i+1, counter-clockwise).
template <int N>
struct PolygonElement {
    double area = 0.0;
    Eigen::Matrix<double, N, N> one_form;
};

/// The vector area ½ Σ x_i × x_{i+1} of the polygon with corners @p P (n × 3, counter-clockwise).
template <int N>
Eigen::Vector3d polygon_vector_area(const Eigen::Matrix<double, N, 3>& P) {
    Eigen::Vector3d vector_area = Eigen::Vector3d::Zero();
    const Eigen::Index n = P.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
        vector_area += 0.5 * Eigen::Vector3d(P.row(i)).cross(Eigen::Vector3d(P.row((i + 1) % n)));
    }
    return vector_area;
}

/// True when @p area is not finite or (numerically) zero against the polygon's longest edge.
template <int N>
bool polygon_is_degenerate(const Eigen::Matrix<double, N, 3>& P, double area) {
    double scale = 0.0;
    const Eigen::Index n = P.rows();
    for (Eigen::Index i = 0; i < n; ++i) {
        scale = std::max(scale, (P.row((i + 1) % n) - P.row(i)).squaredNorm());
    }
    return !(std::isfinite(area) && area > 1e-14 * scale);
}

/// An orthonormal pair spanning the plane orthogonal to the unit vector @p normal.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> tangent_basis(const Eigen::Vector3d& normal) {
    const Eigen::Vector3d helper = std::abs(normal.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d t1 = normal.cross(helper).normalized();
    return {t1, normal.cross(t1)};
}

/// @brief The element of the polygon with corners @p P (n × 3, counter-clockwise):
///   one_form = B Bᵀ / |a| + λ P_⊥ (inner_products.h). @pre not polygon_is_degenerate
template <int N>
PolygonElement<N> polygon_element(const Eigen::Matrix<double, N, 3>& P, const Eigen::Vector3d& vector_area) {
    using Square = Eigen::Matrix<double, N, N>;
    using Rows3 = Eigen::Matrix<double, N, 3>;
    using Rows2 = Eigen::Matrix<double, N, 2>;
    const Eigen::Index n = P.rows();
    const Eigen::RowVector3d centroid = P.colwise().mean();
    Rows3 B(n, 3);
    Rows3 E(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        const Eigen::Index next = (i + 1) % n;
        B.row(i) = 0.5 * (P.row(i) + P.row(next)) - centroid;
        E.row(i) = P.row(next) - P.row(i);
    }
    PolygonElement<N> element;
    element.area = vector_area.norm();
    const auto [t1, t2] = tangent_basis(vector_area / element.area);
    Rows2 flat(n, 2);  // the edges flattened onto the face's plane, in 2D coordinates
    flat.col(0) = E * t1;
    flat.col(1) = E * t2;
    const Eigen::Matrix2d gram = flat.transpose() * flat;
    // The projector onto ker(flatᵀ): the circulation part that the consistency term cannot see.
    const Square kernel_projector = Square::Identity(n, n) - flat * gram.inverse() * flat.transpose();
    const Square consistency = B * B.transpose() / element.area;
    const double lambda = consistency.trace() / 2.0;
    element.one_form = consistency + lambda * kernel_projector;
    return element;
}

}  // namespace limsurf::detail
