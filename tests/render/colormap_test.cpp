// The pieces of a picture: colour maps (viridis' published ends and middle, increasing lightness;
// Moreland's cool-warm ends and grey middle), sRGB decoding, views and the camera fit, and PNG output,
// decoded again by an independent reader (stb_image) to the same pixels.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb_image.h>

#include "limsurf/core/error.h"
#include "limsurf/render/camera.h"
#include "limsurf/render/colormap.h"
#include "limsurf/render/image.h"
#include "support/paths.h"

namespace limsurf::test {
namespace {

Eigen::Vector3d bytes(Colormap map, double t) {
    return colormap_color(map, t) * 255.0;
}

double lightness(const Eigen::Vector3d& srgb) {
    return 0.2126 * srgb_to_linear(srgb.x()) + 0.7152 * srgb_to_linear(srgb.y()) + 0.0722 * srgb_to_linear(srgb.z());
}

TEST(Colormap, ViridisHasItsPublishedValuesAndGetsLighter) {
    EXPECT_LT((colormap_color(Colormap::Viridis, 0.0) - Eigen::Vector3d{0.267004, 0.004874, 0.329415}).norm(), 1e-12);
    EXPECT_LT((colormap_color(Colormap::Viridis, 1.0) - Eigen::Vector3d{0.993248, 0.906157, 0.143936}).norm(), 1e-12);
    EXPECT_LT((colormap_color(Colormap::Viridis, 128.0 / 255.0) - Eigen::Vector3d{0.127568, 0.566949, 0.550556}).norm(),
              1e-12);
    double previous = -1.0;
    for (int k = 0; k <= 100; ++k) {
        const double l = lightness(colormap_color(Colormap::Viridis, k / 100.0));
        EXPECT_GT(l, previous) << k;
        previous = l;
    }
    EXPECT_EQ(colormap_color(Colormap::Viridis, -3.0), colormap_color(Colormap::Viridis, 0.0));
    EXPECT_EQ(colormap_color(Colormap::Viridis, 7.0), colormap_color(Colormap::Viridis, 1.0));
    EXPECT_THROW((void)colormap_color(Colormap::Viridis, std::nan("")), InputError);
}

// Moreland's table: (59, 76, 192) at 0, (221, 221, 221) at 1/2, (180, 4, 38) at 1; lightness rises to the
// middle and falls after it.
TEST(Colormap, CoolWarmHasMorelandsEndsAndAGreyMiddle) {
    EXPECT_LT((bytes(Colormap::CoolWarm, 0.0) - Eigen::Vector3d{59, 76, 192}).cwiseAbs().maxCoeff(), 0.6);
    EXPECT_LT((bytes(Colormap::CoolWarm, 1.0) - Eigen::Vector3d{180, 4, 38}).cwiseAbs().maxCoeff(), 0.6);
    EXPECT_LT((bytes(Colormap::CoolWarm, 0.5) - Eigen::Vector3d{221, 221, 221}).cwiseAbs().maxCoeff(), 1.0);
    for (int k = 1; k <= 50; ++k) {
        EXPECT_GT(lightness(colormap_color(Colormap::CoolWarm, k / 100.0)),
                  lightness(colormap_color(Colormap::CoolWarm, (k - 1) / 100.0)));
        EXPECT_LT(lightness(colormap_color(Colormap::CoolWarm, (k + 50) / 100.0)),
                  lightness(colormap_color(Colormap::CoolWarm, (k + 49) / 100.0)));
    }
    EXPECT_TRUE(is_diverging(Colormap::CoolWarm));
    EXPECT_FALSE(is_diverging(Colormap::Viridis));
    EXPECT_EQ(colormap_from_name("coolwarm"), Colormap::CoolWarm);
    EXPECT_EQ(colormap_name(Colormap::Viridis), "viridis");
    EXPECT_THROW((void)colormap_from_name("jet"), InputError);
}

TEST(Colormap, SrgbDecodingHasItsFixedPoints) {
    EXPECT_EQ(srgb_to_linear(0.0), 0.0);
    EXPECT_NEAR(srgb_to_linear(1.0), 1.0, 1e-15);
    EXPECT_NEAR(srgb_to_linear(0.5), 0.21404, 1e-5);
}

TEST(Camera, ViewsHaveTheirDirections) {
    const Points one = Points::Zero(1, 3);
    const Camera front = fit_camera(parse_view("front"), one, 0, 0, 10, 10);
    EXPECT_LT((front.toward_viewer - Eigen::Vector3d{0, -1, 0}).norm(), 1e-15);
    EXPECT_LT((front.right - Eigen::Vector3d{1, 0, 0}).norm(), 1e-15);
    EXPECT_LT((front.up - Eigen::Vector3d{0, 0, 1}).norm(), 1e-15);
    const Camera top = fit_camera(parse_view("top"), one, 0, 0, 10, 10);
    EXPECT_LT((top.toward_viewer - Eigen::Vector3d{0, 0, 1}).norm(), 1e-15);
    EXPECT_LT((top.up - Eigen::Vector3d{0, 1, 0}).norm(), 1e-15);
    const Camera iso = fit_camera(parse_view("iso"), one, 0, 0, 10, 10);
    EXPECT_LT((iso.toward_viewer - Eigen::Vector3d{1, -1, 1}.normalized()).norm(), 1e-15);
    const View custom = parse_view("30,-20.5");
    EXPECT_EQ(custom.azimuth, 30.0);
    EXPECT_EQ(custom.elevation, -20.5);
    for (const char* bad : {"", "side", "30", "30,", ",20", "30,91", "nan,0", "1e999,0", "30;20", "30,20,1"}) {
        EXPECT_THROW((void)parse_view(bad), InputError) << bad;
    }
}

// The bounding box of the projection is scaled uniformly into the box and centred.
TEST(Camera, FitsTheProjectedBoxAndCentresIt) {
    Points square(4, 3);
    square << 0, 0, 0, 2, 0, 0, 2, 0, 1, 0, 0, 1;  // 2 wide, 1 high, seen from the front
    const Camera c = fit_camera(parse_view("front"), square, 10, 20, 110, 220);
    EXPECT_DOUBLE_EQ(c.scale, 50.0);  // the width limits: 100 pixels for 2 units
    EXPECT_LT((c.project(Eigen::Vector3d{0, 0, 0}) - Eigen::Vector3d{10, 145, 0}).norm(), 1e-12);
    EXPECT_LT((c.project(Eigen::Vector3d{2, 0, 1}) - Eigen::Vector3d{110, 95, 0}).norm(), 1e-12);
    EXPECT_GT(c.project(Eigen::Vector3d{0, -1, 0}).z(), c.project(Eigen::Vector3d{0, 1, 0}).z());  // nearer: larger
    EXPECT_THROW((void)fit_camera(View{}, Points(0, 3), 0, 0, 1, 1), InputError);
    EXPECT_THROW((void)fit_camera(View{}, square, 5, 0, 5, 1), InputError);
}

TEST(Image, PngDecodesToTheSamePixels) {
    Image image(7, 5, Rgb{10, 20, 30});
    image.set_pixel(3, 2, {255, 0, 128});
    image.set_pixel(6, 4, {1, 2, 3});
    const std::vector<std::uint8_t> png = encode_png(image);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png[1], 'P');
    EXPECT_EQ(png[2], 'N');
    EXPECT_EQ(png[3], 'G');
    int w = 0;
    int h = 0;
    int channels = 0;
    unsigned char* decoded = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &w, &h, &channels, 3);
    ASSERT_NE(decoded, nullptr);
    EXPECT_EQ(w, 7);
    EXPECT_EQ(h, 5);
    EXPECT_EQ(std::vector<std::uint8_t>(decoded, decoded + std::ptrdiff_t{105}), image.pixels);
    stbi_image_free(decoded);

    const std::filesystem::path dir = make_temp_dir("render_png");
    write_png(dir / "a.png", image);
    std::ifstream in(dir / "a.png", std::ios::binary);
    const std::vector<std::uint8_t> written((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(written, png);
    EXPECT_THROW(write_png(dir / "missing" / "a.png", image), InputError);
    EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
    Image broken = image;
    broken.pixels.pop_back();
    EXPECT_THROW((void)encode_png(broken), InputError);
    EXPECT_THROW(Image(0, 5, Rgb{}), InputError);
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace limsurf::test
