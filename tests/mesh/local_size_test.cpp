// mesh/local_size.h: the largest face and fan, and the refusal that names them; and the
// topology's construction stays linear for faces and fans of 10⁵.
#include <chrono>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/mesh/topology.h"
#include "support/timing.h"

namespace limsurf {
namespace {

/// Two n-gons glued along their rims (every vertex has valence 2).
Topology pillow(Index n) {
    std::vector<Index> top(static_cast<std::size_t>(n));
    std::iota(top.begin(), top.end(), Index{0});
    std::vector<Index> bottom(top.rbegin(), top.rend());
    return Topology::from_polygons(n, {top, bottom});
}

/// n triangles around vertex 0, shuffled so that no sort can be helped by the input order.
Topology fan(Index n) {
    std::vector<std::vector<Index>> faces;
    for (Index i = 0; i < n; ++i) {
        const Index j = (i * 7919) % n;  // 7919 is prime: a permutation of the faces
        faces.push_back({0, j + 1, (j + 1) % n + 1});
    }
    return Topology::from_polygons(n + 1, faces);
}

double seconds_to_build(const std::function<Topology()>& build) {
    const auto start = std::chrono::steady_clock::now();
    (void)build();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(LocalSize, FindsTheLargestFaceAndFan) {
    const Topology t = fan(7);
    const LocalSize size = local_size(t);
    EXPECT_EQ(size.max_face_degree, 3);
    EXPECT_EQ(size.face, 0);
    EXPECT_EQ(size.max_valence, 7);
    EXPECT_EQ(size.vertex, 0);
    EXPECT_NO_THROW(require_local_size(t, 7, "the test"));
    try {
        require_local_size(t, 6, "the test");
        FAIL();
    } catch (const UnsupportedError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "vertex 0 has 7 edges; the test handles faces and vertices of at most 6 (docs/io.md \"Limits\")");
        ASSERT_TRUE(e.element().has_value());
        EXPECT_EQ(e.element()->kind, ErrorElement::Kind::Vertex);
        EXPECT_EQ(e.element()->index, 0);
    }
    try {
        require_local_size(pillow(9), 8, "the test");
        FAIL();
    } catch (const UnsupportedError& e) {
        EXPECT_EQ(std::string(e.what()).rfind("face 0 has 9 corners;", 0), 0U) << e.what();
        EXPECT_EQ(e.element()->kind, ErrorElement::Kind::Face);
    }
}

TEST(LocalSize, TopologiesOfHugeFacesAndFansBuildInLinearTime) {
    // Quadratic in the face degree before (a search of the face for each one-ring step; an
    // insertion sort of the apex's half-edges): minutes at 10⁵.
    const Topology big = pillow(100000);
    EXPECT_EQ(big.num_edges(), 100000);
    EXPECT_EQ(big.vertex_faces(5).size(), 2U);
    EXPECT_LT(seconds_to_build([] { return pillow(100000); }), 0.5 * test::time_scale);
    const Topology cone = fan(100000);
    EXPECT_EQ(cone.valence(0), 100000);
    EXPECT_TRUE(cone.has_boundary());
    EXPECT_LT(seconds_to_build([] { return fan(100000); }), 0.5 * test::time_scale);
}

}  // namespace
}  // namespace limsurf
