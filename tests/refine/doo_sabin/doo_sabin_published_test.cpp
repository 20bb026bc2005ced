// The Doo–Sabin subdivision matrices printed in volume-trilinear-forms
// (Hakenberg, "Volume of Doo-Sabin, Catmull-Clark and Loop subdivision
// surfaces via trilinear forms"), section "Doo-Sabin", "Non-regular facet",
// Example τ(f) = 3: the facet of a vertex v of valence 4 in three quads and one
// triangle, with m(f) = 8 control points numbered as a 3×3 grid without its
// last corner:
//
//     1 — 2 — 3        faces (1 2 5 4), (2 3 6 5), (4 5 8 7) and the triangle (5 6 8)
//     |   |   |
//     4 — 5 — 6        v = 5
//     |   | /
//     7 — 8
//
// One round of subdivision maps these points to the control points of the four
// child facets: S^h is m(f_h)×m(f). We extract S^3 (the regular child facet at
// the child of corner 5 of face (1 2 5 4)) and S^4 (the non-regular child facet
// at the child of corner 5 of the triangle) from our S0 and compare them with
// what the paper prints.
#include <algorithm>
#include <array>
#include <complex>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/refine/refine.h"

namespace limsurf {
namespace {

// The patch, with the paper's 1-based labels as 0-based vertices.
const std::vector<std::vector<Index>> patch_faces = {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 7}};
constexpr Index q1 = 0;   // (1 2 5 4)
constexpr Index q2 = 1;   // (2 3 6 5)
constexpr Index q3 = 2;   // (4 5 8 7)
constexpr Index tri = 3;  // (5 6 8)

/// A child control point: the child of the corner of @p face at paper label @p label.
struct ChildPoint {
    Index face;
    Index label;
};

/// The rows of our S0 for @p points, as a dense |points|×8 matrix in the paper's column order.
Eigen::MatrixXd extract(const Topology& t, const SparseMatrix& S0, const std::vector<ChildPoint>& points) {
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(static_cast<Index>(points.size()), 8);
    for (std::size_t r = 0; r < points.size(); ++r) {
        const auto fv = t.face_vertices(points[r].face);
        const auto it = std::find(fv.begin(), fv.end(), points[r].label - 1);
        const Index child = t.face_offset(points[r].face) + static_cast<Index>(it - fv.begin());
        for (SparseMatrix::InnerIterator entry(S0, child); entry; ++entry) {
            S(static_cast<Index>(r), entry.col()) = entry.value();
        }
    }
    return S;
}

Level refine_patch(const Topology& t) {
    // Every corner of the patch touches its boundary; the paper's matrices are
    // the interior (classic) masks, which BoundaryInterpolation::None applies everywhere.
    SchemeOptions options;
    options.boundary = BoundaryInterpolation::None;
    return refine_doo_sabin(t, options);
}

TEST(DooSabinPublished, HakenbergS3OfTheValence3Facet) {
    const Topology t = Topology::from_polygons(8, patch_faces);
    const Level level = refine_patch(t);
    // Facet f_3 at the child of corner 5 of (1 2 5 4); its 3×3 grid: the F-face
    // of (1 2 5 4) is (1 2 5 4), the E-faces of edges 2-5 and 4-5 give 3, 6 and
    // 7, 8, the V-face of vertex 5 gives 9.
    const std::vector<ChildPoint> f3 = {{q1, 1}, {q1, 2}, {q2, 2}, {q1, 4}, {q1, 5},
                                        {q2, 5}, {q3, 4}, {q3, 5}, {tri, 5}};
    // The paper prints S^3 = 1/16 · (...) with these rows (its extracted text
    // repeats row 6 once more; the matrix is 9×8, m(f_3) = 9).
    const double t3 = 32.0 / 3.0;
    const double e3 = 8.0 / 3.0;
    Eigen::MatrixXd published(9, 8);
    published << 9, 3, 0, 3, 1, 0, 0, 0,  //
        3, 9, 0, 1, 3, 0, 0, 0,           //
        0, 9, 3, 0, 3, 1, 0, 0,           //
        3, 1, 0, 9, 3, 0, 0, 0,           //
        1, 3, 0, 3, 9, 0, 0, 0,           //
        0, 3, 1, 0, 9, 3, 0, 0,           //
        0, 0, 0, 9, 3, 0, 3, 1,           //
        0, 0, 0, 3, 9, 0, 1, 3,           //
        0, 0, 0, 0, t3, e3, 0, e3;
    published /= 16.0;
    const Eigen::MatrixXd ours = extract(t, level.S0, f3);
    EXPECT_LE((ours - published).cwiseAbs().maxCoeff(), 1e-15) << "ours:\n" << ours * 16.0;
}

TEST(DooSabinPublished, HakenbergS4OfTheValence3Facet) {
    const Topology t = Topology::from_polygons(8, patch_faces);
    const Level level = refine_patch(t);
    // Facet f_4 at the child of corner 5 of the triangle; same numbering as f:
    // the V-face of 5 gives 1, the E-face of 5-6 gives 2, 3, the E-face of 5-8
    // gives 4, 7, and the triangle's F-face gives 5, 6, 8.
    const std::vector<ChildPoint> f4 = {{q1, 5}, {q2, 5}, {q2, 6}, {q3, 5}, {tri, 5}, {tri, 6}, {q3, 8}, {tri, 8}};
    const Eigen::MatrixXd S = extract(t, level.S0, f4);
    // "The indexing means S^4_{7,8} = 9/16."
    EXPECT_DOUBLE_EQ(S(6, 7), 9.0 / 16.0);
    // The last row printed: 1/16 · (0 0 0 0 8/3 8/3 0 32/3); and the row of the
    // triangle's corner 5: 1/16 · (0 0 0 0 32/3 8/3 0 8/3).
    Eigen::RowVectorXd last(8);
    last << 0, 0, 0, 0, 8.0 / 3.0, 8.0 / 3.0, 0, 32.0 / 3.0;
    Eigen::RowVectorXd corner5(8);
    corner5 << 0, 0, 0, 0, 32.0 / 3.0, 8.0 / 3.0, 0, 8.0 / 3.0;
    EXPECT_LE((S.row(7) - last / 16.0).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_LE((S.row(4) - corner5 / 16.0).cwiseAbs().maxCoeff(), 1e-15);
    // "The eigenvalues of S^4 are [1, 1/2, 1/2, ..., 1/16] in descending order."
    Eigen::EigenSolver<Eigen::MatrixXd> solver(S);
    std::vector<double> eigenvalues;
    for (Index i = 0; i < 8; ++i) {
        EXPECT_NEAR(solver.eigenvalues()(i).imag(), 0.0, 1e-12);
        eigenvalues.push_back(solver.eigenvalues()(i).real());
    }
    std::sort(eigenvalues.begin(), eigenvalues.end(), std::greater<>());
    EXPECT_NEAR(eigenvalues[0], 1.0, 1e-12);
    EXPECT_NEAR(eigenvalues[1], 0.5, 1e-12);
    EXPECT_NEAR(eigenvalues[2], 0.5, 1e-12);
    EXPECT_NEAR(eigenvalues[7], 1.0 / 16.0, 1e-12);
    // "A right eigenvector to eigenvalue 1 is v = [0, 0, 0, 0, 1, 1, 0, 1]": with
    // S^4 acting on columns of control points (child = S^4 · parent, the paper's
    // own definition) v is the eigenvector of the transpose: vᵀ S^4 = vᵀ.
    Eigen::RowVectorXd v(8);
    v << 0, 0, 0, 0, 1, 1, 0, 1;
    EXPECT_LE((v * S - v).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace limsurf
