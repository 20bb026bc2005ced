// The subdivision schemes and their options (OpenSubdiv's Sdc::SchemeType and
// Sdc::Options, as limsurf spells them). See docs/conventions.md "Sharpness".
#pragma once

#include "limsurf/mesh/sharpness.h"

namespace limsurf {

/// The refinement rules limsurf implements.
enum class SchemeKind {
    CatmullClark,  ///< quads out, any polygon in (n-gons are quadrangulated by the first step)
    Loop,          ///< triangles in and out
    DooSabin,      ///< dual scheme, any polygon in
    Bilinear,      ///< quad split, linear interpolation (any polygon in)
    Linear,        ///< triangle midpoint split, linear interpolation
    C2g0           ///< triangles with valences 3 and 6 only: C² with flexible curvature (scheme/c2g0.h)
};

/// Stable lower-case names as the CLI spells them ("catmull-clark", "doo-sabin").
[[nodiscard]] const char* to_string(SchemeKind kind) noexcept;

/// Options shared by the schemes. The defaults are what most tools mean.
struct SchemeOptions {
    /// Boundary rule (Catmull–Clark, Loop). OpenSubdiv's default in Far is None;
    /// limsurf's is EdgeAndCorner (boundary edges are creases, one-face corners are corners).
    BoundaryInterpolation boundary = BoundaryInterpolation::EdgeAndCorner;
    /// How semi-sharp crease values decay from level to level.
    CreasingMethod creasing = CreasingMethod::Uniform;
    /// Rule for triangles under Catmull–Clark.
    TriangleSubdivision triangles = TriangleSubdivision::CatmullClark;
};

}  // namespace limsurf
