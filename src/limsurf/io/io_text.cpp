#include "limsurf/detail/io_text.h"

#include <array>
#include <cerrno>
#include <charconv>
#include <cstddef>
#include <cstring>
#include <system_error>

#include "limsurf/core/error.h"

namespace limsurf::detail {
namespace {

bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/// Drops one leading '+' when a digit or '.' follows (from_chars rejects it).
std::string_view strip_plus(std::string_view token) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
        return token.substr(1);
    }
    return token;
}

std::string plural(std::size_t n, const char* singular, const char* plural_form) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural_form);
}

}  // namespace

std::string io_where(const std::string& file, long long line) {
    if (line <= 0) {
        return file.empty() ? std::string("<input>") : file;
    }
    if (file.empty()) {
        return "line " + std::to_string(line);
    }
    return file + ":" + std::to_string(line);
}

void io_fail(const std::string& file, long long line, const std::string& what) {
    throw InputError(io_where(file, line) + ": " + what);
}

std::string io_quote(std::string_view token) {
    constexpr std::size_t max_shown = 40;
    std::string out = "'";
    const std::size_t shown = token.size() > max_shown ? max_shown : token.size();
    for (std::size_t i = 0; i < shown; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
            out += static_cast<char>(c);
        } else {
            constexpr std::array<char, 16> hex{'0', '1', '2', '3', '4', '5', '6', '7',
                                               '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'};
            out += "\\x";
            out += hex[c >> 4U];
            out += hex[c & 0xfU];
        }
    }
    if (shown < token.size()) {
        out += "...";
    }
    out += "'";
    return out;
}

void io_split(std::string_view line, std::vector<std::string_view>& tokens) {
    tokens.clear();
    std::size_t i = 0;
    const std::size_t n = line.size();
    while (i < n) {
        while (i < n && is_blank(line[i])) {
            ++i;
        }
        const std::size_t begin = i;
        while (i < n && !is_blank(line[i])) {
            ++i;
        }
        if (i > begin) {
            tokens.push_back(line.substr(begin, i - begin));
        }
    }
}

std::string_view io_strip_comment(std::string_view line) {
    const auto hash = line.find('#');
    return hash == std::string_view::npos ? line : line.substr(0, hash);
}

double io_to_double(std::string_view token, const std::string& file, long long line) {
    const std::string_view digits = strip_plus(token);
    double value = 0.0;
    const char* const end = digits.data() + digits.size();
    const auto result = std::from_chars(digits.data(), end, value, std::chars_format::general);
    if (result.ec == std::errc::result_out_of_range && result.ptr == end) {
        io_fail(file, line, "number " + io_quote(token) + " is out of range for a double");
    }
    if (result.ec != std::errc() || result.ptr != end || digits.empty()) {
        io_fail(file, line, "invalid number " + io_quote(token));
    }
    return value;
}

long long io_to_int(std::string_view token, const std::string& file, long long line) {
    const std::string_view digits = strip_plus(token);
    long long value = 0;
    const char* const end = digits.data() + digits.size();
    const auto result = std::from_chars(digits.data(), end, value, 10);
    if (result.ec == std::errc::result_out_of_range && result.ptr == end) {
        io_fail(file, line, "integer " + io_quote(token) + " is out of range");
    }
    if (result.ec != std::errc() || result.ptr != end || digits.empty()) {
        io_fail(file, line, "invalid integer " + io_quote(token));
    }
    return value;
}

bool IoLineReader::next(std::string& line) {
    if (has_pending_) {
        line.swap(pending_);
        has_pending_ = false;
    } else {
        if (!std::getline(in_, line)) {
            return false;
        }
        bytes_ += line.size();
        if (!in_.eof()) {
            ++bytes_;  // the '\n' getline consumed
        }
        if (line_ == 0 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) {
            line.erase(0, 3);  // a UTF-8 byte-order mark, as some editors on Windows write
        }
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
    }
    ++line_;
    // A "\r" left inside the line is a line ending of its own (classic Mac OS).
    if (const auto cr = line.find('\r'); cr != std::string::npos) {
        if (lone_cr_ == LoneCarriageReturn::Refused) {
            io_fail(file_, line_,
                    "a carriage return (\\r) ends a line without a line feed (classic Mac OS line "
                    "endings): this format needs LF or CRLF line endings");
        }
        pending_.assign(line, cr + 1);
        has_pending_ = true;
        line.resize(cr);
    }
    return true;
}

std::optional<std::uint64_t> io_remaining_bytes(std::istream& in) {
    if (!in.good()) {
        return std::nullopt;
    }
    const std::istream::pos_type here = in.tellg();
    if (here == std::istream::pos_type(-1)) {
        in.clear();
        return std::nullopt;
    }
    in.seekg(0, std::ios::end);
    const std::istream::pos_type end = in.tellg();
    in.clear();
    in.seekg(here);
    if (end == std::istream::pos_type(-1) || !in.good() || end < here) {
        in.clear();
        in.seekg(here);
        return std::nullopt;
    }
    return static_cast<std::uint64_t>(end - here);
}

std::string io_format_double(double value) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

void io_write_double(std::ostream& out, double value) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    out.write(buffer.data(), result.ptr - buffer.data());
}

void io_write_counted_faces(std::ostream& out, const PolygonSoup& soup) {
    for (Index f = 0; f < soup.num_faces(); ++f) {
        const auto corners = soup.face(f);
        out << corners.size();
        for (const Index v : corners) {
            out << ' ' << v;
        }
        out << '\n';
    }
}

void io_check_soup(const PolygonSoup& soup) {
    const auto& offsets = soup.face_offsets;
    LIMSURF_CHECK(!offsets.empty() && offsets.front() == 0, InputError,
                  "cannot write mesh: face_offsets must start with 0");
    LIMSURF_CHECK(static_cast<std::size_t>(offsets.back()) == soup.face_vertices.size(), InputError,
                  "cannot write mesh: face_offsets ends at ", offsets.back(), " but there are ",
                  soup.face_vertices.size(), " face corners");
    const Index nv = soup.num_vertices();
    for (Index f = 0; f < soup.num_faces(); ++f) {
        const auto k = static_cast<std::size_t>(f);
        LIMSURF_CHECK(offsets[k] <= offsets[k + 1], InputError, "cannot write mesh: face ", f,
                      " has a negative number of corners");
        for (const Index v : soup.face(f)) {
            LIMSURF_CHECK(v >= 0 && v < nv, InputError, "cannot write mesh: face ", f, " names vertex ", v,
                          " but there are ", nv, " vertices");
        }
    }
}

std::string io_dropped_tags_warning(const char* format, const PolygonSoup& soup) {
    std::vector<std::string> parts;
    const auto& tags = soup.sharpness;
    if (!tags.creases.empty()) {
        parts.push_back(plural(tags.creases.size(), "crease", "creases"));
    }
    if (!tags.corners.empty()) {
        parts.push_back(plural(tags.corners.size(), "corner", "corners"));
    }
    if (!tags.holes.empty()) {
        parts.push_back(plural(tags.holes.size(), "hole", "holes"));
    }
    const std::size_t hints = static_cast<std::size_t>(soup.hints.boundary.has_value()) +
                              static_cast<std::size_t>(soup.hints.creasing.has_value()) +
                              static_cast<std::size_t>(soup.hints.triangles.has_value());
    if (hints > 0) {
        parts.push_back(plural(hints, "scheme hint", "scheme hints"));
    }
    if (parts.empty()) {
        return {};
    }
    std::string message = std::string(format) + " cannot store subdivision tags: ";
    for (std::size_t i = 0; i < parts.size(); ++i) {
        message += (i == 0 ? "" : ", ") + parts[i];
    }
    return message + " dropped";
}

void io_check_written(const std::ostream& stream, const char* what) {
    LIMSURF_CHECK(stream.good(), InputError, "writing ", what, " failed");
}

}  // namespace limsurf::detail
