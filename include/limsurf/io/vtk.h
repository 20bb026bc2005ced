// VTK output for visualising per-vertex data (ParaView, VisIt, PyVista), and reading one
// per-point scalar back (a solution to render, say).
#pragma once

#include <filesystem>
#include <ostream>
#include <span>
#include <string>

#include <Eigen/Core>

#include "limsurf/io/mesh_io.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf {

/// @brief Writes legacy ASCII VTK ("# vtk DataFile Version 3.0", DATASET POLYDATA):
///   POINTS double, POLYGONS, and POINT_DATA with `SCALARS name double 1` (LOOKUP_TABLE
///   default) for #V×1 fields and `VECTORS name double` for #V×3 fields. Names are
///   sanitised (sanitize_field_name()).
/// @throws InputError for a malformed soup, an invalid field or a failed stream
void write_vtk(std::ostream& out, const PolygonSoup& soup, std::span<const VertexField> fields);

/// @brief Writes an ASCII XML UnstructuredGrid (.vtu): Float64 points, Int64 connectivity
///   and offsets, UInt8 types (all 7, VTK_POLYGON), and one PointData array per field.
/// @throws InputError as write_vtk()
void write_vtu(std::ostream& out, const PolygonSoup& soup, std::span<const VertexField> fields);

/// @brief Writes @p soup with @p fields to @p path atomically, choosing the format by
///   extension (case-insensitive): .ply (encoding from @p options), .vtk or .vtu.
/// @throws InputError for another extension, invalid fields, or a failed write
void write_vertex_data(const std::filesystem::path& path, const PolygonSoup& soup, std::span<const VertexField> fields,
                       const WriteOptions& options = {});

/// @brief Reads the per-point scalar called @p name from a legacy ASCII VTK file: `SCALARS name type`
///   (one component) with its `LOOKUP_TABLE` line under POINT_DATA, as write_vtk() writes it, or a
///   one-component array of a FIELD there. Other sections (POINTS, cells, vectors, cell data, ...) are
///   skipped by their counts; reading stops at the array asked for.
/// @return one value per point (the count of POINT_DATA)
/// @throws InputError "FILE:LINE: ..." for a file that cannot be opened, a header other than
///   "# vtk DataFile Version ...", BINARY data, a malformed section, a POINT_DATA count that differs from
///   POINTS, a section it does not know (before the array), an array of that name with more than one
///   component or under CELL_DATA, a value that is not a number or not finite (naming the point), or
///   no such array (listing the point scalars the file has)
[[nodiscard]] Eigen::VectorXd read_vtk_point_scalar(const std::filesystem::path& path, const std::string& name);

}  // namespace limsurf
