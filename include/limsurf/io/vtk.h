// VTK output for visualising per-vertex data (ParaView, VisIt, PyVista).
#pragma once

#include <filesystem>
#include <ostream>
#include <span>

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

}  // namespace limsurf
