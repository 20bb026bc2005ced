#include "limsurf/io/vtk.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
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

std::string upper(std::string_view token) {
    std::string out(token);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return out;
}

/// Legacy VTK after its three header lines: whitespace-separated tokens, each with its line.
class VtkTokens {
  public:
    VtkTokens(std::istream& in, std::string file) : lines_(in, file), file_(std::move(file)) {}

    /// The next line as it is (the header), or false at the end.
    bool next_line(std::string& line) {
        const bool ok = lines_.next(line);
        line_ = lines_.line_number();
        return ok;
    }
    /// The next token, or empty at the end of the file.
    std::optional<std::string> next() {
        while (position_ >= tokens_.size()) {
            if (!lines_.next(text_)) {
                return std::nullopt;
            }
            line_ = lines_.line_number();
            detail::io_split(text_, tokens_);
            position_ = 0;
        }
        return std::string(tokens_[position_++]);
    }
    /// Puts back the token next() just returned.
    void unread() noexcept { --position_; }
    /// The next token; fails naming @p what at the end of the file.
    std::string require(const std::string& what) {
        std::optional<std::string> token = next();
        if (!token) {
            fail("unexpected end of file: expected " + what);
        }
        return *token;
    }
    /// A count (a non-negative integer).
    long long count(const std::string& what) {
        const std::string token = require(what);
        const long long n = detail::io_to_int(token, file_, line_);
        if (n < 0 || static_cast<unsigned long long>(n) > detail::io_max_count) {
            fail(what + " " + detail::io_quote(token) + " is out of range");
        }
        return n;
    }
    /// Skips @p n values of section @p section.
    void skip(long long n, const std::string& section) {
        for (long long k = 0; k < n; ++k) {
            if (!next()) {
                fail("unexpected end of file in " + section + ": " + std::to_string(n - k) + " more values expected");
            }
        }
    }
    [[noreturn]] void fail(const std::string& what) const { detail::io_fail(file_, line_, what); }
    [[nodiscard]] long long line() const noexcept { return line_; }
    [[nodiscard]] const std::string& file() const noexcept { return file_; }

  private:
    detail::IoLineReader lines_;
    std::string file_;
    std::string text_;
    std::vector<std::string_view> tokens_;
    std::size_t position_ = 0;
    long long line_ = 0;
};

void read_vtk_header(VtkTokens& in) {
    std::string line;
    if (!in.next_line(line) || line.rfind("# vtk DataFile", 0) != 0) {
        in.fail("not a legacy VTK file (expected '# vtk DataFile Version ...')");
    }
    if (!in.next_line(line)) {
        in.fail("unexpected end of file: expected the title line");
    }
    if (!in.next_line(line)) {
        in.fail("unexpected end of file: expected ASCII");
    }
    std::vector<std::string_view> tokens;
    detail::io_split(line, tokens);
    if (tokens.size() != 1 || upper(tokens[0]) != "ASCII") {
        in.fail(tokens.size() == 1 && upper(tokens[0]) == "BINARY" ? "binary VTK is not supported (write ASCII)"
                                                                   : "expected ASCII, got " + detail::io_quote(line));
    }
}

/// Reads @p n values of the array @p name (point p at the p-th value), each finite.
Eigen::VectorXd read_values(VtkTokens& in, const std::string& name, long long n) {
    std::vector<double> values;
    values.reserve(static_cast<std::size_t>(std::min(n, 1LL << 20)));
    for (long long p = 0; p < n; ++p) {
        const std::string token = in.require("value " + std::to_string(p) + " of '" + name + "'");
        const double value = detail::io_to_double(token, in.file(), in.line());
        if (!std::isfinite(value)) {
            in.fail("'" + name + "' at point " + std::to_string(p) + ": value " + detail::io_quote(token) +
                    " is not finite");
        }
        values.push_back(value);
    }
    return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

/// The state of a scan for one point scalar.
struct VtkScan {
    std::string name;
    std::optional<long long> num_points;  // POINTS n
    bool in_point_data = false;
    long long data_count = 0;  // tuples of the current POINT_DATA / CELL_DATA
    bool seen_in_cell_data = false;
    std::vector<std::string> point_scalars;
};

/// One array of a FIELD: read and returned when it is the one asked for, else skipped.
std::optional<Eigen::VectorXd> field_array(VtkTokens& in, VtkScan& scan) {
    const std::string array = in.require("a FIELD array name");
    const long long components = in.count("a number of components");
    const long long tuples = in.count("a number of tuples");
    in.require("a data type");
    const bool match = array == scan.name;
    if (scan.in_point_data && components == 1) {
        scan.point_scalars.push_back(array);
    }
    if (match && !scan.in_point_data) {
        scan.seen_in_cell_data = true;
    } else if (match) {
        if (components != 1) {
            in.fail("'" + array + "' has " + std::to_string(components) + " components: expected a scalar");
        }
        if (tuples != scan.data_count) {
            in.fail("'" + array + "' has " + std::to_string(tuples) + " tuples, POINT_DATA " +
                    std::to_string(scan.data_count));
        }
        return read_values(in, array, tuples);
    }
    in.skip(components * tuples, "FIELD array '" + array + "'");
    return std::nullopt;
}

/// SCALARS name type [components], LOOKUP_TABLE table, values: read when it is the one asked for.
std::optional<Eigen::VectorXd> scalars(VtkTokens& in, VtkScan& scan) {
    const std::string array = in.require("a SCALARS name");
    in.require("a data type");
    std::string token = in.require("LOOKUP_TABLE");
    long long components = 1;
    if (upper(token) != "LOOKUP_TABLE") {
        components = detail::io_to_int(token, in.file(), in.line());
        if (components < 1 || components > 4) {
            in.fail("SCALARS '" + array + "': " + std::to_string(components) + " components (expected 1..4)");
        }
        token = in.require("LOOKUP_TABLE");
    }
    if (upper(token) != "LOOKUP_TABLE") {
        in.fail("SCALARS '" + array + "': expected LOOKUP_TABLE, got " + detail::io_quote(token));
    }
    in.require("a lookup table name");
    if (scan.in_point_data && components == 1) {
        scan.point_scalars.push_back(array);
    }
    if (array == scan.name && !scan.in_point_data) {
        scan.seen_in_cell_data = true;
    } else if (array == scan.name) {
        if (components != 1) {
            in.fail("'" + array + "' has " + std::to_string(components) + " components: expected a scalar");
        }
        return read_values(in, array, scan.data_count);
    }
    in.skip(components * scan.data_count, "SCALARS '" + array + "'");
    return std::nullopt;
}

/// A cell section "KEYWORD n size": the classic layout (size integers), or VTK 5.1's OFFSETS and CONNECTIVITY.
void skip_cells(VtkTokens& in, const std::string& keyword) {
    const long long n = in.count("a " + keyword + " count");
    const long long size = in.count("a " + keyword + " size");
    std::optional<std::string> next = in.next();
    if (next && upper(*next) == "OFFSETS") {
        in.require("a data type");
        in.skip(n, keyword + " offsets");
        if (upper(in.require("CONNECTIVITY")) != "CONNECTIVITY") {
            in.fail(keyword + ": expected CONNECTIVITY");
        }
        in.require("a data type");
        in.skip(size, keyword + " connectivity");
    } else {
        if (next) {
            in.unread();
        }
        in.skip(size, keyword);
    }
}

/// Skips a section of the data set or its attributes; false for a keyword it does not know.
bool skip_section(VtkTokens& in, const std::string& keyword, VtkScan& scan) {
    const long long n = scan.data_count;
    if (keyword == "DATASET") {
        in.require("a data set type");
    } else if (keyword == "DIMENSIONS" || keyword == "ORIGIN" || keyword == "SPACING" || keyword == "ASPECT_RATIO") {
        in.skip(3, keyword);
    } else if (keyword == "X_COORDINATES" || keyword == "Y_COORDINATES" || keyword == "Z_COORDINATES") {
        const long long count = in.count("a coordinate count");
        in.require("a data type");
        in.skip(count, keyword);
    } else if (keyword == "VERTICES" || keyword == "LINES" || keyword == "POLYGONS" || keyword == "TRIANGLE_STRIPS" ||
               keyword == "CELLS") {
        skip_cells(in, keyword);
    } else if (keyword == "CELL_TYPES") {
        in.skip(in.count("a cell count"), keyword);
    } else if (keyword == "VECTORS" || keyword == "NORMALS") {
        in.require("a name");
        in.require("a data type");
        in.skip(3 * n, keyword);
    } else if (keyword == "TENSORS") {
        in.require("a name");
        in.require("a data type");
        in.skip(9 * n, keyword);
    } else if (keyword == "TEXTURE_COORDINATES") {
        in.require("a name");
        const long long dimension = in.count("a dimension");
        in.require("a data type");
        in.skip(dimension * n, keyword);
    } else if (keyword == "COLOR_SCALARS") {
        in.require("a name");
        in.skip(in.count("a number of values") * n, keyword);
    } else if (keyword == "LOOKUP_TABLE") {
        in.require("a name");
        in.skip(4 * in.count("a table size"), keyword);
    } else if (keyword == "GLOBAL_IDS" || keyword == "PEDIGREE_IDS") {
        in.require("a name");
        in.require("a data type");
        in.skip(n, keyword);
    } else {
        return false;
    }
    return true;
}

std::string listed(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names) {
        out += (out.empty() ? "" : ", ") + name;
    }
    return out.empty() ? "none" : out;
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

Eigen::VectorXd read_vtk_point_scalar(const std::filesystem::path& path, const std::string& name) {
    std::ifstream stream = open_input_file(path);
    VtkTokens in(stream, path.string());
    read_vtk_header(in);
    VtkScan scan;
    scan.name = name;
    while (const std::optional<std::string> token = in.next()) {
        const std::string keyword = upper(*token);
        std::optional<Eigen::VectorXd> found;
        if (keyword == "POINTS") {
            scan.num_points = in.count("a point count");
            in.require("a data type");
            in.skip(3 * *scan.num_points, "POINTS");
        } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA") {
            scan.in_point_data = keyword == "POINT_DATA";
            scan.data_count = in.count("a " + keyword + " count");
            if (scan.in_point_data && scan.num_points && scan.data_count != *scan.num_points) {
                in.fail("POINT_DATA " + std::to_string(scan.data_count) + " differs from POINTS " +
                        std::to_string(*scan.num_points));
            }
        } else if (keyword == "SCALARS") {
            found = scalars(in, scan);
        } else if (keyword == "FIELD") {
            in.require("a FIELD name");
            const long long arrays = in.count("a number of arrays");
            for (long long k = 0; k < arrays && !found; ++k) {
                found = field_array(in, scan);
            }
        } else if (!skip_section(in, keyword, scan)) {
            in.fail("unsupported VTK section " + detail::io_quote(*token) + " before the point scalar '" + name + "'");
        }
        if (found) {
            return *found;
        }
    }
    LIMSURF_CHECK(!stream.bad(), InputError, path.string(), ": read error");
    if (scan.seen_in_cell_data) {
        throw InputError(path.string() + ": '" + name + "' is cell data, not point data");
    }
    throw InputError(path.string() + ": no point scalar '" + name +
                     "' (the file's point scalars: " + listed(scan.point_scalars) + ")");
}

}  // namespace limsurf
