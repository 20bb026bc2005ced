// Unit tests of the sharpness rules (scheme/crease.h), against the values of
// OpenSubdiv's Sdc::Crease worked out by hand.
#include <array>

#include <gtest/gtest.h>

#include "limsurf/scheme/crease.h"

namespace limsurf {
namespace {

TEST(Crease, DecrementSharpness) {
    EXPECT_EQ(decrement_sharpness(0.0), 0.0);
    EXPECT_EQ(decrement_sharpness(0.5), 0.0);
    EXPECT_EQ(decrement_sharpness(1.0), 0.0);
    EXPECT_EQ(decrement_sharpness(2.5), 1.5);
    EXPECT_EQ(decrement_sharpness(10.0), infinite_sharpness);
    EXPECT_EQ(decrement_sharpness(12.0), infinite_sharpness);
}

TEST(Crease, VertexRule) {
    EXPECT_EQ(vertex_rule(0.0, 0), CreaseRule::Smooth);
    EXPECT_EQ(vertex_rule(0.0, 1), CreaseRule::Dart);
    EXPECT_EQ(vertex_rule(0.0, 2), CreaseRule::Crease);
    EXPECT_EQ(vertex_rule(0.0, 3), CreaseRule::Corner);
    EXPECT_EQ(vertex_rule(0.5, 0), CreaseRule::Corner);
    const std::array<double, 4> edges{0.0, 2.5, 0.0, 10.0};
    EXPECT_EQ(vertex_rule(0.0, edges), CreaseRule::Crease);
    EXPECT_EQ(crease_ends(edges), (std::array<int, 2>{1, 3}));
}

TEST(Crease, ChaikinAveragesSemiSharpNeighbours) {
    const std::array<double, 4> edges{2.5, 0.0, 1.25, 10.0};
    std::array<double, 4> child{};
    subdivide_edge_sharpness_around_vertex(edges, child, CreasingMethod::Chaikin);
    EXPECT_EQ(child[0], 0.75 * 2.5 + 0.25 * 1.25 - 1.0);
    EXPECT_EQ(child[1], 0.0);
    EXPECT_EQ(child[2], 0.75 * 1.25 + 0.25 * 2.5 - 1.0);
    EXPECT_EQ(child[3], infinite_sharpness);
}

TEST(Crease, UniformIgnoresNeighbours) {
    const std::array<double, 3> edges{2.5, 1.25, 0.0};
    std::array<double, 3> child{};
    subdivide_edge_sharpness_around_vertex(edges, child, CreasingMethod::Uniform);
    EXPECT_EQ(child[0], 1.5);
    EXPECT_EQ(child[1], 0.25);
    EXPECT_EQ(child[2], 0.0);
}

TEST(Crease, FractionalWeight) {
    // Uniform: edges of sharpness <= 1 decay; the weight is their mean sharpness.
    const std::array<double, 4> parent{0.5, 0.0, 0.25, 0.0};
    const std::array<double, 4> child{0.0, 0.0, 0.0, 0.0};
    EXPECT_EQ(fractional_weight_at_vertex(0.0, 0.0, parent, child, CreasingMethod::Uniform), 0.375);
    // A decaying vertex sharpness counts too, and the weight is clamped to 1.
    EXPECT_EQ(fractional_weight_at_vertex(0.75, 0.0, parent, child, CreasingMethod::Uniform), 0.5);
    const std::array<double, 2> high{1.75, 1.75};
    const std::array<double, 2> gone{0.0, 0.0};
    EXPECT_EQ(fractional_weight_at_vertex(0.0, 0.0, high, gone, CreasingMethod::Chaikin), 1.0);
    EXPECT_EQ(fractional_weight_at_vertex(0.0, 0.0, high, gone, CreasingMethod::Uniform), 0.0);
}

}  // namespace
}  // namespace limsurf
