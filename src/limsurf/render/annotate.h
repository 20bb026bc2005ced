// Annotations drawn on a finished picture (private to render.cpp): text in a tiny built-in bitmap
// font and the colour bar.
#pragma once

#include <functional>
#include <string>

#include "limsurf/render/image.h"

namespace limsurf::detail {

/// Glyphs are 5 × 7 pixels on a 6-pixel advance, times the scale.
constexpr int glyph_width = 5;
constexpr int glyph_height = 7;
constexpr int glyph_advance = 6;

/// @brief Draws @p text with its top-left corner at (@p x, @p y), each font pixel @p scale × @p scale;
///   the characters are 0-9, '-', '+', '.', 'e' (others are left blank). Clipped to the image.
void draw_text(Image& image, int x, int y, const std::string& text, int scale, Rgb color);

/// @brief A number as the colour bar labels it: 3 significant digits ("%.3g": 0.25, -1.5e-05, 1e+03).
[[nodiscard]] std::string label_text(double value);

/// @brief Fills the rectangle [x0, x1) × [y0, y1) row by row with color_of(t), t = 0 at the bottom row
///   and 1 at the top, and frames it with a one-pixel border of @p frame outside it. Clipped to the image.
void draw_color_bar(Image& image, int x0, int y0, int x1, int y1, const std::function<Rgb(double)>& color_of,
                    Rgb frame);

}  // namespace limsurf::detail
