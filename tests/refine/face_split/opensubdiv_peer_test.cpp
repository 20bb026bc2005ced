// Peer test: OpenSubdiv Far refines the bundled meshes with the same options and tags;
// compare_with_opensubdiv (opensubdiv_compare.h) checks positions to 1e-12 of the
// bounding-box diagonal over 3 levels, child faces and child edge sharpness.
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/refine/refine.h"
#include "refine/face_split/face_split_helpers.h"
#include "refine/face_split/opensubdiv_compare.h"

namespace limsurf::test {
namespace {

std::vector<SchemeOptions> boundary_options() {
    return {{BoundaryInterpolation::EdgeAndCorner, CreasingMethod::Uniform, TriangleSubdivision::CatmullClark},
            {BoundaryInterpolation::EdgeOnly, CreasingMethod::Uniform, TriangleSubdivision::CatmullClark},
            {BoundaryInterpolation::None, CreasingMethod::Uniform, TriangleSubdivision::CatmullClark}};
}

TEST(OpenSubdivPeer, CatmullClarkBundledMeshes) {
    for (const char* name : {"cube_ngons", "dodecahedron", "prism_hex", "pentagon", "tetrahedron", "icosahedron",
                             "tri_grid", "quad_grid", "disk_ev5_quads", "annulus", "cylinder_open", "single_quad",
                             "cube_creases", "genus2", "quad_valence_7", "hexagon_fan", "single_triangle"}) {
        const auto mesh = load_bundled(name);
        for (const auto& options : boundary_options()) {
            compare_with_opensubdiv(mesh.topology, mesh.positions, SchemeKind::CatmullClark, options,
                                    std::string(name) + " " + to_string(options.boundary));
        }
    }
}

TEST(OpenSubdivPeer, CatmullClarkSmoothTriangles) {
    for (const char* name : {"cube_ngons", "tetrahedron", "icosahedron", "tri_grid", "disk_ev7_tris"}) {
        const auto mesh = load_bundled(name);
        const SchemeOptions options{BoundaryInterpolation::EdgeAndCorner, CreasingMethod::Uniform,
                                    TriangleSubdivision::Smooth};
        compare_with_opensubdiv(mesh.topology, mesh.positions, SchemeKind::CatmullClark, options, name);
    }
}

/// Semi-sharp and infinitely sharp creases along paths, a semi-sharp corner, float-exact values.
SharpnessTags test_creases(const Topology& t, bool triangles) {
    SharpnessTags tags;
    const double values[] = {0.5, 1.25, 2.5, 3.0, 10.0, 1.25, 0.5, 2.5};
    // A path through the mesh: follow the first edge out of vertex 0, several times.
    Index v = 0;
    Index previous_edge = invalid_index;
    for (const double s : values) {
        const auto edges = t.vertex_edges(v);
        Index e = edges[0] == previous_edge ? edges[edges.size() / 2] : edges[0];
        if (!triangles && edges.size() == 4 && previous_edge != invalid_index) {
            // continue straight on a regular vertex
            for (std::size_t i = 0; i < 4; ++i) {
                if (edges[i] == previous_edge) {
                    e = edges[(i + 2) % 4];
                }
            }
        }
        const Index w = t.other_vertex(e, v);
        bool seen = false;
        for (const auto& c : tags.creases) {
            seen = seen || (c.v0 == v && c.v1 == w) || (c.v0 == w && c.v1 == v);
        }
        if (!seen) {
            tags.creases.push_back({v, w, s, 0});
        }
        previous_edge = e;
        v = w;
    }
    tags.corners.push_back({v, 1.25, 0});
    tags.corners.push_back({t.num_vertices() / 2, 0.5, 0});
    return tags;
}

TEST(OpenSubdivPeer, CatmullClarkCreasesUniformAndChaikin) {
    for (const char* name :
         {"quad_torus", "genus2", "sphere_quads", "cube_ngons", "disk_ev5_quads", "quad_grid", "cube_creases"}) {
        const auto mesh = load_bundled(name);
        SharpnessTags tags = test_creases(mesh.topology, false);
        if (std::string(name) == "cube_creases") {
            tags = mesh.topology.sharpness_tags();
        }
        const Topology t = with_tags(mesh.topology, tags);
        for (const auto creasing : {CreasingMethod::Uniform, CreasingMethod::Chaikin}) {
            for (const auto boundary : {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly}) {
                const SchemeOptions options{boundary, creasing, TriangleSubdivision::CatmullClark};
                compare_with_opensubdiv(t, mesh.positions, SchemeKind::CatmullClark, options,
                                        std::string(name) + " " + to_string(creasing) + " " + to_string(boundary));
            }
        }
    }
}

// An edge or vertex tagged twice: OpenSubdiv's factory applies the tags in order, so the last one
// wins even when it is 0. Before, limsurf skipped a later 0 and kept the earlier sharpness.
TEST(OpenSubdivPeer, TheLastOfRepeatedTagsWins) {
    namespace Far = OpenSubdiv::Far;
    const auto mesh = load_bundled("quad_torus");  // closed: Far makes boundary edges sharp itself
    const Topology& plain = mesh.topology;
    const auto e0 = plain.edge_vertices(0);
    const auto e1 = plain.edge_vertices(5);
    SharpnessTags tags;
    tags.creases = {{e0[0], e0[1], 2.0, 0}, {e0[1], e0[0], 0.0, 0}, {e1[0], e1[1], 0.0, 0}, {e1[0], e1[1], 3.5, 0}};
    tags.corners = {{4, 10.0, 0}, {4, 0.0, 0}, {6, 1.0, 0}, {6, 2.5, 0}};
    const Topology ours = with_tags(plain, tags);

    const auto far = make_opensubdiv_refiner(plain, tags, SchemeKind::CatmullClark, SchemeOptions{});
    ASSERT_NE(far, nullptr);
    const Far::TopologyLevel& level = far->GetLevel(0);
    int sharp_edges = 0;
    for (Index e = 0; e < plain.num_edges(); ++e) {
        const auto ends = plain.edge_vertices(e);
        const Far::Index far_edge = level.FindEdge(ends[0], ends[1]);
        ASSERT_NE(far_edge, OpenSubdiv::Far::INDEX_INVALID);
        EXPECT_EQ(ours.edge_sharpness(e), level.GetEdgeSharpness(far_edge)) << "edge " << e;
        sharp_edges += ours.edge_sharpness(e) > 0.0 ? 1 : 0;
    }
    EXPECT_EQ(sharp_edges, 1);
    EXPECT_EQ(ours.edge_sharpness(5), 3.5);
    for (Index v = 0; v < plain.num_vertices(); ++v) {
        EXPECT_EQ(ours.vertex_sharpness(v), level.GetVertexSharpness(v)) << "vertex " << v;
    }
    EXPECT_EQ(ours.vertex_sharpness(4), 0.0);
    EXPECT_EQ(ours.vertex_sharpness(6), 2.5);

    // A later 0 that clears every tag leaves the mesh as smooth as one without tags.
    SharpnessTags cleared;
    cleared.creases = {{e0[0], e0[1], 2.0, 0}, {e0[0], e0[1], 0.0, 0}};
    EXPECT_FALSE(with_tags(plain, cleared).has_sharpness());
}

TEST(OpenSubdivPeer, LoopBundledMeshes) {
    for (const auto& bundled : triangle_meshes()) {
        const auto mesh = load_bundled(bundled.name);
        for (const auto& options : boundary_options()) {
            compare_with_opensubdiv(mesh.topology, mesh.positions, SchemeKind::Loop, options,
                                    bundled.name + " " + to_string(options.boundary));
        }
    }
}

TEST(OpenSubdivPeer, LoopCreasesUniformAndChaikin) {
    for (const char* name : {"tri_torus", "icosahedron", "sphere_tris", "tri_grid", "disk_ev7_tris"}) {
        const auto mesh = load_bundled(name);
        const Topology t = with_tags(mesh.topology, test_creases(mesh.topology, true));
        for (const auto creasing : {CreasingMethod::Uniform, CreasingMethod::Chaikin}) {
            const SchemeOptions options{BoundaryInterpolation::EdgeAndCorner, creasing,
                                        TriangleSubdivision::CatmullClark};
            compare_with_opensubdiv(t, mesh.positions, SchemeKind::Loop, options,
                                    std::string(name) + " " + to_string(creasing));
        }
    }
}

}  // namespace
}  // namespace limsurf::test
