// Subdivision tags: sharpness on edges and vertices, holes, and the scheme
// hints OpenSubdiv's shape files carry (docs/conventions.md, "Sharpness").
//
// Sharpness follows OpenSubdiv's Sdc: 0 is smooth, values in (0, 10) are
// semi-sharp (decremented by one per refinement level), and values >= 10
// (limsurf::infinite_sharpness) are infinitely sharp.
#pragma once

#include <optional>
#include <vector>

#include "limsurf/core/types.h"

namespace limsurf {

/// How boundary vertices are treated (OpenSubdiv's Sdc::Options::VtxBoundaryInterpolation).
enum class BoundaryInterpolation {
    None,          ///< boundary faces are not part of the limit surface (OpenSubdiv's "holes")
    EdgeOnly,      ///< boundary edges are infinitely sharp creases
    EdgeAndCorner  ///< as EdgeOnly, and a boundary vertex in a single face is a sharp corner
};

/// How semi-sharp crease values are propagated to child edges (Sdc::Options::CreasingMethod).
enum class CreasingMethod {
    Uniform,  ///< child sharpness = parent sharpness - 1
    Chaikin   ///< child sharpness blends the sharpness of adjacent crease edges
};

/// Rule for triangles under Catmull–Clark (Sdc::Options::TriangleSubdivision).
enum class TriangleSubdivision {
    CatmullClark,  ///< the plain Catmull–Clark face/edge/vertex rules
    Smooth         ///< OpenSubdiv's modified weights that smooth triangle faces
};

/// Sharpness of the edge between vertices v0 and v1 (order irrelevant).
struct CreaseTag {
    Index v0 = invalid_index;
    Index v1 = invalid_index;
    double sharpness = 0.0;  ///< >= 0; >= infinite_sharpness means infinitely sharp
    int line = 0;            ///< 1-based line in the source file, 0 if unknown
};

/// Sharpness of a vertex (a "corner" when infinitely sharp).
struct CornerTag {
    Index vertex = invalid_index;
    double sharpness = 0.0;  ///< >= 0; >= infinite_sharpness means infinitely sharp
    int line = 0;            ///< 1-based line in the source file, 0 if unknown
};

/// A face marked as a hole (OpenSubdiv's "hole" tag): it stays in the topology
/// but is not part of the limit surface.
struct HoleTag {
    Index face = invalid_index;
    int line = 0;  ///< 1-based line in the source file, 0 if unknown
};

/// The sharpness attributes carried by a Topology.
struct SharpnessTags {
    std::vector<CreaseTag> creases;
    std::vector<CornerTag> corners;
    std::vector<HoleTag> holes;

    [[nodiscard]] bool empty() const noexcept { return creases.empty() && corners.empty() && holes.empty(); }
};

/// Scheme options a file asked for; a command-line option overrides them.
struct SchemeHints {
    std::optional<BoundaryInterpolation> boundary;
    std::optional<CreasingMethod> creasing;
    std::optional<TriangleSubdivision> triangles;

    [[nodiscard]] bool empty() const noexcept { return !boundary && !creasing && !triangles; }
};

/// Stable lower-case names ("edge-and-corner", "chaikin", "smooth"), as the CLI spells them.
[[nodiscard]] constexpr const char* to_string(BoundaryInterpolation value) noexcept {
    switch (value) {
    case BoundaryInterpolation::None:
        return "none";
    case BoundaryInterpolation::EdgeOnly:
        return "edge-only";
    case BoundaryInterpolation::EdgeAndCorner:
        return "edge-and-corner";
    }
    return "?";
}
[[nodiscard]] constexpr const char* to_string(CreasingMethod value) noexcept {
    return value == CreasingMethod::Uniform ? "uniform" : "chaikin";
}
[[nodiscard]] constexpr const char* to_string(TriangleSubdivision value) noexcept {
    return value == TriangleSubdivision::CatmullClark ? "catmull-clark" : "smooth";
}

}  // namespace limsurf
