#include <limits>

#include <gtest/gtest.h>

#include "limsurf/mesh/control_mesh.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

PolygonSoup cube_soup_with_isolated_vertex() {
    PolygonSoup soup;
    const Points cube = test::cube_positions();
    soup.positions.resize(9, 3);
    soup.positions.topRows(4) = cube.topRows(4);
    soup.positions.row(4) << 5, 5, 5;  // isolated
    soup.positions.bottomRows(4) = cube.bottomRows(4);
    soup.source.file = "c.obj";
    soup.source.vertex_lines = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    for (auto face : test::cube_faces()) {
        for (Index& v : face) {
            v = v >= 4 ? v + 1 : v;
        }
        soup.add_face(face, 20);
    }
    soup.sharpness.corners.push_back({8, 10.0, 30});
    soup.sharpness.creases.push_back({0, 1, 2.0, 31});
    soup.hints.boundary = BoundaryInterpolation::EdgeOnly;
    return soup;
}

TEST(ControlMesh, DropsIsolatedVerticesAndRenumbersTags) {
    const BuildResult result = build_control_mesh(cube_soup_with_isolated_vertex());
    EXPECT_EQ(result.mesh.num_vertices(), 8);
    EXPECT_EQ(result.source_vertex, (std::vector<Index>{0, 1, 2, 3, 5, 6, 7, 8}));
    ASSERT_EQ(result.report.issues.size(), 1U);
    EXPECT_EQ(result.report.issues[0].to_string(), "c.obj:5: vertex 4 is in no face (isolated); dropped");
    EXPECT_TRUE(result.mesh.positions().isApprox(test::cube_positions()));
    EXPECT_DOUBLE_EQ(result.mesh.topology().vertex_sharpness(7), 10.0);
    EXPECT_DOUBLE_EQ(result.mesh.topology().edge_sharpness(result.mesh.topology().find_edge(0, 1)), 2.0);
    EXPECT_EQ(result.mesh.hints().boundary, BoundaryInterpolation::EdgeOnly);
}

TEST(ControlMesh, IsolatedVerticesCanBeRefused) {
    try {
        (void)build_control_mesh(cube_soup_with_isolated_vertex(), {.isolated_vertices = IsolatedVertices::Error});
        FAIL() << "expected an error";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "c.obj:5: vertex 4 is in no face (isolated)");
    }
}

TEST(ControlMesh, RefusesWrongShapesAndNonFinitePositions) {
    const Topology t = Topology::from_polygons(8, test::cube_faces());
    EXPECT_THROW(ControlMesh(t, Points::Zero(7, 3)), InputError);
    Points x = test::cube_positions();
    x(2, 0) = std::numeric_limits<double>::infinity();
    try {
        ControlMesh mesh(t, x);
        FAIL() << "expected an error";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "vertex 2 has a non-finite coordinate (inf, 1, 0)");
    }
}

TEST(ControlMesh, RoundTripsThroughPolygonSoup) {
    const BuildResult first = build_control_mesh(cube_soup_with_isolated_vertex());
    const PolygonSoup soup = to_polygon_soup(first.mesh);
    const BuildResult second = build_control_mesh(soup);
    EXPECT_TRUE(second.report.issues.empty());
    EXPECT_EQ(second.mesh.positions(), first.mesh.positions());
    const auto a = first.mesh.topology().all_face_vertices();
    const auto b = second.mesh.topology().all_face_vertices();
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    EXPECT_EQ(second.mesh.topology().sharpness_tags().creases.size(), 1U);
    EXPECT_EQ(second.mesh.hints().boundary, BoundaryInterpolation::EdgeOnly);
}

}  // namespace
}  // namespace limsurf
