// Sharpness rules shared by the face-split schemes (OpenSubdiv's Sdc::Crease,
// as limsurf spells it; docs/schemes.md "Creases").
//
// Sharpness s: s <= 0 is smooth, 0 < s < 10 semi-sharp, s >= 10 infinitely
// sharp (sharpness.h). A vertex's rule follows from its own sharpness and the
// number of sharp incident edges: a sharp vertex or more than two sharp edges
// make a Corner, two a Crease, one a Dart, none Smooth. A semi-sharp feature
// loses one unit of sharpness per level (Uniform) or, along a crease path, is
// first averaged with its neighbours (Chaikin). When the rule of a vertex
// changes between parent and child, the parent and child masks are blended
// with the fractional weight below.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "limsurf/mesh/sharpness.h"

namespace limsurf {

/// Vertex subdivision rule (Sdc::Crease::Rule).
enum class CreaseRule : std::uint8_t { Smooth, Dart, Crease, Corner };

[[nodiscard]] constexpr bool is_smooth_sharpness(double s) noexcept {
    return s <= 0.0;
}
[[nodiscard]] constexpr bool is_sharp(double s) noexcept {
    return s > 0.0;
}
[[nodiscard]] constexpr bool is_infinitely_sharp(double s) noexcept {
    return s >= infinite_sharpness;
}
[[nodiscard]] constexpr bool is_semi_sharp(double s) noexcept {
    return s > 0.0 && s < infinite_sharpness;
}

/// @brief One level of uniform decay: 0 stays 0, infinite stays infinite_sharpness,
///   s > 1 becomes s − 1, 0 < s <= 1 becomes 0.
[[nodiscard]] double decrement_sharpness(double sharpness) noexcept;

/// @brief The rule of a vertex with sharpness @p vertex_sharpness and @p sharp_edge_count sharp edges.
[[nodiscard]] CreaseRule vertex_rule(double vertex_sharpness, int sharp_edge_count) noexcept;

/// @brief The rule of a vertex from its sharpness and those of its incident edges.
[[nodiscard]] CreaseRule vertex_rule(double vertex_sharpness, std::span<const double> edge_sharpness) noexcept;

/// @brief The sharpness of the child of an edge at one of its end vertices.
/// @param[in] edge_sharpness     the parent edge's sharpness
/// @param[in] sharpness_at_vertex the sharpness of every parent edge at that end vertex (the edge included)
/// Uniform (or fewer than two edges): decrement_sharpness(). Chaikin: a semi-sharp
/// edge is first blended 3/4 : 1/4 with the mean of the other semi-sharp edges at the vertex.
[[nodiscard]] double subdivide_edge_sharpness_at_vertex(double edge_sharpness,
                                                        std::span<const double> sharpness_at_vertex,
                                                        CreasingMethod method) noexcept;

/// @brief subdivide_edge_sharpness_at_vertex() for every edge around one vertex.
/// @param[in]  parent #edges at the vertex; @param[out] child same size
void subdivide_edge_sharpness_around_vertex(std::span<const double> parent, std::span<double> child,
                                            CreasingMethod method) noexcept;

/// @brief Weight of the parent mask when a vertex's rule changes between levels
///   (Sdc::Crease::ComputeFractionalWeightAtVertex): the mean sharpness of the
///   features that become smooth, clamped to 1.
/// @param[in] parent_edges, child_edges sharpness of the incident edges and of their children (same size)
[[nodiscard]] double fractional_weight_at_vertex(double parent_vertex_sharpness, double child_vertex_sharpness,
                                                 std::span<const double> parent_edges,
                                                 std::span<const double> child_edges, CreasingMethod method) noexcept;

/// @brief Positions (in @p edge_sharpness) of the first and the last sharp edge: the two
///   edges of a crease. @pre at least one entry is sharp
[[nodiscard]] std::array<int, 2> crease_ends(std::span<const double> edge_sharpness) noexcept;

}  // namespace limsurf
