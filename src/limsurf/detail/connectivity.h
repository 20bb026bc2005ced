// Private: the connectivity checks shared by validate() and the Topology
// constructor, so that both report exactly the same problems.
#pragma once

#include <span>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/validate.h"

namespace limsurf::detail {

/// A face list viewed without copying.
struct FaceListView {
    Index num_vertices = 0;
    std::span<const Index> offsets;   // #F+1
    std::span<const Index> vertices;  // concatenated corners
};

/// @brief Appends every connectivity and tag problem of @p faces to @p report:
///   face size, repeated and out-of-range vertices, no faces, non-manifold
///   edges and vertices, orientation, orientability, isolated vertices,
///   duplicate faces and tags that name nothing.
/// @throws InputError when the offsets themselves are malformed (not a list of faces).
void check_connectivity(const FaceListView& faces, const SharpnessTags& sharpness,
                        const SourceMap& source, ValidationReport& report);

}  // namespace limsurf::detail
