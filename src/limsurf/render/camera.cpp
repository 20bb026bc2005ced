#include "limsurf/render/camera.h"

#include <cmath>
#include <exception>
#include <limits>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

/// The whole of @p text as a finite double, or false.
bool parse_angle(std::string_view text, double& out) {
    const std::string s(text);
    if (s.empty() || s.find_first_not_of("0123456789+-.eE ") != std::string::npos) {
        return false;
    }
    std::size_t used = 0;
    try {
        out = std::stod(s, &used);
    } catch (const std::exception&) {
        return false;
    }
    return s.find_first_not_of(' ', used) == std::string::npos && std::isfinite(out);
}

}  // namespace

View parse_view(std::string_view text) {
    if (text == "iso") {
        return View{};
    }
    if (text == "front") {
        return View{-90.0, 0.0};
    }
    if (text == "top") {
        return View{-90.0, 90.0};
    }
    const auto comma = text.find(',');
    View view;
    LIMSURF_CHECK(comma != std::string_view::npos && parse_angle(text.substr(0, comma), view.azimuth) &&
                      parse_angle(text.substr(comma + 1), view.elevation),
                  InputError, "view '", text, "': expected iso, front, top or AZIMUTH,ELEVATION in degrees");
    LIMSURF_CHECK(view.elevation >= -90.0 && view.elevation <= 90.0, InputError, "view '", text, "': elevation ",
                  view.elevation, " is outside -90..90");
    return view;
}

Camera fit_camera(const View& view, const Points& points, double x0, double y0, double x1, double y1) {
    LIMSURF_CHECK(points.rows() > 0, InputError, "nothing to fit into the picture");
    LIMSURF_CHECK(points.allFinite(), InputError, "a point to fit into the picture is not finite");
    LIMSURF_CHECK(x1 > x0 && y1 > y0, InputError, "the picture's box [", x0, ", ", x1, "] x [", y0, ", ", y1,
                  "] is empty");
    const double a = view.azimuth * std::numbers::pi / 180.0;
    const double e = view.elevation * std::numbers::pi / 180.0;
    Camera camera;
    camera.toward_viewer = {std::cos(e) * std::cos(a), std::cos(e) * std::sin(a), std::sin(e)};
    camera.right = {-std::sin(a), std::cos(a), 0.0};
    camera.up = camera.toward_viewer.cross(camera.right);
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    Eigen::Vector2d hi = -lo;
    for (Index p = 0; p < points.rows(); ++p) {
        const Eigen::Vector3d x = points.row(p);
        const Eigen::Vector2d s{camera.right.dot(x), camera.up.dot(x)};
        lo = lo.cwiseMin(s);
        hi = hi.cwiseMax(s);
    }
    const Eigen::Vector2d extent = hi - lo;
    const double sx = extent.x() > 0.0 ? (x1 - x0) / extent.x() : std::numeric_limits<double>::infinity();
    const double sy = extent.y() > 0.0 ? (y1 - y0) / extent.y() : std::numeric_limits<double>::infinity();
    camera.scale = std::isfinite(std::min(sx, sy)) ? std::min(sx, sy) : 1.0;
    camera.origin = 0.5 * (lo + hi);
    camera.centre = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
    return camera;
}

}  // namespace limsurf
