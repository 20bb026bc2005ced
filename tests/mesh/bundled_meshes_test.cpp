// Every bundled mesh, read through the library, against the analytic values
// that tools/make_meshes.py recorded from each construction.
#include <algorithm>
#include <map>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/statistics.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

class BundledMeshes : public ::testing::TestWithParam<test::BundledMesh> {};

TEST_P(BundledMeshes, TopologyMatchesTheConstruction) {
    const test::BundledMesh& expected = GetParam();
    const BuildResult result = read_mesh(expected.path);
    EXPECT_TRUE(result.report.issues.empty()) << result.report.summary();
    const Topology& t = result.mesh.topology();
    EXPECT_EQ(t.num_vertices(), expected.num_vertices);
    EXPECT_EQ(t.num_edges(), expected.num_edges);
    EXPECT_EQ(t.num_faces(), expected.num_faces);
    EXPECT_EQ(t.euler_characteristic(), expected.euler_characteristic);
    EXPECT_EQ(t.genus(), expected.genus);
    EXPECT_EQ(t.num_boundary_loops(), expected.num_boundary_loops);
    EXPECT_EQ(t.num_components(), expected.num_components);
    EXPECT_EQ(t.is_closed(), expected.closed);
    EXPECT_EQ(t.all_faces_have_degree(3), expected.triangles_only);
    EXPECT_EQ(t.all_faces_have_degree(4), expected.quads_only);
}

/// Meshes of one face degree (triangles or quads), where "regular valence" has a meaning.
class SingleDegreeMeshes : public BundledMeshes {};

TEST_P(SingleDegreeMeshes, ExtraordinaryValencesMatch) {
    const test::BundledMesh& expected = GetParam();
    const BuildResult result = read_mesh(expected.path);
    const Topology& t = result.mesh.topology();
    const Index regular = expected.quads_only ? 4 : 6;
    std::vector<int> irregular;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (!t.is_boundary_vertex(v) && t.valence(v) != regular) {
            irregular.push_back(t.valence(v));
        }
    }
    std::sort(irregular.begin(), irregular.end());
    EXPECT_EQ(irregular, expected.extraordinary_valences);
}

TEST_P(BundledMeshes, OneRingsAreOrientedWithTheFaces) {
    // Around every vertex, the faces turn the same way as the outward
    // normals: the one-ring edge directions rotate counter-clockwise about
    // the vertex normal (sum of the incident faces' vector areas).
    const BuildResult result = read_mesh(GetParam().path);
    const Topology& t = result.mesh.topology();
    const Points& x = result.mesh.positions();
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const auto faces = t.vertex_faces(v);
        const auto edges = t.vertex_edges(v);
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const Eigen::Vector3d a = (x.row(t.other_vertex(edges[i], v)) - x.row(v)).transpose();
            const Eigen::Vector3d b = (x.row(t.other_vertex(edges[(i + 1) % edges.size()], v)) - x.row(v)).transpose();
            Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell normal of face i
            const auto corners = t.face_vertices(faces[i]);
            for (std::size_t k = 0; k < corners.size(); ++k) {
                normal += x.row(corners[k]).cross(x.row(corners[(k + 1) % corners.size()])).transpose();
            }
            EXPECT_GT(a.cross(b).dot(normal), 0.0) << "vertex " << v << " face " << faces[i];
        }
    }
}

std::string mesh_name(const ::testing::TestParamInfo<test::BundledMesh>& param) {
    return param.param.name;
}

std::vector<test::BundledMesh> single_degree_meshes() {
    auto meshes = test::triangle_meshes();
    const auto quads = test::quad_meshes();
    meshes.insert(meshes.end(), quads.begin(), quads.end());
    return meshes;
}

INSTANTIATE_TEST_SUITE_P(Zoo, BundledMeshes, ::testing::ValuesIn(test::bundled_meshes()), mesh_name);
INSTANTIATE_TEST_SUITE_P(Zoo, SingleDegreeMeshes, ::testing::ValuesIn(single_degree_meshes()), mesh_name);

TEST(MeshStatistics, HistogramsOfTheCubeWithACutCorner) {
    const ControlMesh mesh = read_mesh(test::find_bundled("cube_ngons").path).mesh;
    const MeshStatistics stats = statistics(mesh);
    EXPECT_EQ(stats.face_degrees, (std::map<Index, Index>{{3, 1}, {4, 3}, {5, 3}}));
    EXPECT_EQ(stats.interior_valences, (std::map<Index, Index>{{3, 10}}));
    EXPECT_TRUE(stats.boundary_valences.empty());
    EXPECT_TRUE(stats.boundary_loop_lengths.empty());
}

TEST(MeshStatistics, SharpnessOfTheCreasedCube) {
    // tools/make_meshes.py tags 4 top edges at 10 (infinitely sharp), one
    // vertical edge at 2.5 and one bottom vertex as a corner.
    const BuildResult result = read_mesh(test::find_bundled("cube_creases").path);
    const Topology& t = result.mesh.topology();
    const SharpnessSummary s = statistics(result.mesh).sharpness;
    EXPECT_EQ(s.num_sharp_edges, 5);
    EXPECT_EQ(s.num_infinitely_sharp_edges, 4);
    EXPECT_DOUBLE_EQ(s.max_semi_sharp_edge, 2.5);
    EXPECT_EQ(s.num_sharp_vertices, 1);
    EXPECT_EQ(s.num_infinitely_sharp_vertices, 1);
    EXPECT_EQ(s.num_holes, 0);
    // The infinitely sharp edges are those of the face whose vertices all have z = +0.5.
    const Points& x = result.mesh.positions();
    for (Index e = 0; e < t.num_edges(); ++e) {
        const auto ends = t.edge_vertices(e);
        const bool top = x(ends[0], 2) > 0 && x(ends[1], 2) > 0;
        EXPECT_EQ(t.edge_sharpness(e) >= infinite_sharpness, top) << "edge " << e;
    }
}

TEST(MeshStatistics, BoundaryOfTheAnnulus) {
    const ControlMesh mesh = read_mesh(test::find_bundled("annulus").path).mesh;
    const MeshStatistics stats = statistics(mesh);
    EXPECT_EQ(stats.boundary_loop_lengths.size(), 2U);
    EXPECT_EQ(stats.bounding_box_min.z(), 0.0);
    EXPECT_EQ(stats.bounding_box_max.z(), 0.0);
}

}  // namespace
}  // namespace limsurf
