#include "limsurf/render/render.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "annotate.h"
#include "limsurf/core/error.h"
#include "limsurf/core/parallel.h"
#include "limsurf/quadrature/sampler.h"
#include "raster.h"

namespace limsurf {
namespace {

constexpr double ambient = 0.25;            // light that reaches surfaces turned away from the headlight
constexpr double back_side = 0.85;          // the back of an open surface, a little darker than its front
constexpr double isoline_half_width = 0.6;  // output pixels
constexpr std::int64_t max_samples = std::int64_t{1} << 26;

/// Where the surface and the colour bar go (output pixels).
struct Layout {
    int margin = 0;
    double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;  // the box the surface is fitted into
    std::optional<PixelBox> bar;
    int font_scale = 1;
};

Layout make_layout(const RenderOptions& options, bool wants_bar) {
    const int w = options.width;
    const int h = options.height;
    Layout layout;
    layout.margin = std::max(2, static_cast<int>(std::lround(0.05 * std::min(w, h))));
    layout.font_scale = std::max(1, std::min(w, h) / 450);
    layout.x0 = layout.margin;
    layout.y0 = layout.margin;
    layout.x1 = w - layout.margin;
    layout.y1 = h - layout.margin;
    if (!wants_bar) {
        return layout;
    }
    const int s = layout.font_scale;
    const int label_width = 9 * detail::glyph_advance * s;  // "-1.23e-05"
    const int bar_width = std::max(8, static_cast<int>(std::lround(0.02 * w)));
    PixelBox bar;
    bar.x1 = w - layout.margin - label_width - 4 * s;
    bar.x0 = bar.x1 - bar_width;
    bar.y0 = static_cast<int>(std::lround(0.15 * h));
    bar.y1 = static_cast<int>(std::lround(0.85 * h));
    const double surface_x1 = bar.x0 - layout.margin - 3 * s;  // the isoline ticks stick out 3 font pixels
    if (surface_x1 - layout.x0 < w / 3.0) {
        return layout;  // too narrow for a bar: the picture goes without
    }
    layout.x1 = surface_x1;
    layout.bar = bar;
    return layout;
}

void check_options(const RenderOptions& options) {
    LIMSURF_CHECK(options.width >= 16 && options.width <= 8192 && options.height >= 16 && options.height <= 8192,
                  InputError, "image size ", options.width, "x", options.height, " is outside 16..8192");
    LIMSURF_CHECK(options.supersampling >= 1 && options.supersampling <= 4, InputError, "supersampling ",
                  options.supersampling, " is outside 1..4");
    const std::int64_t samples =
        std::int64_t{options.width} * options.height * options.supersampling * options.supersampling;
    LIMSURF_CHECK(samples <= max_samples, InputError, "image size ", options.width, "x", options.height,
                  " with supersampling ", options.supersampling, " needs ", samples,
                  " samples, more than 2^26: lower the size or the supersampling");
    LIMSURF_CHECK(options.isolines >= 0 && options.isolines <= 100, InputError, "isolines ", options.isolines,
                  " is outside 0..100");
    LIMSURF_CHECK(std::isfinite(options.view.azimuth) && std::isfinite(options.view.elevation) &&
                      options.view.elevation >= -90.0 && options.view.elevation <= 90.0,
                  InputError, "view (", options.view.azimuth, ", ", options.view.elevation,
                  ") is not finite or its elevation is outside -90..90");
}

void check_field(const LimitTessellation& surface, const Eigen::VectorXd& field) {
    LIMSURF_CHECK(field.size() == surface.num_points(), InputError, "the field has ", field.size(),
                  " values, but the tessellation has ", surface.num_points(), " points");
    for (Index p = 0; p < surface.num_points(); ++p) {
        const SurfacePoint& at = surface.points[static_cast<std::size_t>(p)];
        LIMSURF_CHECK(std::isfinite(field(p)), InputError, "field value ", field(p), " at tessellation point ", p,
                      " (ptex face ", at.face, ", u = ", at.u, ", v = ", at.v, ") is not finite");
    }
}

void check_overlay(const ControlPolygon& overlay) {
    LIMSURF_CHECK(overlay.points.allFinite(), InputError, "a control point of the overlay is not finite");
    for (const auto& [a, b] : overlay.edges) {
        LIMSURF_CHECK(a >= 0 && b >= 0 && a < overlay.points.rows() && b < overlay.points.rows(), InputError,
                      "overlay edge (", a, ", ", b, ") is out of range (", overlay.points.rows(), " points)");
    }
}

/// The colour map sampled finely once per picture: the per-sample lookup is then a lerp.
class ColorTable {
  public:
    explicit ColorTable(Colormap map) : entries_(1025) {
        for (std::size_t k = 0; k < entries_.size(); ++k) {
            entries_[k] = colormap_color(map, static_cast<double>(k) / 1024.0);
        }
    }
    [[nodiscard]] Eigen::Vector3d at(double t) const {
        const double x = std::clamp(t, 0.0, 1.0) * 1024.0;
        const auto k = std::min(static_cast<std::size_t>(x), std::size_t{1023});
        const double f = x - static_cast<double>(k);
        return (1.0 - f) * entries_[k] + f * entries_[k + 1];
    }

  private:
    std::vector<Eigen::Vector3d> entries_;
};

Eigen::Vector3d to_unit(Rgb c) {
    return Eigen::Vector3d{double(c.r), double(c.g), double(c.b)} / 255.0;
}

Rgb to_rgb(const Eigen::Vector3d& c) {
    const auto channel = [](double x) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(x, 0.0, 1.0) * 255.0));
    };
    return {channel(c.x()), channel(c.y()), channel(c.z())};
}

/// Everything the per-sample shading reads.
struct Shading {
    const LimitTessellation& surface;
    const Eigen::VectorXd& field;
    const Points& projected;  // sample coordinates and depth of every point
    Eigen::Vector3d toward_viewer;
    const ColorTable& table;
    std::array<double, 2> range;
    int isolines = 0;
    int supersampling = 1;
    Eigen::Vector3d surface_color;
    Eigen::Vector3d line_color;
    Eigen::Vector3d background;
};

/// Where @p f lies in @p range, 0..1 inside it. In halves, which are exact: a range as wide as
/// [-1e308, 1e308] must not overflow its width to infinity (every value would map to 0).
double field_position(const std::array<double, 2>& range, double f) {
    return range[1] > range[0] ? (f / 2 - range[0] / 2) / (range[1] / 2 - range[0] / 2) : 0.5;
}

/// How strongly an isoline covers a sample with field value @p f on triangle @p t: 1 on the line, 0 beyond
/// about half a pixel from it.
double isoline_weight(const Shading& c, Index t, double f) {
    const double half_spacing = (c.range[1] / 2 - c.range[0] / 2) / (c.isolines + 1);  // halves: field_position
    if (!(half_spacing > 0.0)) {
        return 0.0;
    }
    const double g = (f / 2 - c.range[0] / 2) / half_spacing;
    const double k = std::round(g);
    if (k < 1.0 || k > c.isolines) {
        return 0.0;
    }
    // The field is linear on the triangle: its gradient on screen converts the distance in value to pixels.
    const auto corner = [&](int i) { return c.surface.triangles(t, i); };
    const Eigen::Vector3d a = c.projected.row(corner(0));
    const Eigen::Vector3d e1 = c.projected.row(corner(1)).transpose() - a;
    const Eigen::Vector3d e2 = c.projected.row(corner(2)).transpose() - a;
    const double df1 = c.field(corner(1)) / 2 - c.field(corner(0)) / 2;  // halves, as half_spacing
    const double df2 = c.field(corner(2)) / 2 - c.field(corner(0)) / 2;
    const double det = e1.x() * e2.y() - e1.y() * e2.x();
    if (det == 0.0) {
        return 0.0;
    }
    const double gx = (df1 * e2.y() - df2 * e1.y()) / det;
    const double gy = (df2 * e1.x() - df1 * e2.x()) / det;
    const double half_per_pixel = std::hypot(gx, gy) * c.supersampling;  // half the field's change per pixel
    if (!(half_per_pixel > 0.0)) {
        return 0.0;
    }
    const double distance = std::abs(g - k) * half_spacing / half_per_pixel;
    return std::clamp(1.5 - distance / isoline_half_width, 0.0, 1.0);
}

Eigen::Vector3d shade_sample(const Shading& c, const detail::SampleBuffer& buffer, std::size_t s) {
    if (buffer.line[s] != 0) {
        return c.line_color;
    }
    const Index t = buffer.triangle[s];
    if (t == invalid_index) {
        return c.background;
    }
    const double l1 = buffer.b1[s];
    const double l2 = buffer.b2[s];
    const double l0 = 1.0 - l1 - l2;
    const Index i0 = c.surface.triangles(t, 0);
    const Index i1 = c.surface.triangles(t, 1);
    const Index i2 = c.surface.triangles(t, 2);
    const Eigen::Vector3d n =
        l0 * c.surface.normals.row(i0) + l1 * c.surface.normals.row(i1) + l2 * c.surface.normals.row(i2);
    const double facing = n.norm() > 0.0 ? n.dot(c.toward_viewer) / n.norm() : 1.0;
    const double light = (ambient + (1.0 - ambient) * std::abs(facing)) * (facing < 0.0 ? back_side : 1.0);
    if (c.field.size() == 0) {
        return light * c.surface_color;
    }
    const double f = l0 * c.field(i0) + l1 * c.field(i1) + l2 * c.field(i2);
    const Eigen::Vector3d color = light * c.table.at(field_position(c.range, f));
    const double line = c.isolines > 0 ? isoline_weight(c, t, f) : 0.0;
    return (1.0 - line) * color + line * c.line_color;
}

/// Each pixel the mean of its samples.
void resolve(const Shading& c, const detail::SampleBuffer& buffer, int num_threads, Image& image) {
    const int ss = c.supersampling;
    parallel_ranges(image.height, num_threads, [&](Index begin, Index end) {
        for (int y = begin; y < end; ++y) {
            for (int x = 0; x < image.width; ++x) {
                Eigen::Vector3d sum = Eigen::Vector3d::Zero();
                for (int j = 0; j < ss; ++j) {
                    for (int i = 0; i < ss; ++i) {
                        sum += shade_sample(c, buffer, buffer.at(x * ss + i, y * ss + j));
                    }
                }
                image.set_pixel(x, y, to_rgb(sum / (ss * ss)));
            }
        }
    });
}

void draw_bar(Image& image, const PixelBox& bar, const Layout& layout, const ColorTable& table,
              const RenderOptions& options, const std::array<double, 2>& range) {
    const Eigen::Vector3d bg = to_unit(options.background);
    const Rgb ink = 0.2126 * bg.x() + 0.7152 * bg.y() + 0.0722 * bg.z() < 0.5 ? Rgb{230, 230, 230} : options.lines;
    detail::draw_color_bar(
        image, bar.x0, bar.y0, bar.x1, bar.y1, [&](double t) { return to_rgb(table.at(t)); }, ink);
    const int s = layout.font_scale;
    for (int k = 1; k <= options.isolines; ++k) {
        const double t = static_cast<double>(k) / (options.isolines + 1);
        const int y = bar.y1 - 1 - static_cast<int>(std::lround(t * (bar.y1 - bar.y0 - 1)));
        for (int x = bar.x0 - 1 - 3 * s; x < bar.x0 - 1; ++x) {
            image.set_pixel(x, y, ink);
        }
    }
    const int label_x = bar.x1 + 4 * s;
    detail::draw_text(image, label_x, bar.y0, detail::label_text(range[1]), s, ink);
    detail::draw_text(image, label_x, bar.y1 - detail::glyph_height * s, detail::label_text(range[0]), s, ink);
}

/// (column, row) in samples and depth.
Eigen::Vector3d to_samples(const Camera& camera, int supersampling, const Eigen::Vector3d& x) {
    const Eigen::Vector3d p = camera.project(x);
    return {p.x() * supersampling, p.y() * supersampling, p.z()};
}

/// The control polygon's edges, one pixel (s samples) wide.
void draw_overlay(detail::SampleBuffer& buffer, const ControlPolygon& overlay, const Camera& camera, int supersampling,
                  double bias) {
    for (const auto& [a, b] : overlay.edges) {
        detail::draw_line(buffer, to_samples(camera, supersampling, overlay.points.row(a).transpose()),
                          to_samples(camera, supersampling, overlay.points.row(b).transpose()), supersampling, bias);
    }
}

/// The tessellation's points in samples.
Points project_points(const LimitTessellation& surface, const Camera& camera, int supersampling) {
    Points projected(surface.num_points(), 3);
    for (Index p = 0; p < surface.num_points(); ++p) {
        projected.row(p) = to_samples(camera, supersampling, surface.positions.row(p).transpose()).transpose();
    }
    return projected;
}

/// The depth buffer of the surface, with the overlay's lines marked on it.
detail::SampleBuffer rasterize(const LimitTessellation& surface, const Points& projected, const ControlPolygon& overlay,
                               const Points& fitted, const Camera& camera, const RenderOptions& options,
                               const Layout& layout) {
    const int ss = options.supersampling;
    detail::SampleBuffer buffer(options.width * ss, options.height * ss);
    for (Index t = 0; t < surface.num_triangles(); ++t) {
        detail::draw_triangle(buffer, t, projected.row(surface.triangles(t, 0)), projected.row(surface.triangles(t, 1)),
                              projected.row(surface.triangles(t, 2)));
    }
    // 1% of the scene's extent: edges lying on the surface (a planar mesh) stay visible.
    const Eigen::VectorXd depth = fitted * camera.toward_viewer;
    const double extent = std::max(depth.maxCoeff() - depth.minCoeff(),
                                   std::max(layout.x1 - layout.x0, layout.y1 - layout.y0) / camera.scale);
    draw_overlay(buffer, overlay, camera, ss, 0.01 * extent);
    return buffer;
}

}  // namespace

ControlPolygon control_polygon(const Topology& topology, const Points& X) {
    LIMSURF_CHECK(X.rows() == topology.num_vertices(), InputError, "expected ", topology.num_vertices(),
                  " control points, got ", X.rows());
    ControlPolygon polygon{X, {}};
    polygon.edges.reserve(static_cast<std::size_t>(topology.num_edges()));
    for (Index e = 0; e < topology.num_edges(); ++e) {
        polygon.edges.push_back(topology.edge_vertices(e));
    }
    return polygon;
}

std::array<double, 2> field_range(const Eigen::VectorXd& field, Colormap colormap,
                                  const std::optional<std::array<double, 2>>& range) {
    if (range) {
        const auto [lo, hi] = *range;
        LIMSURF_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, InputError, "range ", lo, ", ", hi,
                      " is not finite or its minimum exceeds its maximum");
        return *range;
    }
    LIMSURF_CHECK(field.size() > 0, InputError, "no field values to take a range from");
    LIMSURF_CHECK(field.allFinite(), InputError, "the field has a value that is not finite");
    if (is_diverging(colormap)) {
        const double m = field.cwiseAbs().maxCoeff();
        return {-m, m};
    }
    return {field.minCoeff(), field.maxCoeff()};
}

RenderResult render_tessellation(const LimitTessellation& surface, const Eigen::VectorXd& field,
                                 const RenderOptions& options, const ControlPolygon& overlay) {
    check_options(options);
    LIMSURF_CHECK(surface.num_points() > 0 && surface.num_triangles() > 0, InputError,
                  "nothing to render: the tessellation is empty (no ptex face has a limit surface)");
    check_overlay(overlay);
    RenderResult result;
    result.has_field = field.size() > 0;
    if (result.has_field) {
        check_field(surface, field);
        result.field_min = field.minCoeff();
        result.field_max = field.maxCoeff();
        result.range = field_range(field, options.colormap, options.range);
    }
    const Layout layout = make_layout(options, result.has_field && options.color_bar);

    Points fitted(surface.num_points() + overlay.points.rows(), 3);
    fitted << surface.positions, overlay.points;
    result.camera = fit_camera(options.view, fitted, layout.x0, layout.y0, layout.x1, layout.y1);
    const int ss = options.supersampling;
    const Points projected = project_points(surface, result.camera, ss);
    const detail::SampleBuffer buffer = rasterize(surface, projected, overlay, fitted, result.camera, options, layout);

    const ColorTable table(options.colormap);
    const Shading shading{surface,
                          field,
                          projected,
                          result.camera.toward_viewer,
                          table,
                          result.range,
                          result.has_field ? options.isolines : 0,
                          ss,
                          to_unit(options.surface),
                          to_unit(options.lines),
                          to_unit(options.background)};
    result.image = Image(options.width, options.height, options.background);
    resolve(shading, buffer, options.num_threads, result.image);
    const auto covered =
        std::count_if(buffer.triangle.begin(), buffer.triangle.end(), [](Index t) { return t != invalid_index; });
    result.coverage = static_cast<double>(covered) / static_cast<double>(buffer.triangle.size());
    if (layout.bar) {
        draw_bar(result.image, *layout.bar, layout, table, options, result.range);
        result.color_bar = layout.bar;
    }
    return result;
}

TriangleSurface triangle_surface(const LimitTessellation& surface, const Eigen::VectorXd& field,
                                 const std::string& name, Colormap colormap,
                                 const std::optional<std::array<double, 2>>& range) {
    TriangleSurface out;
    out.positions = surface.positions;
    out.normals = surface.normals;
    out.triangles = surface.triangles;
    if (field.size() == 0) {
        return out;
    }
    check_field(surface, field);
    const std::array<double, 2> r = field_range(field, colormap, range);
    out.colors.resize(surface.num_points(), 4);
    for (Index p = 0; p < surface.num_points(); ++p) {
        const Eigen::Vector3d c = colormap_color(colormap, field_position(r, field(p)));
        // sRGB, as the colour map gives it: write_glb converts to glTF's linear COLOR_0.
        out.colors.row(p) << static_cast<float>(c.x()), static_cast<float>(c.y()), static_cast<float>(c.z()), 1.0f;
    }
    out.scalar = field;
    out.scalar_name = name;
    return out;
}

}  // namespace limsurf
