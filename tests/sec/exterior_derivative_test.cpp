// The exterior derivatives d0, d1 of every bundled mesh: their entries follow the documented
// orientation convention, d1·d0 = 0 exactly, and their ranks give the Betti numbers the
// construction of each mesh fixes (b0 = components; b1 = 2g + boundary loops − 1 and b2 = 0 for a
// connected mesh with boundary; b1 = 2g and b2 = components for closed meshes) — the discrete de
// Rham complex sees the topology.
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/sec/exterior_derivative.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

class EveryMesh : public ::testing::TestWithParam<test::BundledMesh> {};

Eigen::Index rank(const SparseMatrix& m) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(Eigen::MatrixXd(m.toDense()));
    return lu.rank();
}

TEST_P(EveryMesh, EntriesFollowTheOrientationConvention) {
    const BuildResult built = read_mesh(GetParam().path);
    const Topology& t = built.mesh.topology();
    const SparseMatrix d0 = exterior_derivative_0(t);
    const SparseMatrix d1 = exterior_derivative_1(t);
    ASSERT_EQ(d0.rows(), t.num_edges());
    ASSERT_EQ(d0.cols(), t.num_vertices());
    ASSERT_EQ(d1.rows(), t.num_faces());
    ASSERT_EQ(d1.cols(), t.num_edges());
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ends = t.edge_vertices(e);
        EXPECT_EQ(d0.coeff(e, ends[0]), -1.0);
        EXPECT_EQ(d0.coeff(e, ends[1]), 1.0);
    }
    EXPECT_EQ(d0.nonZeros(), 2 * t.num_edges());
    EXPECT_EQ(d1.nonZeros(), t.num_corners());
    // Walking face f counter-clockwise from corner k to k+1 follows edge e when the head is higher.
    for (Index f = 0; f < t.num_faces(); ++f) {
        const auto verts = t.face_vertices(f);
        const auto edges = t.face_edges(f);
        for (std::size_t k = 0; k < verts.size(); ++k) {
            const Index next = verts[(k + 1) % verts.size()];
            EXPECT_EQ(d1.coeff(f, edges[k]), next > verts[k] ? 1.0 : -1.0);
        }
    }
    // An interior edge is walked once each way by its two faces: its column of d1 sums to 0.
    const Eigen::RowVectorXd column_sums = Eigen::RowVectorXd::Ones(t.num_faces()) * d1;
    for (Index e = 0; e < t.num_edges(); ++e) {
        if (!t.is_boundary_edge(e)) {
            EXPECT_EQ(column_sums(e), 0.0) << e;
        }
    }
}

TEST_P(EveryMesh, D1D0IsZero) {
    const BuildResult built = read_mesh(GetParam().path);
    const SparseMatrix product =
        exterior_derivative_1(built.mesh.topology()) * exterior_derivative_0(built.mesh.topology());
    EXPECT_EQ(SparseMatrix(product.pruned()).nonZeros(), 0);
}

TEST_P(EveryMesh, RanksGiveTheBettiNumbers) {
    const test::BundledMesh& mesh = GetParam();
    const BuildResult built = read_mesh(mesh.path);
    const Topology& t = built.mesh.topology();
    if (t.num_edges() > 3000) {
        GTEST_SKIP() << "dense ranks only on small meshes";
    }
    const Eigen::Index r0 = rank(exterior_derivative_0(t));
    const Eigen::Index r1 = rank(exterior_derivative_1(t));
    const Eigen::Index b0 = t.num_vertices() - r0;
    const Eigen::Index b1 = t.num_edges() - r0 - r1;
    const Eigen::Index b2 = t.num_faces() - r1;
    EXPECT_EQ(b0, mesh.num_components);
    if (mesh.closed) {
        EXPECT_EQ(b1, 2 * mesh.genus);
        EXPECT_EQ(b2, mesh.num_components);
    } else if (mesh.num_components == 1) {
        EXPECT_EQ(b1, 2 * mesh.genus + mesh.num_boundary_loops - 1);
        EXPECT_EQ(b2, 0);
    }
    EXPECT_EQ(b0 - b1 + b2, mesh.euler_characteristic);
}

INSTANTIATE_TEST_SUITE_P(Sec, EveryMesh, ::testing::ValuesIn(test::bundled_meshes()),
                         [](const ::testing::TestParamInfo<test::BundledMesh>& param) { return param.param.name; });

}  // namespace
}  // namespace limsurf
