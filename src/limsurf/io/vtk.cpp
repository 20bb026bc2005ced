#include "limsurf/io/vtk.h"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>

#include "limsurf/core/error.h"
#include "limsurf/detail/io_text.h"
#include "limsurf/io/atomic_file.h"

namespace limsurf {
namespace {

void write_row(std::ostream& out, const Eigen::MatrixXd& values, Eigen::Index row) {
    for (Eigen::Index c = 0; c < values.cols(); ++c) {
        if (c > 0) {
            out << ' ';
        }
        detail::io_write_double(out, values(row, c));
    }
    out << '\n';
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

}  // namespace

void write_vtk(std::ostream& out, const PolygonSoup& soup, std::span<const VertexField> fields) {
    detail::io_check_soup(soup);
    validate_vertex_fields(fields, soup.num_vertices());
    const Index nv = soup.num_vertices();
    const Index nf = soup.num_faces();
    out << "# vtk DataFile Version 3.0\n"
        << "limsurf\n"
        << "ASCII\n"
        << "DATASET POLYDATA\n"
        << "POINTS " << nv << " double\n";
    for (Index v = 0; v < nv; ++v) {
        for (Index c = 0; c < 3; ++c) {
            if (c > 0) {
                out << ' ';
            }
            detail::io_write_double(out, soup.positions(v, c));
        }
        out << '\n';
    }
    out << "POLYGONS " << nf << ' ' << (static_cast<std::size_t>(nf) + soup.face_vertices.size()) << '\n';
    for (Index f = 0; f < nf; ++f) {
        const auto corners = soup.face(f);
        out << corners.size();
        for (const Index v : corners) {
            out << ' ' << v;
        }
        out << '\n';
    }
    if (!fields.empty()) {
        out << "POINT_DATA " << nv << '\n';
        for (const VertexField& field : fields) {
            const std::string name = sanitize_field_name(field.name);
            if (field.values.cols() == 1) {
                out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
            } else {
                out << "VECTORS " << name << " double\n";
            }
            for (Index v = 0; v < nv; ++v) {
                write_row(out, field.values, v);
            }
        }
    }
    detail::io_check_written(out, "VTK");
}

void write_vtu(std::ostream& out, const PolygonSoup& soup, std::span<const VertexField> fields) {
    detail::io_check_soup(soup);
    validate_vertex_fields(fields, soup.num_vertices());
    const Index nv = soup.num_vertices();
    const Index nf = soup.num_faces();
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << nv << "\" NumberOfCells=\"" << nf << "\">\n";
    // Sanitised names contain only [A-Za-z0-9_.-]: no XML escaping needed.
    std::string scalars;
    std::string vectors;
    for (const VertexField& field : fields) {
        std::string& first = field.values.cols() == 1 ? scalars : vectors;
        if (first.empty()) {
            first = sanitize_field_name(field.name);
        }
    }
    out << "      <PointData";
    if (!scalars.empty()) {
        out << " Scalars=\"" << scalars << '"';
    }
    if (!vectors.empty()) {
        out << " Vectors=\"" << vectors << '"';
    }
    out << ">\n";
    for (const VertexField& field : fields) {
        out << "        <DataArray type=\"Float64\" Name=\"" << sanitize_field_name(field.name)
            << "\" NumberOfComponents=\"" << field.values.cols() << "\" format=\"ascii\">\n";
        for (Index v = 0; v < nv; ++v) {
            out << "          ";
            write_row(out, field.values, v);
        }
        out << "        </DataArray>\n";
    }
    out << "      </PointData>\n"
        << "      <Points>\n"
        << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (Index v = 0; v < nv; ++v) {
        out << "          ";
        for (Index c = 0; c < 3; ++c) {
            if (c > 0) {
                out << ' ';
            }
            detail::io_write_double(out, soup.positions(v, c));
        }
        out << '\n';
    }
    out << "        </DataArray>\n"
        << "      </Points>\n"
        << "      <Cells>\n"
        << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (Index f = 0; f < nf; ++f) {
        out << "         ";
        for (const Index v : soup.face(f)) {
            out << ' ' << v;
        }
        out << '\n';
    }
    out << "        </DataArray>\n"
        << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (Index f = 0; f < nf; ++f) {
        out << "          " << soup.face_offsets[static_cast<std::size_t>(f) + 1] << '\n';
    }
    out << "        </DataArray>\n"
        << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (Index f = 0; f < nf; ++f) {
        out << "          7\n";
    }
    out << "        </DataArray>\n"
        << "      </Cells>\n"
        << "    </Piece>\n"
        << "  </UnstructuredGrid>\n"
        << "</VTKFile>\n";
    detail::io_check_written(out, "VTU");
}

void write_vertex_data(const std::filesystem::path& path, const PolygonSoup& soup, std::span<const VertexField> fields,
                       const WriteOptions& options) {
    const std::string ext = lower_extension(path);
    if (ext == ".ply") {
        write_file_atomically(path, [&](std::ostream& out) { write_ply(out, soup, options.ply_encoding, fields); });
    } else if (ext == ".vtk") {
        write_file_atomically(path, [&](std::ostream& out) { write_vtk(out, soup, fields); });
    } else if (ext == ".vtu") {
        write_file_atomically(path, [&](std::ostream& out) { write_vtu(out, soup, fields); });
    } else {
        throw InputError(path.string() + ": unknown vertex data format '" + path.extension().string() +
                         "' (expected .ply, .vtk or .vtu)");
    }
}

}  // namespace limsurf
