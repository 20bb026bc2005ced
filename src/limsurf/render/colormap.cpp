#include "limsurf/render/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "limsurf/core/error.h"

namespace limsurf {
namespace {

constexpr std::array<std::array<double, 3>, 256> viridis_table =
#include "viridis_table.inc"
    ;

Eigen::Vector3d viridis(double t) {
    const double x = t * 255.0;
    const auto i = std::min(static_cast<std::size_t>(x), std::size_t{254});
    const double f = x - static_cast<double>(i);
    const auto& a = viridis_table[i];
    const auto& b = viridis_table[i + 1];
    return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

// Moreland's Msh space (ISVC 2009, §4 and its appendix): CIELAB with the D65 white of sRGB, in
// polar form (M the magnitude, s the angle from the lightness axis, h the hue angle).
const Eigen::Vector3d d65_white{0.95047, 1.0, 1.08883};

double linear_to_srgb(double c) {
    return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

double lab_f(double t) {
    return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0;
}

double lab_f_inverse(double f) {
    return f * f * f > 0.008856 ? f * f * f : (f - 16.0 / 116.0) / 7.787;
}

Eigen::Vector3d srgb_to_msh(const Eigen::Vector3d& srgb) {
    const Eigen::Vector3d rgb{srgb_to_linear(srgb.x()), srgb_to_linear(srgb.y()), srgb_to_linear(srgb.z())};
    Eigen::Matrix3d to_xyz;
    to_xyz << 0.4124, 0.3576, 0.1805, 0.2126, 0.7152, 0.0722, 0.0193, 0.1192, 0.9505;
    const Eigen::Vector3d xyz = (to_xyz * rgb).cwiseQuotient(d65_white);
    const double L = 116.0 * lab_f(xyz.y()) - 16.0;
    const double a = 500.0 * (lab_f(xyz.x()) - lab_f(xyz.y()));
    const double b = 200.0 * (lab_f(xyz.y()) - lab_f(xyz.z()));
    const double M = std::sqrt(L * L + a * a + b * b);
    const double s = M > 1e-3 ? std::acos(L / M) : 0.0;
    const double h = s > 1e-3 ? std::atan2(b, a) : 0.0;
    return {M, s, h};
}

Eigen::Vector3d msh_to_srgb(const Eigen::Vector3d& msh) {
    const double L = msh.x() * std::cos(msh.y());
    const double a = msh.x() * std::sin(msh.y()) * std::cos(msh.z());
    const double b = msh.x() * std::sin(msh.y()) * std::sin(msh.z());
    const double fy = (L + 16.0) / 116.0;
    const Eigen::Vector3d xyz =
        Eigen::Vector3d{lab_f_inverse(fy + a / 500.0), lab_f_inverse(fy), lab_f_inverse(fy - b / 200.0)}.cwiseProduct(
            d65_white);
    Eigen::Matrix3d to_rgb;
    to_rgb << 3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570;
    const Eigen::Vector3d rgb = to_rgb * xyz;
    return {std::clamp(linear_to_srgb(rgb.x()), 0.0, 1.0), std::clamp(linear_to_srgb(rgb.y()), 0.0, 1.0),
            std::clamp(linear_to_srgb(rgb.z()), 0.0, 1.0)};
}

/// Moreland's hue adjustment: interpolating from a saturated to an unsaturated colour, the hue of the
/// unsaturated end is spun so that the path does not bend through an unrelated hue.
double adjust_hue(const Eigen::Vector3d& saturated, double unsaturated_m) {
    if (saturated.x() >= unsaturated_m) {
        return saturated.z();
    }
    const double spin = saturated.y() * std::sqrt(unsaturated_m * unsaturated_m - saturated.x() * saturated.x()) /
                        (saturated.x() * std::sin(saturated.y()));
    return saturated.z() > -std::numbers::pi / 3.0 ? saturated.z() + spin : saturated.z() - spin;
}

Eigen::Vector3d cool_warm(double t) {
    Eigen::Vector3d a = srgb_to_msh(Eigen::Vector3d{59.0, 76.0, 192.0} / 255.0);
    Eigen::Vector3d b = srgb_to_msh(Eigen::Vector3d{180.0, 4.0, 38.0} / 255.0);
    // Two saturated ends of distant hues pass through a neutral white point in the middle.
    const double white_m = std::max({a.x(), b.x(), 88.0});
    if (t < 0.5) {
        b = {white_m, 0.0, 0.0};
        t *= 2.0;
    } else {
        a = {white_m, 0.0, 0.0};
        t = 2.0 * t - 1.0;
    }
    if (a.y() < 0.05 && b.y() > 0.05) {
        a.z() = adjust_hue(b, a.x());
    } else if (b.y() < 0.05 && a.y() > 0.05) {
        b.z() = adjust_hue(a, b.x());
    }
    return msh_to_srgb((1.0 - t) * a + t * b);
}

}  // namespace

double srgb_to_linear(double c) noexcept {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Eigen::Vector3d colormap_color(Colormap map, double t) {
    LIMSURF_CHECK(!std::isnan(t), InputError, "colour map position is NaN");
    t = std::clamp(t, 0.0, 1.0);
    return map == Colormap::Viridis ? viridis(t) : cool_warm(t);
}

Colormap colormap_from_name(std::string_view name) {
    if (name == "viridis") {
        return Colormap::Viridis;
    }
    if (name == "coolwarm") {
        return Colormap::CoolWarm;
    }
    throw InputError("unknown colour map '" + std::string(name) + "' (expected viridis or coolwarm)");
}

std::string colormap_name(Colormap map) {
    return map == Colormap::Viridis ? "viridis" : "coolwarm";
}

bool is_diverging(Colormap map) noexcept {
    return map == Colormap::CoolWarm;
}

}  // namespace limsurf
