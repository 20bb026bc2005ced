// Doo–Sabin against CGAL 5.5's Subdivision_method_3::DooSabin_subdivision
// (classic weights, PEERS.md) on closed meshes, levels 1 to 3: positions to
// 1e-12 of the bounding-box diagonal after a one-to-one nearest-neighbour
// matching of the vertices, and identical oriented faces.
#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#include <gtest/gtest.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

CgalMesh to_cgal(const Topology& t, const Points& x) {
    CgalMesh mesh;
    std::vector<CgalMesh::Vertex_index> vertices;
    for (Index v = 0; v < t.num_vertices(); ++v) {
        vertices.push_back(mesh.add_vertex(Kernel::Point_3(x(v, 0), x(v, 1), x(v, 2))));
    }
    for (Index f = 0; f < t.num_faces(); ++f) {
        std::vector<CgalMesh::Vertex_index> face;
        for (const Index v : t.face_vertices(f)) {
            face.push_back(vertices[static_cast<std::size_t>(v)]);
        }
        const auto added = mesh.add_face(face);
        EXPECT_NE(added, CgalMesh::null_face()) << "CGAL refused face " << f;
    }
    return mesh;
}

/// A face as the cycle of its vertices, rotated to start at the smallest index.
std::vector<Index> canonical(std::vector<Index> face) {
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    return face;
}

void compare(const std::string& what, const Topology& ours, const Points& x, const CgalMesh& peer) {
    ASSERT_EQ(static_cast<Index>(peer.number_of_vertices()), ours.num_vertices()) << what;
    ASSERT_EQ(static_cast<Index>(peer.number_of_faces()), ours.num_faces()) << what;
    std::vector<Kernel::Point_3> points;
    std::vector<CgalMesh::Vertex_index> handles;
    for (const auto v : peer.vertices()) {
        points.push_back(peer.point(v));
        handles.push_back(v);
    }
    const double diagonal = (x.colwise().maxCoeff() - x.colwise().minCoeff()).norm();
    const double tolerance = 1e-12 * diagonal;
    // Nearest CGAL vertex of each of ours; the matching must be one-to-one.
    std::vector<Index> match(static_cast<std::size_t>(ours.num_vertices()));
    std::vector<Index> ours_of_peer(peer.number_of_vertices() + peer.number_of_removed_vertices(), invalid_index);
    double worst = 0.0;
    for (Index v = 0; v < ours.num_vertices(); ++v) {
        double best = std::numeric_limits<double>::infinity();
        std::size_t best_j = 0;
        for (std::size_t j = 0; j < points.size(); ++j) {
            const double d = std::hypot(points[j].x() - x(v, 0), points[j].y() - x(v, 1), points[j].z() - x(v, 2));
            if (d < best) {
                best = d;
                best_j = j;
            }
        }
        worst = std::max(worst, best);
        const auto peer_index = static_cast<std::size_t>(handles[best_j].idx());
        ASSERT_EQ(ours_of_peer[peer_index], invalid_index) << what << ": matching is not one-to-one at vertex " << v;
        ours_of_peer[peer_index] = v;
        match[static_cast<std::size_t>(v)] = static_cast<Index>(peer_index);
    }
    EXPECT_LE(worst, tolerance) << what;
    // Faces: the same oriented cycles of matched vertices.
    std::vector<std::vector<Index>> our_faces;
    for (Index f = 0; f < ours.num_faces(); ++f) {
        const auto fv = ours.face_vertices(f);
        our_faces.push_back(canonical(std::vector<Index>(fv.begin(), fv.end())));
    }
    std::vector<std::vector<Index>> peer_faces;
    for (const auto f : peer.faces()) {
        std::vector<Index> face;
        for (const auto v : CGAL::vertices_around_face(peer.halfedge(f), peer)) {
            face.push_back(ours_of_peer[static_cast<std::size_t>(v.idx())]);
        }
        peer_faces.push_back(canonical(face));
    }
    std::sort(our_faces.begin(), our_faces.end());
    std::sort(peer_faces.begin(), peer_faces.end());
    EXPECT_EQ(our_faces, peer_faces) << what;
}

class DooSabinPeer : public ::testing::TestWithParam<std::string> {};

void expect_cgal_agrees(const std::string& name, const SchemeOptions& options) {
    const BuildResult r = read_mesh(test::find_bundled(name).path);
    Topology t = r.mesh.topology();
    Points x = r.mesh.positions();
    for (int level = 1; level <= 3; ++level) {
        const Level child = refine_doo_sabin(t, options);
        x = child.S0 * x;
        t = child.topology;
        CgalMesh peer = to_cgal(r.mesh.topology(), r.mesh.positions());
        CGAL::Subdivision_method_3::DooSabin_subdivision(peer, CGAL::parameters::number_of_iterations(level));
        compare(name + " level " + std::to_string(level), t, x, peer);
    }
}

TEST_P(DooSabinPeer, MatchesCgalOverThreeLevels) {
    expect_cgal_agrees(GetParam(), SchemeOptions{});
}

class DooSabinPeerBoundaryNone : public ::testing::TestWithParam<std::string> {};

TEST_P(DooSabinPeerBoundaryNone, MatchesCgalOverThreeLevels) {
    // CGAL has no boundary rule (boundary edges and vertices make no faces);
    // BoundaryInterpolation::None is that behaviour.
    SchemeOptions options;
    options.boundary = BoundaryInterpolation::None;
    expect_cgal_agrees(GetParam(), options);
}

INSTANTIATE_TEST_SUITE_P(WithBoundary, DooSabinPeerBoundaryNone,
                         ::testing::Values("quad_grid", "tri_grid", "disk_ev5_quads", "cylinder_open", "annulus",
                                           "hexagon_fan", "pentagon"),
                         [](const auto& param_info) { return param_info.param; });

INSTANTIATE_TEST_SUITE_P(Closed, DooSabinPeer,
                         ::testing::Values("cube", "tetrahedron", "octahedron", "icosahedron", "dodecahedron",
                                           "cube_ngons", "prism_hex", "quad_torus", "genus2", "quad_valence_3",
                                           "quad_valence_5", "quad_valence_8", "tri_valence_3", "tri_valence_7",
                                           "tri_valence_12", "sphere_tris", "tetra_and_cube"),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace limsurf
