// ControlMesh: a validated Topology plus one position per vertex.
#pragma once

#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/mesh/validate.h"

namespace limsurf {

class ControlMesh {
  public:
    ControlMesh() = default;

    /// @param[in] topology  validated connectivity
    /// @param[in] positions #V×3, finite
    /// @param[in] hints     scheme options the source asked for (may be empty)
    /// @throws InputError if positions has the wrong row count or a non-finite entry
    ControlMesh(Topology topology, Points positions, SchemeHints hints = {});

    [[nodiscard]] const Topology& topology() const noexcept { return topology_; }
    [[nodiscard]] const Points& positions() const noexcept { return positions_; }
    [[nodiscard]] const SchemeHints& hints() const noexcept { return hints_; }

    [[nodiscard]] Index num_vertices() const noexcept { return topology_.num_vertices(); }
    [[nodiscard]] Index num_edges() const noexcept { return topology_.num_edges(); }
    [[nodiscard]] Index num_faces() const noexcept { return topology_.num_faces(); }

    /// The same connectivity with new positions (e.g. after S0 · X).
    /// @throws InputError as the constructor
    [[nodiscard]] ControlMesh with_positions(Points positions) const;

  private:
    Topology topology_;
    Points positions_;
    SchemeHints hints_;
};

/// What to do with vertices that no face uses.
enum class IsolatedVertices {
    Drop,  ///< remove them (renumbering the rest in order) and warn in the report
    Error  ///< refuse the mesh
};

/// Options for build_control_mesh().
struct BuildOptions {
    IsolatedVertices isolated_vertices = IsolatedVertices::Drop;
    ValidateOptions validation{};
};

/// A ControlMesh together with what validation had to say about its source.
struct BuildResult {
    ControlMesh mesh;
    ValidationReport report;           ///< warnings only (errors throw)
    std::vector<Index> source_vertex;  ///< #V: index in the soup of each mesh vertex
    /// Where the mesh's elements came from, renumbered to the mesh (vertex v: line of
    /// source_vertex[v]; faces keep their numbers): for naming file and line in later errors.
    SourceMap source;
    /// The soup's face groups (materials), unchanged: faces keep their numbers. Empty when the
    /// source had none.
    FaceGroups groups;
};

/// @brief Validates @p soup and builds a ControlMesh from it.
/// @throws InputError / TopologyError naming file, line and element of the
///   first error, with the number of further problems (see validate()); InputError when
///   soup.groups is malformed (FaceGroups::check()).
[[nodiscard]] BuildResult build_control_mesh(const PolygonSoup& soup, const BuildOptions& options = {});

/// The faces, positions and tags of @p mesh as a PolygonSoup (for writers). A ControlMesh has
/// no face groups: set soup.groups from BuildResult::groups to write them.
[[nodiscard]] PolygonSoup to_polygon_soup(const ControlMesh& mesh);

/// @brief Writes @p topology's face list and sharpness tags into @p soup's face_offsets,
///   face_vertices and sharpness (to_polygon_soup's, without positions and hints).
void write_faces(const Topology& topology, PolygonSoup& soup);

}  // namespace limsurf
