// Pictures (render/render.h), checked by their structure, never byte for byte against a stored file:
// the projected sphere covers π r² pixels, the corners keep the background, the headlight makes the
// centre brighter than the rim, a constant field gives one colour, a given range is used, the field's minimum shows the
// colour map's first colour where it faces the viewer, the colour bar spans the map at its place, isolines and the
// control polygon change pixels only where they are drawn, renders are deterministic and views differ.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/render/render.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

struct Scene {
    Scene(const std::string& name, SchemeKind scheme, int resolution = 6)
        : built(read_mesh(find_bundled(name).path)), basis(built.mesh.topology(), scheme),
          surface(tessellate_limit_surface(basis, built.mesh.positions(), {.resolution = resolution})) {}
    [[nodiscard]] const Points& X() const { return built.mesh.positions(); }
    BuildResult built;
    LimitBasis basis;
    LimitTessellation surface;
};

RenderOptions small(const std::string& view = "iso") {
    RenderOptions options;
    options.width = 200;
    options.height = 150;
    options.view = parse_view(view);
    return options;
}

double luminance(Rgb c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

Rgb expected(Colormap map, double t) {
    const Eigen::Vector3d c = colormap_color(map, t) * 255.0;
    return {static_cast<std::uint8_t>(std::lround(c.x())), static_cast<std::uint8_t>(std::lround(c.y())),
            static_cast<std::uint8_t>(std::lround(c.z()))};
}

bool near(Rgb a, Rgb b, int tolerance) {
    return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance && std::abs(a.b - b.b) <= tolerance;
}

/// The pixel under the projection of @p x.
Rgb pixel_at(const RenderResult& r, const Eigen::Vector3d& x) {
    const Eigen::Vector3d p = r.camera.project(x);
    return r.image.pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
}

int count_different(const Image& a, const Image& b) {
    int n = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            n += a.pixel(x, y) == b.pixel(x, y) ? 0 : 1;
        }
    }
    return n;
}

/// Distance from (x, y) to the segment from a to b, in the plane.
double segment_distance(double x, double y, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector2d p{x, y};
    const Eigen::Vector2d d = (b - a).head<2>();
    const double t = d.squaredNorm() > 0.0 ? std::clamp((p - a.head<2>()).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - a.head<2>() - t * d).norm();
}

// The limit surface of sphere_quads is nearly a sphere: it projects to a disc that fills the height of
// the fitted box (150 - 2 · 8 margin = 134 pixels), covering π 67² of the 200 × 150 pixels.
TEST(Render, SphereCoversItsProjectedDiscAndKeepsTheBackgroundInTheCorners) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark, 8);
    const RenderOptions options = small();
    const RenderResult r = render_tessellation(s.surface, {}, options);
    ASSERT_EQ(r.image.width, 200);
    ASSERT_EQ(r.image.height, 150);
    const double expected_coverage = std::numbers::pi * 67.0 * 67.0 / (200.0 * 150.0);
    EXPECT_NEAR(r.coverage, expected_coverage, 0.03 * expected_coverage);
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{199, 0}, std::pair{0, 149}, std::pair{199, 149}}) {
        EXPECT_EQ(r.image.pixel(x, y), options.background) << x << ", " << y;
    }
    EXPECT_FALSE(r.has_field);
    EXPECT_FALSE(r.color_bar.has_value());
}

TEST(Render, HeadlightMakesTheCentreBrighterThanTheRim) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark);
    const RenderResult r = render_tessellation(s.surface, {}, small());
    const Eigen::Vector3d centre = r.camera.project(Eigen::Vector3d::Zero());
    const Rgb middle = r.image.pixel(static_cast<int>(centre.x()), static_cast<int>(centre.y()));
    const Rgb rim = r.image.pixel(static_cast<int>(centre.x() - 0.9 * 67.0), static_cast<int>(centre.y()));
    EXPECT_GT(luminance(middle), luminance(rim) + 40.0);
    // Facing the viewer, the surface shows its colour unshaded.
    EXPECT_TRUE(near(middle, small().surface, 2));
}

// A constant vertex field (partition of unity: exactly 1 on the surface) with the range [0, 2] maps to
// the colour map's middle everywhere: every surface pixel away from the silhouette has its chromaticity.
TEST(Render, ConstantFieldGivesOneColour) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark);
    const Eigen::VectorXd one = evaluate_vertex_field(s.surface, Eigen::VectorXd::Ones(s.X().rows()));
    RenderOptions options = small();
    options.range = std::array<double, 2>{0.0, 2.0};
    const RenderResult r = render_tessellation(s.surface, one, options);
    const Eigen::Vector3d mid = colormap_color(Colormap::Viridis, 0.5);
    const Eigen::Vector3d chroma = mid / mid.sum();
    int inside = 0;
    for (int y = 1; y + 1 < 150; ++y) {
        for (int x = 1; x + 1 < r.color_bar->x0 - 5; ++x) {
            bool interior = true;
            for (int j = -1; j <= 1; ++j) {
                for (int i = -1; i <= 1; ++i) {
                    interior = interior && !(r.image.pixel(x + i, y + j) == options.background);
                }
            }
            if (!interior) {
                continue;
            }
            ++inside;
            const Rgb c = r.image.pixel(x, y);
            const Eigen::Vector3d v{double(c.r), double(c.g), double(c.b)};
            EXPECT_LT((v / v.sum() - chroma).cwiseAbs().maxCoeff(), 0.03) << x << ", " << y;
        }
    }
    EXPECT_GT(inside, 5000);
}

// A range from the options is used as given; the field's own extremes are reported beside it (C2g0's
// F_tetra,3 sphere: its Gaussian curvature is near 1 away from the valence-3 vertices, up to ~6 next to them).
TEST(Render, RangeFromTheOptionsIsUsedAndTheFieldExtremesReported) {
    const Scene s("tetra_3", SchemeKind::C2g0, 4);
    RenderOptions options = small();
    options.range = std::array<double, 2>{0.0, 2.0};
    const RenderResult r = render_tessellation(s.surface, s.surface.gaussian_curvature, options);
    EXPECT_EQ(r.field_min, s.surface.gaussian_curvature.minCoeff());
    EXPECT_EQ(r.field_max, s.surface.gaussian_curvature.maxCoeff());
    EXPECT_GT(r.field_min, 0.5);
    EXPECT_EQ(r.range[0], 0.0);
    EXPECT_EQ(r.range[1], 2.0);
}

// The field y, seen from the front (the viewer at -y): its minimum is the point nearest the viewer,
// where the surface faces the viewer and shows the colour map's first colour unshaded.
TEST(Render, FieldMinimumShowsTheFirstColourOfTheMap) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark, 8);
    const Eigen::VectorXd y = s.surface.positions.col(1);
    for (const Colormap map : {Colormap::Viridis, Colormap::CoolWarm}) {
        RenderOptions options = small("front");
        options.colormap = map;
        options.range = std::array<double, 2>{y.minCoeff(), y.maxCoeff()};
        const RenderResult r = render_tessellation(s.surface, y, options);
        Index lowest = 0;
        y.minCoeff(&lowest);
        EXPECT_TRUE(near(pixel_at(r, s.surface.positions.row(lowest)), expected(map, 0.0), 3));
    }
}

TEST(Render, ColourBarSpansTheMapBesideTheSurface) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark);
    const RenderOptions options = small();
    const RenderResult r = render_tessellation(s.surface, s.surface.positions.col(2), options);
    ASSERT_TRUE(r.color_bar.has_value());
    const PixelBox bar = *r.color_bar;
    EXPECT_GT(bar.x0, 100);
    EXPECT_LT(bar.x1, 200);
    const int x = (bar.x0 + bar.x1) / 2;
    EXPECT_TRUE(near(r.image.pixel(x, bar.y1 - 1), expected(Colormap::Viridis, 0.0), 1));
    EXPECT_TRUE(near(r.image.pixel(x, bar.y0), expected(Colormap::Viridis, 1.0), 1));
    EXPECT_TRUE(near(r.image.pixel(x, (bar.y0 + bar.y1) / 2), expected(Colormap::Viridis, 0.5), 4));
    // The surface stays left of the bar; the labels are drawn right of it.
    const Eigen::Vector3d right_end = r.camera.project(Eigen::Vector3d{1.0, 1.0, 0.0} / std::sqrt(2.0));
    EXPECT_LT(right_end.x(), bar.x0);
    int ink = 0;
    for (int y = bar.y0; y < bar.y1; ++y) {
        for (int x2 = bar.x1 + 2; x2 < 200; ++x2) {
            ink += r.image.pixel(x2, y) == options.background ? 0 : 1;
        }
    }
    EXPECT_GT(ink, 20);
    EXPECT_EQ(r.range[0], r.field_min);
    EXPECT_EQ(r.range[1], r.field_max);
}

// Isolines of the height z seen from the front are horizontal: they change only pixels in the rows of
// the levels lo + k (hi - lo)/6, k = 1..5, and only a band of them.
TEST(Render, IsolinesChangeOnlyTheRowsOfTheLevels) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark);
    const Eigen::VectorXd z = s.surface.positions.col(2);
    RenderOptions options = small("front");
    const RenderResult plain = render_tessellation(s.surface, z, options);
    options.isolines = 5;
    const RenderResult lined = render_tessellation(s.surface, z, options);
    std::vector<double> rows;
    for (int k = 1; k <= 5; ++k) {
        const double level = lined.range[0] + k * (lined.range[1] - lined.range[0]) / 6.0;
        rows.push_back(lined.camera.project(Eigen::Vector3d{0.0, 0.0, level}).y());
    }
    int changed = 0;
    int surface = 0;
    for (int y = 0; y < 150; ++y) {
        for (int x = 0; x < plain.color_bar->x0 - 5; ++x) {
            surface += plain.image.pixel(x, y) == options.background ? 0 : 1;
            if (plain.image.pixel(x, y) == lined.image.pixel(x, y)) {
                continue;
            }
            ++changed;
            double nearest = std::numeric_limits<double>::infinity();
            for (const double row : rows) {
                nearest = std::min(nearest, std::abs(y + 0.5 - row));
            }
            EXPECT_LT(nearest, 1.5) << x << ", " << y;
        }
    }
    EXPECT_GT(changed, 5 * 60);  // five lines across a disc about 130 pixels wide
    EXPECT_LT(changed, surface / 4);
}

// The control polygon changes only pixels near its projected edges; the camera is the same when the
// overlay has its points but no edges.
TEST(Render, ControlPolygonChangesPixelsOnlyAlongItsEdges) {
    const Scene s("cube", SchemeKind::CatmullClark);
    const ControlPolygon polygon = control_polygon(s.built.mesh.topology(), s.X());
    const RenderResult without = render_tessellation(s.surface, {}, small(), ControlPolygon{polygon.points, {}});
    const RenderResult with = render_tessellation(s.surface, {}, small(), polygon);
    EXPECT_EQ(without.camera.scale, with.camera.scale);
    int changed = 0;
    for (int y = 0; y < 150; ++y) {
        for (int x = 0; x < 200; ++x) {
            if (without.image.pixel(x, y) == with.image.pixel(x, y)) {
                continue;
            }
            ++changed;
            double nearest = std::numeric_limits<double>::infinity();
            for (const auto& [a, b] : polygon.edges) {
                nearest = std::min(nearest, segment_distance(x + 0.5, y + 0.5, with.camera.project(s.X().row(a)),
                                                             with.camera.project(s.X().row(b))));
            }
            EXPECT_LT(nearest, 1.5) << x << ", " << y;
        }
    }
    EXPECT_GT(changed, 300);  // the 9 visible edges of the cube, ~60 pixels each
}

// A field and its range scaled by 2^1020 (values up to 2^1020 ≈ 1.1e307, a range twice as wide):
// the same picture, isolines included. The width of that range overflows a double; computed as it
// was, every value mapped to the colour map's first colour.
TEST(Render, ARangeNearTheLargestDoubleGivesTheSamePictureAsAScaledDown) {
    const Scene s("sphere_quads", SchemeKind::CatmullClark, 6);
    const Eigen::VectorXd y = s.surface.positions.col(1) / s.surface.positions.col(1).cwiseAbs().maxCoeff();
    const double scale = std::ldexp(1.0, 1020);
    RenderOptions options = small("front");
    options.color_bar = false;  // its labels print the range
    options.isolines = 4;
    options.range = std::array<double, 2>{-1.0, 1.0};
    const RenderResult unit = render_tessellation(s.surface, y, options);
    options.range = std::array<double, 2>{-scale, scale};
    const RenderResult huge = render_tessellation(s.surface, Eigen::VectorXd(scale * y), options);
    EXPECT_EQ(count_different(unit.image, huge.image), 0);
    // The picture is not one colour: the field and its isolines show.
    std::set<std::tuple<int, int, int>> colours;
    for (int py = 0; py < unit.image.height; ++py) {
        for (int px = 0; px < unit.image.width; ++px) {
            const Rgb c = unit.image.pixel(px, py);
            colours.insert({c.r, c.g, c.b});
        }
    }
    EXPECT_GT(colours.size(), 100U);
}

TEST(Render, IsDeterministicAndViewsDiffer) {
    const Scene s("genus2", SchemeKind::CatmullClark, 4);
    const RenderResult a = render_tessellation(s.surface, s.surface.mean_curvature, small());
    const RenderResult b = render_tessellation(s.surface, s.surface.mean_curvature, small());
    EXPECT_EQ(a.image.pixels, b.image.pixels);
    const RenderResult top = render_tessellation(s.surface, s.surface.mean_curvature, small("top"));
    const RenderResult side = render_tessellation(s.surface, s.surface.mean_curvature, small("30,10"));
    EXPECT_GT(count_different(a.image, top.image), 2000);
    EXPECT_GT(count_different(top.image, side.image), 2000);
}

TEST(Render, BackgroundAndSizeAreHonoured) {
    const Scene s("icosahedron", SchemeKind::Loop, 3);
    RenderOptions options = small();
    options.width = 64;
    options.height = 48;
    options.background = {0, 0, 0};
    options.supersampling = 1;
    const RenderResult r = render_tessellation(s.surface, {}, options);
    EXPECT_EQ(r.image.pixels.size(), std::size_t{64} * 48 * 3);
    EXPECT_EQ(r.image.pixel(0, 0), (Rgb{0, 0, 0}));
    EXPECT_GT(r.coverage, 0.2);
}

TEST(Render, RefusesBadInput) {
    const Scene s("cube", SchemeKind::CatmullClark, 2);
    RenderOptions options = small();
    Eigen::VectorXd field = s.surface.positions.col(0);
    field(7) = std::nan("");
    try {
        (void)render_tessellation(s.surface, field, options);
        ADD_FAILURE() << "expected an InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("point 7 (ptex face 0"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)render_tessellation(s.surface, Eigen::VectorXd::Zero(3), options), InputError);
    options.range = std::array<double, 2>{1.0, 0.0};
    EXPECT_THROW((void)render_tessellation(s.surface, s.surface.positions.col(0), options), InputError);
    options = small();
    options.width = 8;
    EXPECT_THROW((void)render_tessellation(s.surface, {}, options), InputError);
    options = small();
    options.supersampling = 5;
    EXPECT_THROW((void)render_tessellation(s.surface, {}, options), InputError);
    EXPECT_THROW((void)render_tessellation(LimitTessellation{}, {}, small()), InputError);
    ControlPolygon bad{s.X(), {{0, 99}}};
    EXPECT_THROW((void)render_tessellation(s.surface, {}, small(), bad), InputError);
}

TEST(Render, TriangleSurfaceForGltfCarriesLinearColoursAndTheField) {
    const Scene s("cube", SchemeKind::CatmullClark, 2);
    const Eigen::VectorXd z = s.surface.positions.col(2);
    const TriangleSurface plain = triangle_surface(s.surface);
    EXPECT_EQ(plain.positions, s.surface.positions);
    EXPECT_EQ(plain.colors.rows(), 0);
    const TriangleSurface coloured = triangle_surface(s.surface, z, "height", Colormap::Viridis);
    ASSERT_EQ(coloured.colors.rows(), s.surface.num_points());
    Index lowest = 0;
    z.minCoeff(&lowest);
    const Eigen::Vector3d first = colormap_color(Colormap::Viridis, 0.0);
    EXPECT_NEAR(coloured.colors(lowest, 0), first.x(), 1e-6);
    EXPECT_NEAR(coloured.colors(lowest, 2), first.z(), 1e-6);
    EXPECT_EQ(coloured.colors(lowest, 3), 1.0f);
    EXPECT_EQ(coloured.scalar, z);
    EXPECT_EQ(coloured.scalar_name, "height");
}

}  // namespace
}  // namespace limsurf::test
