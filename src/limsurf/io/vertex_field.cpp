#include "limsurf/io/vertex_field.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
#include "limsurf/detail/io_text.h"
#include "limsurf/io/atomic_file.h"

namespace limsurf {

std::string sanitize_field_name(std::string_view name) {
    std::string out(name);
    for (char& c : out) {
        const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                          c == '.' || c == '-';
        if (!keep) {
            c = '_';
        }
    }
    return out;
}

void validate_vertex_field(const VertexField& field, Index num_vertices) {
    LIMSURF_CHECK(!field.name.empty(), InputError, "vertex field with an empty name");
    LIMSURF_CHECK(field.values.rows() == num_vertices && (field.values.cols() == 1 || field.values.cols() == 3),
                  InputError, "field '", field.name, "': expected ", num_vertices, "x1 or ", num_vertices,
                  "x3 values, got ", field.values.rows(), "x", field.values.cols());
    for (Eigen::Index row = 0; row < field.values.rows(); ++row) {
        for (Eigen::Index col = 0; col < field.values.cols(); ++col) {
            const double value = field.values(row, col);
            LIMSURF_CHECK(std::isfinite(value), InputError, "field '", field.name, "': row ", row,
                          (field.values.cols() == 1 ? "" : ", column "),
                          (field.values.cols() == 1 ? std::string() : std::to_string(col)), " is not finite (", value,
                          ")");
        }
    }
}

void validate_vertex_fields(std::span<const VertexField> fields, Index num_vertices,
                            std::span<const std::string_view> reserved) {
    std::vector<std::string> names(reserved.begin(), reserved.end());
    for (const VertexField& field : fields) {
        validate_vertex_field(field, num_vertices);
        const std::string name = sanitize_field_name(field.name);
        // A vector field is one array in VTK but three properties in PLY: claim every name.
        std::vector<std::string> claimed{name};
        if (field.values.cols() == 3) {
            claimed.insert(claimed.end(), {name + "_x", name + "_y", name + "_z"});
        }
        for (const std::string& column : claimed) {
            for (const std::string& taken : names) {
                LIMSURF_CHECK(column != taken, InputError, "field '", field.name, "': name '", column,
                              "' is already used");
            }
        }
        names.insert(names.end(), claimed.begin(), claimed.end());
    }
}

Eigen::VectorXd read_vertex_values(const std::filesystem::path& path, Index count, ValuesPer per) {
    const char* element = per == ValuesPer::Edge ? "edge" : "vertex";
    std::ifstream in = open_input_file(path);
    const std::string name = path.string();
    Eigen::VectorXd out(count);
    Index n = 0;
    detail::IoLineReader lines(in);
    std::string line;
    std::vector<std::string_view> tokens;
    while (lines.next(line)) {
        detail::io_split(detail::io_strip_comment(line), tokens);
        if (tokens.empty()) {
            continue;
        }
        const long long number = lines.line_number();
        if (tokens.size() != 1) {
            detail::io_fail(name, number, "expected one number, got " + std::to_string(tokens.size()) + " fields");
        }
        const double value = detail::io_to_double(tokens[0], name, number);
        if (!std::isfinite(value)) {
            detail::io_fail(name, number, "value " + detail::io_quote(tokens[0]) + " is not finite");
        }
        if (n >= count) {
            detail::io_fail(name, number, "more than " + std::to_string(count) + " values (one per " + element + ")");
        }
        out(n++) = value;
    }
    LIMSURF_CHECK(!in.bad(), InputError, name, ": read error");
    LIMSURF_CHECK(n == count, InputError, name, ": ", n, " values, but the mesh has ", count,
                  per == ValuesPer::Edge ? " edges" : " vertices");
    return out;
}

void write_values(const std::filesystem::path& path, const Eigen::VectorXd& values) {
    for (Index i = 0; i < values.size(); ++i) {
        LIMSURF_CHECK(std::isfinite(values[i]), InputError, path.string(), ": value ", i, " is ", values[i],
                      " (not finite): nothing written");
    }
    write_file_atomically(path, [&](std::ostream& out) {
        out << std::setprecision(17);
        for (Index i = 0; i < values.size(); ++i) {
            out << values[i] << '\n';
        }
    });
}

}  // namespace limsurf
