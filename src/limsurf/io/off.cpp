#include "limsurf/io/off.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
#include "limsurf/detail/io_text.h"

namespace limsurf {
namespace {

using detail::io_fail;
using detail::io_quote;

/// Smallest number of bytes one vertex line ("0 0 0") and one face line ("0") take, not
/// counting the line terminator.
constexpr std::uint64_t min_vertex_bytes = 5;
constexpr std::uint64_t min_face_bytes = 1;

/// True for "OFF" with the optional prefixes ST, C and N in that order.
bool is_off_header(std::string_view word) {
    if (word.starts_with("ST")) {
        word.remove_prefix(2);
    }
    if (word.starts_with("C")) {
        word.remove_prefix(1);
    }
    if (word.starts_with("N")) {
        word.remove_prefix(1);
    }
    return word == "OFF";
}

class OffReader {
  public:
    OffReader(std::istream& in, const std::string& file) : in_(in), reader_(in), file_(file) {
        soup_.source.file = file;
    }

    PolygonSoup run() {
        if (!next_data_line()) {
            io_fail(file_, 0, "empty file");
        }
        const std::string_view header = tokens_[0];
        if (header.find("OFF") != std::string_view::npos && !is_off_header(header)) {
            io_fail(file_, reader_.line_number(),
                    "OFF variant " + io_quote(header) + " is not supported (expected OFF, COFF, NOFF, CNOFF or STOFF)");
        }
        if (!is_off_header(header)) {
            io_fail(file_, reader_.line_number(), "expected the 'OFF' header, found " + io_quote(header));
        }
        if (tokens_.size() > 1 && tokens_[1] == "BINARY") {
            io_fail(file_, reader_.line_number(), "binary OFF is not supported");
        }
        if (tokens_.size() == 1) {
            if (!next_data_line()) {
                io_fail(file_, reader_.line_number(), "unexpected end of file: expected the counts line 'nv nf ne'");
            }
            read_counts(0);
        } else {
            read_counts(1);
        }
        read_vertices();
        read_faces();
        return std::move(soup_);
    }

  private:
    /// Next line with something other than blanks and comments, split into tokens_.
    bool next_data_line() {
        while (reader_.next(line_)) {
            detail::io_split(detail::io_strip_comment(line_), tokens_);
            if (!tokens_.empty()) {
                return true;
            }
        }
        return false;
    }

    void read_counts(std::size_t first) {
        const long long line = reader_.line_number();
        const std::size_t n = tokens_.size() - first;
        if (n != 2 && n != 3) {
            io_fail(file_, line, "expected the counts 'nv nf ne', found " + std::to_string(n) + " values");
        }
        const long long nv = detail::io_to_int(tokens_[first], file_, line);
        const long long nf = detail::io_to_int(tokens_[first + 1], file_, line);
        if (n == 3) {
            (void)detail::io_to_int(tokens_[first + 2], file_, line);  // edge count: unused
        }
        if (nv < 0 || nf < 0) {
            io_fail(file_, line, "negative vertex or face count");
        }
        const auto unv = static_cast<std::uint64_t>(nv);
        const auto unf = static_cast<std::uint64_t>(nf);
        // Every vertex and face needs some bytes: refuse counts the stream cannot hold
        // before allocating anything for them.
        const std::optional<std::uint64_t> remaining = detail::io_remaining_bytes(in_);
        sizes_checked_ = remaining.has_value();
        if (remaining) {
            const std::uint64_t cap = *remaining + 1;  // the last line may lack its newline
            const bool fits = unv <= cap / (min_vertex_bytes + 1) && unf <= cap / (min_face_bytes + 1) &&
                              unv * (min_vertex_bytes + 1) + unf * (min_face_bytes + 1) <= cap;
            if (!fits) {
                io_fail(file_, line,
                        std::to_string(nv) + " vertices and " + std::to_string(nf) +
                            " faces cannot fit in the remaining " + std::to_string(*remaining) + " bytes");
            }
        }
        if (unv > detail::io_max_count || unf > detail::io_max_count) {
            io_fail(file_, line,
                    "counts " + std::to_string(nv) + " " + std::to_string(nf) + " exceed the supported maximum " +
                        std::to_string(detail::io_max_count));
        }
        num_vertices_ = static_cast<Index>(nv);
        num_faces_ = static_cast<Index>(nf);
    }

    void read_vertices() {
        // Reserve only what the stream is known to hold (it may not be seekable).
        const auto expected =
            static_cast<std::size_t>(sizes_checked_ ? num_vertices_ : std::min<Index>(num_vertices_, Index{1} << 16));
        std::vector<double> coordinates;
        coordinates.reserve(3 * expected);
        soup_.source.vertex_lines.reserve(expected);
        for (Index v = 0; v < num_vertices_; ++v) {
            if (!next_data_line()) {
                io_fail(file_, reader_.line_number(),
                        "unexpected end of file: expected " + std::to_string(num_vertices_) + " vertices, found " +
                            std::to_string(v));
            }
            const long long line = reader_.line_number();
            if (tokens_.size() < 3) {
                io_fail(file_, line,
                        "vertex " + std::to_string(v) + " needs 3 coordinates, found " +
                            std::to_string(tokens_.size()));
            }
            for (std::size_t c = 0; c < 3; ++c) {
                coordinates.push_back(detail::io_to_double(tokens_[c], file_, line));
            }
            soup_.source.vertex_lines.push_back(static_cast<int>(line));
        }
        soup_.positions.resize(num_vertices_, 3);
        for (Index v = 0; v < num_vertices_; ++v) {
            for (Index c = 0; c < 3; ++c) {
                soup_.positions(v, c) = coordinates[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(c)];
            }
        }
    }

    void read_faces() {
        const auto expected =
            static_cast<std::size_t>(sizes_checked_ ? num_faces_ : std::min<Index>(num_faces_, Index{1} << 16));
        soup_.face_offsets.reserve(expected + 1);
        soup_.source.face_lines.reserve(expected);
        std::vector<Index> corners;
        for (Index f = 0; f < num_faces_; ++f) {
            if (!next_data_line()) {
                io_fail(file_, reader_.line_number(),
                        "unexpected end of file: expected " + std::to_string(num_faces_) + " faces, found " +
                            std::to_string(f));
            }
            const long long line = reader_.line_number();
            const long long n = detail::io_to_int(tokens_[0], file_, line);
            if (n < 0) {
                io_fail(file_, line, "face " + std::to_string(f) + " has a negative corner count");
            }
            if (static_cast<std::uint64_t>(n) > tokens_.size() - 1) {
                io_fail(file_, line,
                        "face " + std::to_string(f) + " declares " + std::to_string(n) + " corners but the line has " +
                            std::to_string(tokens_.size() - 1) + " values");
            }
            corners.clear();
            for (std::size_t i = 1; i <= static_cast<std::size_t>(n); ++i) {
                const long long index = detail::io_to_int(tokens_[i], file_, line);
                if (index < 0 || index >= num_vertices_) {
                    io_fail(file_, line,
                            "vertex index " + std::to_string(index) + " out of range [0, " +
                                std::to_string(num_vertices_ - 1LL) + "]");
                }
                corners.push_back(static_cast<Index>(index));
            }
            // Anything after the corners (a colour) is ignored.
            if (soup_.face_vertices.size() + corners.size() > detail::io_max_count) {
                io_fail(file_, line, "too many face corners");
            }
            soup_.add_face(corners, static_cast<int>(line));
        }
    }

    std::istream& in_;
    detail::IoLineReader reader_;
    const std::string& file_;
    PolygonSoup soup_;
    std::string line_;
    std::vector<std::string_view> tokens_;
    Index num_vertices_ = 0;
    Index num_faces_ = 0;
    bool sizes_checked_ = false;
};

}  // namespace

PolygonSoup read_off(std::istream& in, const std::string& source_name) {
    return OffReader(in, source_name).run();
}

PolygonSoup read_off(const std::filesystem::path& path) {
    std::ifstream in = open_input_file(path);
    return read_off(in, path.string());
}

void write_off(std::ostream& out, const PolygonSoup& soup) {
    detail::io_check_soup(soup);
    out << "OFF\n" << soup.num_vertices() << ' ' << soup.num_faces() << " 0\n";
    for (Index v = 0; v < soup.num_vertices(); ++v) {
        for (Index c = 0; c < 3; ++c) {
            if (c > 0) {
                out << ' ';
            }
            detail::io_write_double(out, soup.positions(v, c));
        }
        out << '\n';
    }
    detail::io_write_counted_faces(out, soup);
    detail::io_check_written(out, "OFF");
}

}  // namespace limsurf
