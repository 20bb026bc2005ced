// Published facts about Doo–Sabin limit surfaces, checked on the exact evaluator
// (src/limsurf/limit/doo_sabin_limit.h):
//   - the volume enclosed by the Doo–Sabin surface of the unit cube is 6241/9920
//     (Hakenberg, "volume via trilinear forms", Figure 1 and the Doo–Sabin section);
//   - a Doo–Sabin step keeps every face centroid (the face mask is a circulant whose
//     columns sum to 1; Doo & Sabin 1978): the limit point of a face centre is the
//     centroid of the face, and the limit point of a control vertex is the centroid of
//     its level-1 V-face;
//   - planar control meshes give planar limits with the normal of the plane.
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/doo_sabin_limit.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

using detail::DooSabinLimit;
using Rows6 = Eigen::Matrix<double, 6, 3>;

struct Loaded {
    Topology topology;
    Points X;
    double scale = 1.0;
};

Loaded load(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    Loaded m{built.mesh.topology(), built.mesh.positions(), 1.0};
    m.scale = (m.X.colwise().maxCoeff() - m.X.colwise().minCoeff()).norm();
    return m;
}

Rows6 eval(const DooSabinLimit& ds, const Points& X, Index p, double u, double v) {
    std::vector<Index> support;
    Eigen::Matrix<double, 6, Eigen::Dynamic> w;
    ds.evaluate(p, u, v, support, w);
    Rows6 r = Rows6::Zero();
    for (std::size_t i = 0; i < support.size(); ++i) {
        r += w.col(static_cast<Index>(i)) * X.row(support[i]);
    }
    return r;
}

/// ∫ p · (p_u × p_v) over the square [x0, x0 + h] × [y0, y0 + h] of ptex face @p p, where
/// the surface is one biquadratic piece: the integrand has degree 5 in each parameter, so
/// 3 × 3 Gauss–Legendre points are exact.
double gauss_square(const DooSabinLimit& ds, const Points& X, Index p, double x0, double y0, double h) {
    const double a = std::sqrt(0.6) / 2;
    const double nodes[3] = {0.5 - a, 0.5, 0.5 + a};
    const double weights[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const Rows6 r = eval(ds, X, p, x0 + h * nodes[i], y0 + h * nodes[j]);
            const Eigen::Vector3d pos = r.row(0);
            sum += weights[i] * weights[j] * pos.dot(Eigen::Vector3d(r.row(1)).cross(Eigen::Vector3d(r.row(2))));
        }
    }
    return sum * h * h;
}

/// The same over a square of size h with corner (cx, cy) at an extraordinary point and
/// extending in directions (sx, sy): the nested patches are squares of size h/2, h/4, …
/// (three polynomial pieces per ring); the rings below 2^-45 are negligible.
double corner_square(const DooSabinLimit& ds, const Points& X, Index p, double cx, double cy, double sx, double sy,
                     double h) {
    double sum = 0.0;
    for (int level = 0; level < 45; ++level) {
        const double g = h / 2;
        for (const auto& [i, j] : {std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 1}}) {
            const double x0 = sx > 0 ? cx + i * g : cx - (i + 1) * g;
            const double y0 = sy > 0 ? cy + j * g : cy - (j + 1) * g;
            sum += gauss_square(ds, X, p, x0, y0, g);
        }
        h = g;
    }
    return sum;
}

TEST(DooSabinLimitPublished, UnitCubeEnclosesVolume6241Over9920) {
    const Loaded cube = load("cube");
    ASSERT_NEAR(cube.scale, std::sqrt(3.0), 1e-15);  // unit cube
    const DooSabinLimit ds(cube.topology);
    // Every face is a quad and every vertex has valence 3: the quadrant at each corner of
    // a face is a stationary patch with the extraordinary point at that corner.
    double volume = 0.0;
    for (Index p = 0; p < ds.num_ptex_faces(); ++p) {
        ASSERT_EQ(ds.ptex_face(p).corner, -1);
        volume += corner_square(ds, cube.X, p, 0, 0, 1, 1, 0.5);
        volume += corner_square(ds, cube.X, p, 1, 0, -1, 1, 0.5);
        volume += corner_square(ds, cube.X, p, 1, 1, -1, -1, 0.5);
        volume += corner_square(ds, cube.X, p, 0, 1, 1, -1, 0.5);
    }
    volume /= 3.0;
    EXPECT_NEAR(volume, 6241.0 / 9920.0, 1e-14);
}

class DooSabinLimitCentroids : public ::testing::TestWithParam<std::string> {};

TEST_P(DooSabinLimitCentroids, FaceCentresAndVerticesGoToCentroids) {
    const Loaded m = load(GetParam());
    const Topology& t = m.topology;
    const DooSabinLimit ds(t);
    for (Index f = 0; f < t.num_faces(); ++f) {
        Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
        for (Index v : t.face_vertices(f)) {
            centroid += m.X.row(v);
        }
        centroid /= static_cast<double>(t.face_degree(f));
        const Index first = ds.first_ptex_face(f);
        if (t.face_degree(f) == 4) {
            EXPECT_LT((eval(ds, m.X, first, 0.5, 0.5).row(0) - centroid).norm(), 1e-12 * m.scale) << "face " << f;
            continue;
        }
        for (Index k = 0; k < t.face_degree(f); ++k) {
            EXPECT_LT((eval(ds, m.X, first + k, 1.0, 1.0).row(0) - centroid).norm(), 1e-12 * m.scale)
                << "face " << f << " sub-face " << k;
        }
    }
    // A control vertex goes to the centroid of its level-1 V-face, whose centroid no later step moves.
    const Level level = refine_doo_sabin(t);
    const Points X1 = level.S0 * m.X;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        Eigen::RowVector3d centroid = Eigen::RowVector3d::Zero();
        const auto faces = t.vertex_faces(v);
        const auto corners = t.vertex_face_corners(v);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            centroid += X1.row(t.face_offset(faces[i]) + corners[i]);
        }
        centroid /= static_cast<double>(faces.size());
        const Index f = faces[0];
        const Index k = corners[0];
        const Index first = ds.first_ptex_face(f);
        static const double square[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        const Rows6 r = t.face_degree(f) == 4 ? eval(ds, m.X, first, square[k][0], square[k][1])
                                              : eval(ds, m.X, first + k, 0.0, 0.0);
        EXPECT_LT((r.row(0) - centroid).norm(), 1e-12 * m.scale) << "vertex " << v;
    }
}

INSTANTIATE_TEST_SUITE_P(ClosedMeshes, DooSabinLimitCentroids,
                         ::testing::Values("cube", "tetrahedron", "octahedron", "icosahedron", "dodecahedron",
                                           "quad_torus", "cube_ngons", "prism_hex", "tetra_and_cube", "genus2",
                                           "quad_valence_5", "tri_valence_7"));

TEST(DooSabinLimitPublished, PlanarMeshGivesPlanarLimitWithThePlaneNormal) {
    const Loaded disk = load("disk_ev5_quads");
    ASSERT_LT(disk.X.col(2).cwiseAbs().maxCoeff(), 1e-15);
    const DooSabinLimit ds(disk.topology);
    int evaluated = 0;
    for (Index p = 0; p < ds.num_ptex_faces(); ++p) {
        if (!ds.has_limit_surface(p)) {
            continue;
        }
        // The orientation of the control face: its (unnormalised) polygon normal.
        const auto fv = disk.topology.face_vertices(ds.ptex_face(p).control_face);
        Eigen::Vector3d area = Eigen::Vector3d::Zero();
        for (std::size_t i = 0; i < fv.size(); ++i) {
            area += Eigen::Vector3d(disk.X.row(fv[i])).cross(Eigen::Vector3d(disk.X.row(fv[(i + 1) % fv.size()])));
        }
        const Eigen::Vector3d plane = area.normalized();
        for (double u : {0.0, 0.2, 0.5, 0.77, 1.0}) {
            for (double v : {0.0, 0.31, 0.5, 0.9, 1.0}) {
                const Rows6 r = eval(ds, disk.X, p, u, v);
                ++evaluated;
                EXPECT_LT(r.col(2).cwiseAbs().maxCoeff(), 1e-14 * disk.scale) << "ptex " << p;
                const Eigen::Vector3d n = Eigen::Vector3d(r.row(1)).cross(Eigen::Vector3d(r.row(2))).normalized();
                EXPECT_LT((n - plane).norm(), 1e-12) << "ptex " << p << " at " << u << ", " << v;
            }
        }
    }
    EXPECT_GT(evaluated, 0);
}

}  // namespace
}  // namespace limsurf::test
