#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/obj.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

std::string error_of(const auto& call) {
    try {
        call();
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

TEST(MeshIo, FormatFromTheExtension) {
    EXPECT_EQ(mesh_format_from_path("a/b.obj"), MeshFormat::Obj);
    EXPECT_EQ(mesh_format_from_path("B.OBJ"), MeshFormat::Obj);
    EXPECT_EQ(mesh_format_from_path("c.Off"), MeshFormat::Off);
    EXPECT_EQ(mesh_format_from_path("d.PLY"), MeshFormat::Ply);
    EXPECT_EQ(error_of([] { (void)mesh_format_from_path("dir/mesh.xyz"); }),
              "dir/mesh.xyz: unknown mesh format '.xyz' (expected .obj, .off or .ply)");
    EXPECT_EQ(error_of([] { (void)mesh_format_from_path("mesh"); }),
              "mesh: unknown mesh format '' (expected .obj, .off or .ply)");
}

TEST(MeshIo, UnreadableFilesNameThePathAndTheReason) {
    const fs::path missing = test::test_data_dir() / "io" / "no_such_file.obj";
    EXPECT_EQ(error_of([&] { (void)read_polygon_soup(missing); }),
              missing.string() + ": cannot open: No such file or directory");
    const fs::path dir = test::make_temp_dir("meshio") / "looks_like.ply";
    fs::create_directories(dir);
    EXPECT_EQ(error_of([&] { (void)read_polygon_soup(dir); }), dir.string() + ": cannot open: is a directory");
    fs::remove_all(dir.parent_path());
}

TEST(MeshIo, ReadPolygonSoupDispatches) {
    const fs::path io = test::test_data_dir() / "io";
    EXPECT_EQ(read_polygon_soup(io / "cube_forms.obj").num_faces(), 6);
    EXPECT_EQ(read_polygon_soup(io / "cube.off").num_faces(), 6);
    EXPECT_EQ(read_polygon_soup(io / "extra_props_le.ply").num_faces(), 5);
}

TEST(MeshIo, ReadMeshBuildsAControlMesh) {
    const BuildResult result = read_mesh(test::test_data_dir() / "io" / "cube.off");
    EXPECT_EQ(result.mesh.num_vertices(), 8);
    EXPECT_EQ(result.mesh.num_edges(), 12);
    EXPECT_EQ(result.mesh.num_faces(), 6);
}

TEST(MeshIo, WriteMeshWarnsAboutWhatTheFormatCannotStore) {
    const fs::path dir = test::make_temp_dir("meshio");
    PolygonSoup soup = read_obj(test::test_data_dir() / "io" / "shape_tags.obj");
    soup.sharpness.holes.clear();
    soup.hints = {};
    EXPECT_TRUE(write_mesh(dir / "a.obj", soup).empty());
    EXPECT_EQ(write_mesh(dir / "a.off", soup),
              std::vector<std::string>{"OFF cannot store subdivision tags: 3 creases, 3 corners dropped"});
    soup.sharpness.corners.resize(1);
    soup.hints.creasing = CreasingMethod::Chaikin;
    soup.sharpness.holes.push_back({2, 0});
    EXPECT_EQ(write_mesh(dir / "a.ply", soup, {.ply_encoding = PlyEncoding::BinaryBigEndian}),
              std::vector<std::string>{
                  "PLY cannot store subdivision tags: 3 creases, 1 corner, 1 hole, 1 scheme hint dropped"});
    const PolygonSoup off = read_polygon_soup(dir / "a.off");
    const PolygonSoup ply = read_polygon_soup(dir / "a.ply");
    EXPECT_EQ(off.positions, soup.positions);
    EXPECT_EQ(ply.positions, soup.positions);
    EXPECT_EQ(ply.face_vertices, soup.face_vertices);
    EXPECT_EQ(read_polygon_soup(dir / "a.obj").sharpness.corners.size(), 3U);
    EXPECT_EQ(error_of([&] { (void)write_mesh(dir / "a.stl", soup); }),
              (dir / "a.stl").string() + ": unknown mesh format '.stl' (expected .obj, .off or .ply)");
    fs::remove_all(dir);
}

TEST(MeshIo, WriteControlMesh) {
    const fs::path dir = test::make_temp_dir("meshio");
    const BuildResult built = read_mesh(test::test_data_dir() / "io" / "shape_tags.obj");
    EXPECT_TRUE(write_mesh(dir / "m.obj", built.mesh).empty());
    const BuildResult back = read_mesh(dir / "m.obj");
    EXPECT_EQ(back.mesh.num_faces(), built.mesh.num_faces());
    EXPECT_EQ(back.mesh.positions(), built.mesh.positions());
    EXPECT_EQ(back.mesh.hints().creasing, built.mesh.hints().creasing);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace limsurf
