#include "limsurf/render/image.h"

#include <ostream>

#include <stb_image_write.h>

#include "limsurf/core/error.h"
#include "limsurf/io/atomic_file.h"

namespace limsurf {
namespace {

void append_bytes(void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

Image::Image(int w, int h, Rgb fill) : width(w), height(h) {
    LIMSURF_CHECK(width >= 1 && width <= 65535 && height >= 1 && height <= 65535, InputError, "image size ", width, "x",
                  height, " is outside 1..65535");
    pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
    for (std::size_t k = 0; k < pixels.size(); k += 3) {
        pixels[k] = fill.r;
        pixels[k + 1] = fill.g;
        pixels[k + 2] = fill.b;
    }
}

std::vector<std::uint8_t> encode_png(const Image& image) {
    LIMSURF_CHECK(image.width >= 1 && image.height >= 1 &&
                      image.pixels.size() ==
                          static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 3,
                  InputError, "image of ", image.width, "x", image.height, " pixels has ", image.pixels.size(),
                  " bytes, expected width * height * 3");
    std::vector<std::uint8_t> png;
    // stb keeps its compression level in a global; the default (8) is left alone, so the bytes depend
    // only on the image.
    const int ok =
        stbi_write_png_to_func(append_bytes, &png, image.width, image.height, 3, image.pixels.data(), image.width * 3);
    LIMSURF_CHECK(ok != 0, Error, "PNG encoding of a ", image.width, "x", image.height, " image failed");
    return png;
}

void write_png(const std::filesystem::path& path, const Image& image) {
    const std::vector<std::uint8_t> png = encode_png(image);
    write_file_atomically(path, [&](std::ostream& out) {
        out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
    });
}

}  // namespace limsurf
