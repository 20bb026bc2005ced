// The bundled example meshes (data/meshes) and their expected invariants.
//
// The expectations come from tests/data/bundled_meshes.csv, written by
// tools/make_meshes.py together with the meshes. They are an independent
// oracle: the script counts V/E/F itself, takes genus, boundary loops and
// components from each construction, and checks them against each other.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "limsurf/refine/hierarchy.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::test {

struct BundledMesh {
    std::string name;            ///< file stem, e.g. "quad_torus"
    std::filesystem::path path;  ///< absolute path of the OBJ in data/meshes
    int num_vertices = 0;
    int num_edges = 0;
    int num_faces = 0;
    int euler_characteristic = 0;  ///< V - E + F = 2*components - 2*genus - boundary loops
    int genus = 0;
    int num_boundary_loops = 0;
    int num_components = 0;
    bool closed = false;  ///< no boundary edges
    bool triangles_only = false;
    bool quads_only = false;
    /// Sorted valences of the interior vertices whose valence is irregular
    /// (!= 4 for quad meshes, != 6 for triangle meshes), one entry per vertex;
    /// empty for mixed-degree meshes.
    std::vector<int> extraordinary_valences;
    std::string description;
};

/// All bundled meshes, in CSV order (parsed once).
/// @throws std::runtime_error when the CSV is missing or malformed
[[nodiscard]] const std::vector<BundledMesh>& bundled_meshes();

/// Meshes without boundary.
[[nodiscard]] std::vector<BundledMesh> closed_meshes();
/// Meshes with at least one boundary loop.
[[nodiscard]] std::vector<BundledMesh> meshes_with_boundary();
/// Meshes whose faces are all triangles.
[[nodiscard]] std::vector<BundledMesh> triangle_meshes();
/// Meshes whose faces are all quads.
[[nodiscard]] std::vector<BundledMesh> quad_meshes();

/// The bundled mesh called @p name.
/// @throws std::runtime_error when there is none
[[nodiscard]] const BundledMesh& find_bundled(std::string_view name);

/// The bundled mesh called @p name refined @p levels times by @p scheme (its finest level only).
/// @throws as find_bundled and refine_finest
[[nodiscard]] FinestLevel refined_bundled(std::string_view name, SchemeKind scheme, int levels);

/// A bundled mesh with the scheme that refines it with form subdivision (SEC).
struct SchemeCase {
    std::string name;
    SchemeKind scheme;
};

/// Every bundled triangle mesh under Loop and every quad mesh under Catmull–Clark, except those
/// with creases (form subdivision has no crease rules).
[[nodiscard]] std::vector<SchemeCase> form_subdivision_cases();

/// GoogleTest value printer (parameterised tests print the name).
void PrintTo(const BundledMesh& mesh, std::ostream* os);

}  // namespace limsurf::test
