// The rasterizer behind render.h (private): a supersampled depth buffer that records, per sample, the
// nearest triangle and its barycentric coordinates (shading is deferred to one pass over the visible
// samples), and depth-tested lines marked in a mask.
//
// Sample coordinates: x to the right, y downwards, sample (i, j) centred at (i + 1/2, j + 1/2); depth
// grows towards the viewer (the nearest surface has the largest depth).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf::detail {

struct SampleBuffer {
    /// @pre width, height >= 1
    SampleBuffer(int width, int height);

    int width = 0;
    int height = 0;
    std::vector<double> depth;       ///< -inf where nothing was drawn
    std::vector<Index> triangle;     ///< invalid_index where nothing was drawn
    std::vector<float> b1;           ///< barycentric weight of the triangle's second vertex
    std::vector<float> b2;           ///< ... and of its third (the first has 1 - b1 - b2)
    std::vector<std::uint8_t> line;  ///< 1 where a line was drawn

    [[nodiscard]] std::size_t at(int x, int y) const noexcept {
        return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
    }
};

/// @brief Draws triangle @p id with corners @p a, @p b, @p c (x, y in samples, depth) where it is
///   nearer than what the buffer holds. Either orientation is drawn. Samples on an edge shared by two
///   triangles belong to exactly one of them, so a closed surface has no cracks.
void draw_triangle(SampleBuffer& buffer, Index id, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                   const Eigen::Vector3d& c);

/// @brief Marks the samples of a line from @p a to @p b, @p width samples wide, where no surface is
///   nearer than the line's depth minus @p bias.
void draw_line(SampleBuffer& buffer, const Eigen::Vector3d& a, const Eigen::Vector3d& b, int width, double bias);

}  // namespace limsurf::detail
