// Per-vertex data written next to a mesh (PLY properties, VTK point data).
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "limsurf/core/types.h"

namespace limsurf {

/// A named per-vertex quantity: #V×1 (scalar) or #V×3 (vector), finite.
struct VertexField {
    std::string name;        ///< non-empty; sanitised on output (see sanitize_field_name())
    Eigen::MatrixXd values;  ///< #V×1 or #V×3
};

/// @brief @p name with every character other than [A-Za-z0-9_.-] replaced by '_'
///   (so "mean curvature" becomes "mean_curvature").
[[nodiscard]] std::string sanitize_field_name(std::string_view name);

/// @brief Checks one field against a mesh of @p num_vertices vertices.
/// @throws InputError "field 'NAME': ..." for an empty name, a shape other than
///   #V×1 / #V×3, or a non-finite value (naming its row and column)
void validate_vertex_field(const VertexField& field, Index num_vertices);

/// @brief validate_vertex_field() on each field, and checks that the sanitised names are
///   distinct and do not collide with @p reserved names (e.g. "x", "y", "z" in PLY).
/// @throws InputError naming the offending field
void validate_vertex_fields(std::span<const VertexField> fields, Index num_vertices,
                            std::span<const std::string_view> reserved = {});

/// What a file of values holds one value per: the word its error messages use.
enum class ValuesPer { Vertex, Edge };

/// @brief Reads one finite number per line ('#' comments and blank lines skipped), @p count of
///   them: per-vertex data such as a right-hand side, or (@p per Edge) a 1-form.
/// @throws InputError naming the file (and line): cannot open, a directory, a line that is not
///   one finite number, more or fewer than @p count values ("… the mesh has 12 edges")
[[nodiscard]] Eigen::VectorXd read_vertex_values(const std::filesystem::path& path, Index count,
                                                 ValuesPer per = ValuesPer::Vertex);

/// @brief Writes @p values one per line with 17 significant digits (what read_vertex_values reads
///   back bit for bit: per-vertex or per-edge data such as a 1-form), atomically (io/atomic_file.h).
/// @throws InputError naming the file when a value is not finite or the file cannot be written
void write_values(const std::filesystem::path& path, const Eigen::VectorXd& values);

}  // namespace limsurf
