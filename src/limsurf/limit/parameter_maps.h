// Parameter maps shared by the limit evaluators (private to src/limsurf/limit):
// affine maps between a ptex domain, its rotations and the children of its split,
// the chain rule that turns patch derivatives into ptex derivatives, and dense rows
// of a sparse subdivision matrix. Quads are the unit square with corners (0,0),
// (1,0), (1,1), (0,1); triangles u, v >= 0, u + v <= 1 with corners (0,0), (1,0), (0,1).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "limsurf/core/types.h"

namespace limsurf::detail {

/// parent = offset + axes · child.
struct Affine {
    Eigen::Vector2d offset = Eigen::Vector2d::Zero();
    Eigen::Matrix2d axes = Eigen::Matrix2d::Identity();

    [[nodiscard]] Eigen::Vector2d to_child(const Eigen::Vector2d& parent) const {
        return axes.inverse() * (parent - offset);
    }
    [[nodiscard]] Affine then(const Affine& inner) const {  // this ∘ inner
        return {offset + axes * inner.offset, axes * inner.axes};
    }
};

inline Eigen::Vector2d domain_corner(bool quad, int k) {
    static const Eigen::Vector2d square[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const Eigen::Vector2d triangle[3] = {{0, 0}, {1, 0}, {0, 1}};
    return quad ? square[k % 4] : triangle[k % 3];
}

/// The domain seen from corner k: (0,0) at corner k, (1,0) at corner k+1, (0,1) at corner k-1.
inline Affine rotation(bool quad, int k) {
    const int n = quad ? 4 : 3;
    const Eigen::Vector2d p = domain_corner(quad, k);
    Affine a;
    a.offset = p;
    a.axes.col(0) = domain_corner(quad, k + 1) - p;
    a.axes.col(1) = domain_corner(quad, k + n - 1) - p;
    return a;
}

/// Child q of the split: corner children are half-size rotations; the middle
/// triangle (q = 3, Loop) is [e0, e1, e2].
inline Affine child_map(bool quad, int q) {
    if (!quad && q == 3) {
        Affine a;
        a.offset = {0.5, 0.0};
        a.axes.col(0) = Eigen::Vector2d(0.0, 0.5);
        a.axes.col(1) = Eigen::Vector2d(-0.5, 0.5);
        return a;
    }
    Affine a = rotation(quad, q);
    a.axes *= 0.5;
    return a;
}

inline bool in_corner_child(bool quad, const Eigen::Vector2d& p) {
    return quad ? (p.x() < 0.5 && p.y() < 0.5) : (p.x() + p.y() < 0.5);
}

inline int child_containing(bool quad, const Eigen::Vector2d& p) {
    if (quad) {
        return p.x() < 0.5 ? (p.y() < 0.5 ? 0 : 3) : (p.y() < 0.5 ? 1 : 2);
    }
    if (p.x() + p.y() < 0.5) {
        return 0;
    }
    return p.x() >= 0.5 ? 1 : (p.y() >= 0.5 ? 2 : 3);
}

/// Basis rows in patch coordinates (s, t) turned into ptex derivatives, for
/// ptex = offset + J · (s, t); @p r may be any 6 × N matrix (it is resized), and may be @p b
/// itself (each column is read before it is written). N may be Eigen::Dynamic.
template <int N, class Out>
void to_ptex(const Eigen::Matrix<double, 6, N>& b, const Eigen::Matrix2d& J, Out& r) {
    const Eigen::Matrix2d Ji = J.inverse();
    r.resize(6, b.cols());
    // H_uv(a, c) = sum_{i,j} Ji(i, a) H_st(i, j) Ji(j, c), with H_st = [[ss, st], [st, tt]].
    const double h[3][3] = {{Ji(0, 0) * Ji(0, 0), 2.0 * Ji(0, 0) * Ji(1, 0), Ji(1, 0) * Ji(1, 0)},
                            {Ji(0, 0) * Ji(0, 1), Ji(0, 0) * Ji(1, 1) + Ji(1, 0) * Ji(0, 1), Ji(1, 0) * Ji(1, 1)},
                            {Ji(0, 1) * Ji(0, 1), 2.0 * Ji(0, 1) * Ji(1, 1), Ji(1, 1) * Ji(1, 1)}};
    for (Eigen::Index k = 0; k < b.cols(); ++k) {
        const double value = b(0, k);
        const double ds = b(1, k);
        const double dt = b(2, k);
        const double second[3] = {b(3, k), b(4, k), b(5, k)};
        r(0, k) = value;
        r(1, k) = Ji(0, 0) * ds + Ji(1, 0) * dt;
        r(2, k) = Ji(0, 1) * ds + Ji(1, 1) * dt;
        for (int i = 0; i < 3; ++i) {
            r(3 + i, k) = h[i][0] * second[0] + h[i][1] * second[1] + h[i][2] * second[2];
        }
    }
}

/// Rows @p rows of the sparse matrix S as a dense matrix.
inline Eigen::MatrixXd dense_rows(const SparseMatrix& S, const std::vector<Index>& rows) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Index>(rows.size()), S.cols());
    for (std::size_t r = 0; r < rows.size(); ++r) {
        for (SparseMatrix::InnerIterator it(S, rows[r]); it; ++it) {
            M(static_cast<Index>(r), it.col()) = it.value();
        }
    }
    return M;
}

}  // namespace limsurf::detail
