// OpenSubdiv's regression shapes (tests/data/opensubdiv_shapes, extracted from OpenSubdiv's
// regression/shapes by tools/extract_opensubdiv_shapes.py): the list, the scheme each runs under,
// the ones limsurf refuses and why, and a reader of the files that shares no code with limsurf's
// OBJ reader (the witness that limsurf reads OpenSubdiv's tags as OpenSubdiv means them).
#pragma once

#include <array>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::test {

/// One regression shape.
struct OpenSubdivShape {
    std::string name;            ///< the file's stem, OpenSubdiv's shape name
    std::filesystem::path path;  ///< tests/data/opensubdiv_shapes/<name>.obj
    SchemeKind scheme;           ///< from the name's prefix: catmark, loop, bilinear
    /// Empty when limsurf reads the shape; otherwise a fragment of the error message limsurf's
    /// reader gives (the reason it refuses it).
    std::string refusal;
};

/// GoogleTest prints a shape parameter by its name.
inline void PrintTo(const OpenSubdivShape& shape, std::ostream* os) {
    *os << shape.name;
}

/// All 122 shapes in name order.
[[nodiscard]] std::vector<OpenSubdivShape> opensubdiv_shapes();

/// A shape file read the way OpenSubdiv's regression/common/shape_utils reads it: `v`, `f`
/// (1-based, `v/vt/vn` corners) and the `t` tags; other lines ignored.
struct OpenSubdivShapeFile {
    std::vector<std::array<double, 3>> positions;
    std::vector<std::vector<Index>> faces;  ///< 0-based
    struct Crease {
        Index v0, v1;
        double sharpness;
    };
    std::vector<Crease> creases;
    std::vector<std::pair<Index, double>> corners;
    std::vector<Index> holes;
    SchemeHints hints;
};

/// @throws std::runtime_error when the file cannot be read or a line is malformed
[[nodiscard]] OpenSubdivShapeFile read_opensubdiv_shape(const std::filesystem::path& path);

/// @p t with every edge and vertex sharpness rounded to float, as Far stores it (a file's "0.1" is
/// 0.1f to Far): the input both sides of a peer test get.
[[nodiscard]] Topology with_float_sharpness(const Topology& t);

}  // namespace limsurf::test
