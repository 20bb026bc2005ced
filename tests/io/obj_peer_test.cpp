// Peer check: tinyobjloader (an independent OBJ reader) and read_obj() agree on the faces
// and positions of every OBJ we bundle.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_obj_loader.h>
#include <unistd.h>

#include "limsurf/io/obj.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> obj_files() {
    std::vector<fs::path> files;
    for (const char* name : {"cube_forms.obj", "negative.obj", "crlf.obj", "shape_tags.obj"}) {
        files.push_back(test::test_data_dir() / "io" / name);
    }
    if (fs::is_directory(test::mesh_dir())) {
        for (const auto& entry : fs::directory_iterator(test::mesh_dir())) {
            if (entry.path().extension() == ".obj") {
                files.push_back(entry.path());
            }
        }
    }
    return files;
}

/// The x y z of every "v" line, parsed with std::strtod.
Points strtod_positions(const fs::path& path) {
    std::ifstream in(path);
    std::vector<double> values;
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string key;
        std::string x;
        std::string y;
        std::string z;
        if (words >> key >> x >> y >> z && key == "v") {
            for (const std::string* token : {&x, &y, &z}) {
                values.push_back(std::strtod(token->c_str(), nullptr));
            }
        }
    }
    Points points(static_cast<Index>(values.size() / 3), 3);
    for (std::size_t i = 0; i < values.size(); ++i) {
        points(static_cast<Index>(i / 3), static_cast<Index>(i % 3)) = values[i];
    }
    return points;
}

TEST(ObjPeer, TinyObjLoaderReadsTheSameFacesAndPositions) {
    const auto files = obj_files();
    ASSERT_GE(files.size(), 4U);
    for (const fs::path& path : files) {
        SCOPED_TRACE(path.string());
        tinyobj::ObjReaderConfig config;
        config.triangulate = false;
        config.mtl_search_path = "/nonexistent";
        tinyobj::ObjReader peer;
        ASSERT_TRUE(peer.ParseFromFile(path.string(), config)) << peer.Error();
        const PolygonSoup ours = read_obj(path);

        // tinyobjloader's number parser is not correctly rounded (it is off by up to a few
        // units in the last place), so positions agree to a few ulps only.
        const auto& coords = peer.GetAttrib().vertices;
        ASSERT_EQ(coords.size(), 3 * static_cast<std::size_t>(ours.num_vertices()));
        for (Index v = 0; v < ours.num_vertices(); ++v) {
            for (Index c = 0; c < 3; ++c) {
                const double theirs = coords[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(c)];
                const double mine = ours.positions(v, c);
                EXPECT_LE(std::abs(theirs - mine), 8 * std::numeric_limits<double>::epsilon() * std::abs(mine))
                    << "vertex " << v;
            }
        }
        // Ours is exact: every coordinate equals glibc's correctly rounded strtod.
        EXPECT_EQ(strtod_positions(path), ours.positions);

        std::vector<std::vector<Index>> peer_faces;
        for (const auto& shape : peer.GetShapes()) {
            std::size_t next = 0;
            for (const auto n : shape.mesh.num_face_vertices) {
                std::vector<Index> face;
                for (std::size_t k = 0; k < n; ++k) {
                    face.push_back(shape.mesh.indices[next++].vertex_index);
                }
                peer_faces.push_back(face);
            }
        }
        std::vector<std::vector<Index>> our_faces;
        our_faces.reserve(static_cast<std::size_t>(ours.num_faces()));
        for (Index f = 0; f < ours.num_faces(); ++f) {
            our_faces.emplace_back(ours.face(f).begin(), ours.face(f).end());
        }
        EXPECT_EQ(peer_faces, our_faces);
    }
}

TEST(ObjPeer, TinyObjLoaderSeesTheGroupsWeWrite) {
    // write_obj puts a `g NAME` line before each run of faces of one group; tinyobjloader starts
    // a shape named after each `g` line: every face's shape name must be our group name.
    PolygonSoup soup = read_obj(test::mesh_dir() / "rve_block.obj");
    ASSERT_EQ(soup.groups.names.size(), 2U);
    std::ostringstream text;
    write_obj(text, soup);
    const fs::path path =
        fs::temp_directory_path() / ("limsurf_obj_peer_groups_" + std::to_string(::getpid()) + ".obj");
    {
        std::ofstream out(path);
        out << text.str();
    }
    tinyobj::ObjReaderConfig config;
    config.triangulate = false;
    tinyobj::ObjReader peer;
    const bool parsed = peer.ParseFromFile(path.string(), config);
    fs::remove(path);
    ASSERT_TRUE(parsed) << peer.Error();
    std::vector<std::string> peer_groups;
    for (const auto& shape : peer.GetShapes()) {
        peer_groups.insert(peer_groups.end(), shape.mesh.num_face_vertices.size(), shape.name);
    }
    std::vector<std::string> our_groups;
    for (Index f = 0; f < soup.num_faces(); ++f) {
        our_groups.push_back(soup.groups.names.at(static_cast<std::size_t>(soup.groups.group_of(f))));
    }
    EXPECT_EQ(peer_groups, our_groups);
}

}  // namespace
}  // namespace limsurf
