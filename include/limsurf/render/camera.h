// The orthographic camera of limsurf's pictures.
//
// A view is a direction towards the viewer given by two angles in degrees, z up: the viewer sits at
// (cos e cos a, cos e sin a, sin e) from the object. On screen, x grows to the right along
// (-sin a, cos a, 0) and y upwards along the direction toward the viewer × right (z for e = 0).
//   iso   = (-45, 35.26...): the viewer on the diagonal (1, -1, 1), x and y receding to either side;
//   front = (-90, 0): looking along +y, x to the right, z up;
//   top   = (-90, 90): looking down -z, x to the right, y up.
// A camera fits a set of points into a box of the image: the box of their projection is scaled
// uniformly to the largest size that fits and centred.
#pragma once

#include <string_view>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf {

/// A viewing direction, in degrees.
struct View {
    double azimuth = -45.0;                 ///< about z, from +x towards +y
    double elevation = 35.264389682754654;  ///< above the xy-plane, -90..90 (atan(1/√2) for iso)
};

/// @brief The view named "iso", "front", "top", or written "AZIMUTH,ELEVATION" in degrees ("30,20").
/// @throws InputError for anything else, a non-finite angle, or an elevation outside -90..90
[[nodiscard]] View parse_view(std::string_view text);

/// Maps points to pixel coordinates of an image: column x (from the left edge), row y (from the top
/// edge; pixel (i, j) covers [i, i+1) × [j, j+1)), and a depth that grows towards the viewer.
struct Camera {
    Eigen::Vector3d right = Eigen::Vector3d::UnitX();           ///< screen x in space
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();              ///< screen y in space
    Eigen::Vector3d toward_viewer = -Eigen::Vector3d::UnitY();  ///< unit, right × up
    double scale = 1.0;                                         ///< pixels per unit length
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();           ///< (right·x, up·x) of the point at `centre`
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();           ///< its pixel coordinates

    /// (column, row, depth) of @p x.
    [[nodiscard]] Eigen::Vector3d project(const Eigen::Vector3d& x) const noexcept {
        return {centre.x() + scale * (right.dot(x) - origin.x()), centre.y() - scale * (up.dot(x) - origin.y()),
                toward_viewer.dot(x)};
    }
};

/// @brief The camera of @p view that fits @p points (#P×3, P >= 1, finite) into the pixel box
///   [x0, x1] × [y0, y1]: the bounding box of their projection, scaled uniformly and centred.
///   Points that project to one pixel position get scale 1.
/// @throws InputError for no points, a non-finite point or an empty box
[[nodiscard]] Camera fit_camera(const View& view, const Points& points, double x0, double y0, double x1, double y1);

}  // namespace limsurf
