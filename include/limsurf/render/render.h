// Pictures of the limit surface: a small deterministic software rasterizer (no display server, no
// GPU, no global state) that draws a tessellation (tessellation.h) shaded by a headlight, optionally
// coloured by a scalar field through a colour map (colormap.h) with a colour bar, isolines of the
// field, and the control polygon drawn over it (docs/guide/render.md).
//
// What a picture shows:
//   - The surface through an orthographic camera (camera.h) fitted into the image with a margin of 5%
//     of the smaller side (the control polygon is fitted too when it is drawn). The colour bar, when
//     drawn, takes a strip on the right.
//   - Shading: a headlight, the light at the viewer: colour × (a + (1 − a)|n·d|), a = 0.25 ambient,
//     n the interpolated unit normal, d the direction towards the viewer (camera.toward_viewer). A
//     surface facing the viewer shows its colour exactly; the back side of an open surface is shaded
//     alike at 85%.
//   - Field colours: t = (f − lo)/(hi − lo) clamped to [0, 1], the colour map at t (t = 1/2 when
//     hi = lo). The field is interpolated linearly in each triangle and mapped per pixel.
//   - Isolines: k = 1..N at lo + k (hi − lo)/(N + 1), drawn about one pixel wide where the interpolated
//     field crosses a level (distance to the level divided by the field's gradient on screen).
//   - Control polygon: its edges as dark lines one pixel wide, hidden behind the surface by the depth
//     buffer, with a depth bias of 1% of the scene's depth so that edges lying on the surface show.
//   - Anti-aliasing by supersampling: each pixel is the mean of s × s samples.
// Deterministic: the same input gives the same pixels on every run and thread count.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/io/gltf.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/render/camera.h"
#include "limsurf/render/colormap.h"
#include "limsurf/render/image.h"
#include "limsurf/render/tessellation.h"

namespace limsurf {

/// Options of render_tessellation().
struct RenderOptions {
    View view{};            ///< iso by default
    int width = 1200;       ///< pixels, 16..8192
    int height = 900;       ///< pixels, 16..8192
    int supersampling = 2;  ///< samples per pixel along each axis, 1..4
    Colormap colormap = Colormap::Viridis;
    /// The field values at the colour map's ends; empty: the field's minimum and maximum (for a
    /// diverging map, ±max|f|, so that 0 is neutral).
    std::optional<std::array<double, 2>> range;
    int isolines = 0;       ///< number of isolines, 0..100
    bool color_bar = true;  ///< draw the colour bar with its min and max labels (only with a field)
    Rgb background{255, 255, 255};
    Rgb surface{178, 190, 210};  ///< colour of the surface without a field
    Rgb lines{25, 25, 25};       ///< isolines and control polygon
    int num_threads = 0;         ///< threads for shading the pixels; 0: hardware concurrency (same image)
};

/// The control polygon to draw over the surface: points and the edges between them.
struct ControlPolygon {
    Points points;                            ///< #V×3
    std::vector<std::array<Index, 2>> edges;  ///< pairs of indices into points
};

/// @brief The edges of @p topology with control points @p X (#V×3).
/// @throws InputError when X does not have one row per vertex
[[nodiscard]] ControlPolygon control_polygon(const Topology& topology, const Points& X);

/// A pixel rectangle [x0, x1) × [y0, y1).
struct PixelBox {
    int x0 = 0;
    int y0 = 0;
    int x1 = 0;
    int y1 = 0;
};

/// What render_tessellation() drew.
struct RenderResult {
    Image image;
    Camera camera;          ///< maps points of space to pixel coordinates of image
    double coverage = 0.0;  ///< fraction of the image's samples the surface covers, 0..1
    bool has_field = false;
    double field_min = 0.0;  ///< of the field over the tessellation's points (0 without a field)
    double field_max = 0.0;
    std::array<double, 2> range{0.0, 0.0};  ///< the field values at the colour map's ends
    std::optional<PixelBox> color_bar;      ///< the bar itself (labels beside it), when drawn: 0 at the bottom
};

/// @brief Renders @p surface, coloured by @p field when it is not empty, with @p overlay's edges on top.
/// @param field #P values at the tessellation's points (evaluate_vertex_field(), tessellation curvatures), or empty
/// @throws InputError for options out of range, a field of the wrong length or with a value that is not
///   finite (naming the point and its ptex face), a range with lo > hi or not finite, overlay edges out of range,
///   or an empty tessellation
[[nodiscard]] RenderResult render_tessellation(const LimitTessellation& surface, const Eigen::VectorXd& field,
                                               const RenderOptions& options, const ControlPolygon& overlay = {});

/// The colour map's range for @p field: @p range when given, else min..max (a diverging map: ±max|f|).
/// @throws InputError for an empty field, a non-finite value, or a range with lo > hi or not finite
[[nodiscard]] std::array<double, 2> field_range(const Eigen::VectorXd& field, Colormap colormap,
                                                const std::optional<std::array<double, 2>>& range = std::nullopt);

/// @brief @p surface as a glTF triangle surface (io/gltf.h): positions, normals, and, when @p field is
///   not empty, the colour map's colours (sRGB, alpha 1; write_glb makes them linear, as glTF's COLOR_0 is) and the
///   field itself as the scalar attribute called @p name.
/// @throws InputError as field_range()
[[nodiscard]] TriangleSurface triangle_surface(const LimitTessellation& surface, const Eigen::VectorXd& field = {},
                                               const std::string& name = "field", Colormap colormap = Colormap::Viridis,
                                               const std::optional<std::array<double, 2>>& range = std::nullopt);

}  // namespace limsurf
