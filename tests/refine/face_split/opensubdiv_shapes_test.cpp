// Peer test on OpenSubdiv's own regression shapes (tests/data/opensubdiv_shapes, 122 files extracted
// from OpenSubdiv's regression/shapes by tools/extract_opensubdiv_shapes.py):
//   - limsurf reads every shape it accepts as OpenSubdiv's shape reader reads it (a reader in the test
//     support that shares no code with limsurf's: vertices, faces, creases, corners, holes, the
//     boundary, creasing and triangle hints; catmark_nonman_bareverts' isolated vertices are dropped, as
//     limsurf drops them everywhere), and refuses the 18 it does not accept — 13 not 2-manifold, 5 with
//     hierarchical edits — with the reason in the message;
//   - limsurf's refinement equals Far's on every accepted shape, with the file's options, over 3 levels
//     (2 for the largest): positions to 1e-12 of the bounding-box diagonal, faces and edge sharpness
//     exactly (compare_with_opensubdiv). Shapes without an `interpolateboundary` tag run under both
//     OpenSubdiv's regression default (edge-only) and limsurf's (edge-and-corner).
// Sharpness is handed to both sides as float: OpenSubdiv stores it as float, so a file's "0.1" means
// 0.1f to Far (limsurf keeps the double the text says; semi-sharp blends differ by ~1e-8 otherwise).
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "refine/face_split/opensubdiv_compare.h"
#include "support/opensubdiv_shapes.h"

namespace limsurf::test {
namespace {

std::vector<OpenSubdivShape> shapes(bool accepted) {
    std::vector<OpenSubdivShape> out;
    for (auto& s : opensubdiv_shapes()) {
        if (s.refusal.empty() == accepted) {
            out.push_back(std::move(s));
        }
    }
    return out;
}

std::string shape_name(const ::testing::TestParamInfo<OpenSubdivShape>& info) {
    return info.param.name;
}

TEST(OpenSubdivShapes, AllAreExtracted) {
    // OpenSubdiv's regression/shapes/all.h (commit 7d0ab55) lists 122 shapes: 4 bilinear, 87 catmark, 31 loop.
    int count[3] = {0, 0, 0};
    for (const auto& s : opensubdiv_shapes()) {
        ++count[s.scheme == SchemeKind::Bilinear ? 0 : s.scheme == SchemeKind::CatmullClark ? 1 : 2];
    }
    EXPECT_EQ(count[0], 4);
    EXPECT_EQ(count[1], 87);
    EXPECT_EQ(count[2], 31);
    EXPECT_EQ(shapes(false).size(), 18U);
}

class RefusedShape : public ::testing::TestWithParam<OpenSubdivShape> {};

TEST_P(RefusedShape, IsRefusedWithItsReason) {
    try {
        (void)read_mesh(GetParam().path);
        FAIL() << GetParam().name << " was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(GetParam().refusal), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(GetParam().name + ".obj:"), std::string::npos) << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(OpenSubdivShapes, RefusedShape, ::testing::ValuesIn(shapes(false)), shape_name);

class AcceptedShape : public ::testing::TestWithParam<OpenSubdivShape> {};

TEST_P(AcceptedShape, IsReadAsOpenSubdivReadsIt) {
    const OpenSubdivShapeFile file = read_opensubdiv_shape(GetParam().path);
    const BuildResult built = read_mesh(GetParam().path);
    const Topology& t = built.mesh.topology();
    // File vertex -> mesh vertex (isolated vertices are dropped; the others keep their order).
    std::vector<Index> to_mesh(file.positions.size(), invalid_index);
    ASSERT_EQ(built.source_vertex.size(), static_cast<std::size_t>(t.num_vertices()));
    for (Index v = 0; v < t.num_vertices(); ++v) {
        const Index source = built.source_vertex[static_cast<std::size_t>(v)];
        to_mesh.at(static_cast<std::size_t>(source)) = v;
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(built.mesh.positions()(v, k), file.positions[static_cast<std::size_t>(source)][k])
                << "vertex " << v;
        }
    }
    const auto mesh_vertex = [&](Index file_vertex) { return to_mesh.at(static_cast<std::size_t>(file_vertex)); };
    ASSERT_EQ(t.num_faces(), static_cast<Index>(file.faces.size()));
    for (Index f = 0; f < t.num_faces(); ++f) {
        std::vector<Index> expected;
        for (const Index v : file.faces[static_cast<std::size_t>(f)]) {
            expected.push_back(mesh_vertex(v));
        }
        const auto ours = t.face_vertices(f);
        ASSERT_EQ(std::vector<Index>(ours.begin(), ours.end()), expected) << "face " << f;
    }
    for (const auto& c : file.creases) {
        const Index e = t.find_edge(mesh_vertex(c.v0), mesh_vertex(c.v1));
        ASSERT_NE(e, invalid_index) << "crease " << c.v0 << " " << c.v1;
        EXPECT_EQ(t.edge_sharpness(e), c.sharpness) << "crease " << c.v0 << " " << c.v1;
    }
    for (const auto& [v, s] : file.corners) {
        EXPECT_EQ(t.vertex_sharpness(mesh_vertex(v)), s) << "corner " << v;
    }
    Index holes = 0;
    for (Index f = 0; f < t.num_faces(); ++f) {
        holes += t.is_hole(f) ? 1 : 0;
    }
    EXPECT_EQ(holes, static_cast<Index>(file.holes.size()));
    for (const Index f : file.holes) {
        EXPECT_TRUE(t.is_hole(f)) << "hole " << f;
    }
    EXPECT_EQ(built.mesh.hints().boundary, file.hints.boundary);
    EXPECT_EQ(built.mesh.hints().creasing, file.hints.creasing);
    EXPECT_EQ(built.mesh.hints().triangles, file.hints.triangles);
}

TEST_P(AcceptedShape, RefinesAsFar) {
    const BuildResult built = read_mesh(GetParam().path);
    const Topology t = with_float_sharpness(built.mesh.topology());
    const SchemeHints& hints = built.mesh.hints();
    SchemeOptions options;
    options.creasing = hints.creasing.value_or(options.creasing);
    options.triangles = hints.triangles.value_or(options.triangles);
    std::vector<BoundaryInterpolation> boundaries{BoundaryInterpolation::EdgeOnly,
                                                  BoundaryInterpolation::EdgeAndCorner};
    bool has_boundary = false;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        has_boundary = has_boundary || t.is_boundary_vertex(v);
    }
    if (hints.boundary || !has_boundary) {
        boundaries = {hints.boundary.value_or(options.boundary)};
    }
    // Three levels; two for the largest shapes (the suite stays fast).
    const int levels = t.num_faces() > 2000 ? 2 : 3;
    for (const auto boundary : boundaries) {
        options.boundary = boundary;
        compare_with_opensubdiv(t, built.mesh.positions(), GetParam().scheme, options,
                                GetParam().name + " " + to_string(boundary), levels);
    }
}

INSTANTIATE_TEST_SUITE_P(OpenSubdivShapes, AcceptedShape, ::testing::ValuesIn(shapes(true)), shape_name);

}  // namespace
}  // namespace limsurf::test
