// glTF 2.0 binary (.glb) output of a triangulated surface with normals and per-vertex
// colours or a scalar field: Blender, three.js and web viewers open limsurf's results.
// Specification: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html (docs/io.md "glTF").
//
// The file holds one buffer (the GLB's BIN chunk), one tightly packed bufferView per
// attribute and one for the indices, one mesh with one primitive of mode TRIANGLES, one node
// (no transform: coordinates exactly as given, so a Z-up surface lies on its side in a Y-up
// viewer), one scene, and one double-sided, non-metallic material with a white base colour
// that COLOR_0, when present, multiplies.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf {

/// A triangle soup ready for a viewer (a tessellation of the limit surface, say).
/// glTF stores 32-bit floats: positions, normals and the scalar are rounded to float on output.
struct TriangleSurface {
    /// #P×3, #P ≥ 1, finite and within the range of a float (|x| ≤ 3.4028235e38).
    Points positions;
    /// #P×3 unit vectors (length within 1e-3 of 1; they are renormalised before rounding to
    /// float), or empty (then no NORMAL attribute: viewers compute flat normals).
    Points normals;
    /// #T×3, #T ≥ 1, indices into positions; counter-clockwise seen from outside (glTF's front face).
    Eigen::Matrix<Index, Eigen::Dynamic, 3> triangles;
    /// #P×4 RGBA in [0, 1], RGB sRGB-encoded (as colour maps and colour pickers give them), or
    /// empty. glTF's COLOR_0 is linear, so RGB is converted with the sRGB transfer function
    /// (IEC 61966-2-1) and written as FLOAT VEC4; alpha is written as given. Any alpha below 1
    /// makes the material's alphaMode BLEND.
    Eigen::Matrix<float, Eigen::Dynamic, 4> colors;
    /// #P finite values within the range of a float, written as the application-specific
    /// attribute "_<NAME>" (FLOAT SCALAR, with min and max), or empty (then scalar_name is ignored).
    Eigen::VectorXd scalar;
    /// Non-empty when scalar is given. The attribute name is "_" followed by this name
    /// upper-cased with every character other than [A-Z0-9_] replaced by '_'
    /// ("mean curvature" → "_MEAN_CURVATURE"); the name itself, when valid UTF-8, becomes
    /// the accessor's "name".
    std::string scalar_name;
};

/// @brief Writes @p surface as one glTF 2.0 binary file (one mesh, one primitive of mode
///   TRIANGLES, one node, one scene; positions and normals FLOAT VEC3, COLOR_0 FLOAT VEC4,
///   indices UNSIGNED_INT, POSITION with the min/max the specification requires), atomically
///   (write_file_atomically(): on any error no file is created and an existing one is kept).
/// @details Everything is checked before anything is written. Vertex numbers in messages
///   are rows of @p surface (not vertices of a control mesh), so the errors carry no
///   ErrorElement.
/// @throws InputError naming @p path for: inconsistent sizes (normals, colors or scalar with a
///   row count other than #P or 0), no positions or no triangles, an index out of range, a
///   non-finite position, normal, colour or scalar, a position or scalar beyond the range of a
///   float, a normal that is not unit length, a colour component outside [0, 1], a scalar
///   without a name, a file that would exceed the 4 GiB a GLB can hold, or a failed write
void write_glb(const std::filesystem::path& path, const TriangleSurface& surface);

}  // namespace limsurf
