// An 8-bit RGB image in memory, and PNG output (through stb_image_write, Debian's libstb-dev).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace limsurf {

/// An sRGB colour, 8 bits per component.
struct Rgb {
    std::uint8_t r = 0;
    std::uint8_t g = 0;
    std::uint8_t b = 0;

    friend bool operator==(const Rgb&, const Rgb&) = default;
};

/// width × height pixels, row-major from the top-left corner, 3 bytes (R, G, B) per pixel.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  ///< height · width · 3 bytes

    Image() = default;
    /// @throws InputError for a size outside 1..65535
    Image(int w, int h, Rgb fill);

    /// @pre 0 <= x < width, 0 <= y < height (not checked)
    [[nodiscard]] Rgb pixel(int x, int y) const noexcept {
        const std::uint8_t* p = &pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x) * 3];
        return {p[0], p[1], p[2]};
    }
    /// @pre 0 <= x < width, 0 <= y < height (not checked)
    void set_pixel(int x, int y, Rgb c) noexcept {
        std::uint8_t* p = &pixels[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x) * 3];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
    }
};

/// @brief The PNG encoding of @p image (8-bit RGB, no interlacing; the same bytes for the same image).
/// @throws InputError when the image is empty or its pixel buffer does not have width · height · 3 bytes;
///   Error when the encoder fails (out of memory)
[[nodiscard]] std::vector<std::uint8_t> encode_png(const Image& image);

/// @brief Writes encode_png(image) to @p path atomically (io/atomic_file.h): a failure leaves no file.
/// @throws as encode_png(), and InputError naming @p path when it cannot be written
void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace limsurf
