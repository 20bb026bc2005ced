// Colour maps for scalar fields on the limit surface: viridis (perceptually uniform, sequential) and
// Moreland's cool-warm (diverging, for signed fields such as mean curvature). Colours are sRGB
// components in [0, 1], as they are written to PNG files.
#pragma once

#include <string>
#include <string_view>

#include <Eigen/Core>

namespace limsurf {

/// A colour map from [0, 1] to sRGB.
enum class Colormap {
    /// matplotlib's viridis (van der Walt, Smith, Firing 2015; CC0), its 256-entry table interpolated linearly:
    /// dark blue-violet (0.267, 0.005, 0.329) at 0 to yellow (0.993, 0.906, 0.144) at 1, lightness increasing.
    Viridis,
    /// K. Moreland's diverging cool-warm map ("Diverging Color Maps for Scientific Visualization", ISVC 2009):
    /// blue (59, 76, 192)/255 at 0 through light grey (221, 221, 221)/255 at 1/2 to red (180, 4, 38)/255 at 1,
    /// interpolated in his Msh colour space (CIELAB in polar form, D65).
    CoolWarm
};

/// @brief The colour of @p map at @p t (clamped to [0, 1]), sRGB components in [0, 1].
/// @throws InputError when t is NaN
[[nodiscard]] Eigen::Vector3d colormap_color(Colormap map, double t);

/// @brief The map called "viridis" or "coolwarm".
/// @throws InputError for any other name
[[nodiscard]] Colormap colormap_from_name(std::string_view name);

/// "viridis" or "coolwarm".
[[nodiscard]] std::string colormap_name(Colormap map);

/// True for maps whose middle is neutral (CoolWarm): an automatic range is symmetric about 0.
[[nodiscard]] bool is_diverging(Colormap map) noexcept;

/// @brief An sRGB component in [0, 1] as linear light (IEC 61966-2-1), as glTF's COLOR_0 expects.
[[nodiscard]] double srgb_to_linear(double c) noexcept;

}  // namespace limsurf
