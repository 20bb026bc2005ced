#include "annotate.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>

namespace limsurf::detail {
namespace {

/// Rows of a glyph, top first; bit 4 is the leftmost pixel. Drawn for limsurf.
struct Glyph {
    char c;
    std::array<std::uint8_t, glyph_height> rows;
};

constexpr std::array<Glyph, 14> font{{
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
    {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
    {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
    {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
    {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
    {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
}};

const Glyph* find_glyph(char c) {
    for (const Glyph& g : font) {
        if (g.c == c) {
            return &g;
        }
    }
    return nullptr;
}

void fill(Image& image, int x0, int y0, int x1, int y1, Rgb color) {
    for (int y = std::max(0, y0); y < std::min(image.height, y1); ++y) {
        for (int x = std::max(0, x0); x < std::min(image.width, x1); ++x) {
            image.set_pixel(x, y, color);
        }
    }
}

}  // namespace

void draw_text(Image& image, int x, int y, const std::string& text, int scale, Rgb color) {
    for (std::size_t i = 0; i < text.size(); ++i) {
        const Glyph* glyph = find_glyph(text[i]);
        if (glyph == nullptr) {
            continue;
        }
        const int left = x + static_cast<int>(i) * glyph_advance * scale;
        for (int row = 0; row < glyph_height; ++row) {
            for (int col = 0; col < glyph_width; ++col) {
                if ((glyph->rows[static_cast<std::size_t>(row)] >> (glyph_width - 1 - col) & 1) != 0) {
                    fill(image, left + col * scale, y + row * scale, left + (col + 1) * scale, y + (row + 1) * scale,
                         color);
                }
            }
        }
    }
}

std::string label_text(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", value);
    return buffer;
}

void draw_color_bar(Image& image, int x0, int y0, int x1, int y1, const std::function<Rgb(double)>& color_of,
                    Rgb frame) {
    fill(image, x0 - 1, y0 - 1, x1 + 1, y1 + 1, frame);
    const int rows = y1 - y0;
    for (int y = y0; y < y1; ++y) {
        const double t = rows > 1 ? static_cast<double>(y1 - 1 - y) / (rows - 1) : 0.5;
        fill(image, x0, y, x1, y + 1, color_of(t));
    }
}

}  // namespace limsurf::detail
