// The regular Catmull–Clark subdivision matrix of a valence-4 one-ring as
// printed in iga-with-catmull-clark §3 (the 9×9 matrix S and the eigenvalues
// of its first 4×4 circulant block M).
#include <array>
#include <complex>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "refine/face_split/face_split_helpers.h"
#include "limsurf/refine/refine.h"

namespace limsurf::test {
namespace {

TEST(PublishedCatmullClark, RegularOneRingMatrixOfSection3) {
    // quad_grid: 5×5 vertices; vertex 12 is the centre, interior and regular.
    const auto mesh = load_bundled("quad_grid");
    const Topology& t = mesh.topology;
    Index centre = invalid_index;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (mesh.positions.row(v).norm() < 1e-12) {
            centre = v;
        }
    }
    ASSERT_NE(centre, invalid_index);
    ASSERT_EQ(t.valence(centre), 4);
    const Level level = refine_catmull_clark(t);
    const Index V = t.num_vertices(), F = t.num_faces();

    // The paper's order: centre, the 4 edge neighbours counter-clockwise, then the 4
    // diagonal vertices, diagonal k lying in the face between edge neighbours k and k+1.
    // Rows: the centre's vertex point, the 4 edge points, the 4 face points (same order).
    const auto edges = t.vertex_edges(centre);
    const auto faces = t.vertex_faces(centre);
    std::array<Index, 9> parent{};
    std::array<Index, 9> child{};
    parent[0] = centre;
    child[0] = centre;
    for (std::size_t k = 0; k < 4; ++k) {
        parent[1 + k] = t.other_vertex(edges[k], centre);
        child[1 + k] = V + F + edges[k];
        child[5 + k] = V + faces[k];
        const auto corners = t.face_vertices(faces[k]);
        const auto c = static_cast<std::size_t>(t.vertex_face_corners(centre)[k]);
        parent[5 + k] = corners[(c + 2) % 4];
    }
    // iga-with-catmull-clark §3, the matrix S (times 64) as printed.
    const int printed[9][9] = {
        {36, 6, 6, 6, 6, 1, 1, 1, 1},    {24, 24, 4, 0, 4, 4, 0, 0, 4},   {24, 4, 24, 4, 0, 4, 4, 0, 0},
        {24, 0, 4, 24, 4, 0, 4, 4, 0},   {24, 4, 0, 4, 24, 0, 0, 4, 4},   {16, 16, 16, 0, 0, 16, 0, 0, 0},
        {16, 0, 16, 16, 0, 0, 16, 0, 0}, {16, 0, 0, 16, 16, 0, 0, 16, 0}, {16, 16, 0, 0, 16, 0, 0, 0, 16}};
    Eigen::Matrix<double, 9, 9> S;
    for (int i = 0; i < 9; ++i) {
        double row_sum = 0.0;
        for (int j = 0; j < 9; ++j) {
            S(i, j) = level.S0.coeff(child[static_cast<std::size_t>(i)], parent[static_cast<std::size_t>(j)]);
            row_sum += S(i, j);
            EXPECT_EQ(S(i, j), printed[i][j] / 64.0) << "S(" << i << ", " << j << ")";
        }
        // The one-ring is closed: nothing outside it contributes.
        EXPECT_EQ(row_sum, 1.0);
    }
    // §3: F_4 M F_4^* = diag(1/2, 3/8, 1/4, 3/8) for the block M = S(1..4, 1..4).
    const Eigen::Matrix4d M = S.block<4, 4>(1, 1);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(M);
    const Eigen::Vector4d expected(1.0 / 4.0, 3.0 / 8.0, 3.0 / 8.0, 1.0 / 2.0);
    EXPECT_LT((solver.eigenvalues() - expected).cwiseAbs().maxCoeff(), 1e-15);
    // §4: rows sum to one, so 1 is an eigenvalue of S (eigenvector of ones) and the dominant one.
    const Eigen::EigenSolver<Eigen::Matrix<double, 9, 9>> full(S);
    double largest = 0.0;
    for (int i = 0; i < 9; ++i) {
        largest = std::max(largest, std::abs(full.eigenvalues()(i)));
    }
    EXPECT_NEAR(largest, 1.0, 1e-14);
}

}  // namespace
}  // namespace limsurf::test
