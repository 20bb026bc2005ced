// Private helpers shared by the mesh readers and writers (src/limsurf/io).
//
// Every reader reports problems as InputError("FILE:LINE: what is wrong");
// these helpers build such messages, split lines into tokens, parse numbers
// strictly (the whole token, std::from_chars) and format doubles so that they
// read back bitwise (std::to_chars shortest round trip).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"

namespace limsurf::detail {

/// Largest vertex or face count a reader accepts (Index is 32-bit signed).
inline constexpr std::uint64_t io_max_count = 2147483646;

/// "file:line", or "line N" when @p file is empty, or "file" when @p line <= 0.
[[nodiscard]] std::string io_where(const std::string& file, long long line);

/// Throws InputError(io_where(file, line) + ": " + what).
[[noreturn]] void io_fail(const std::string& file, long long line, const std::string& what);

/// A token quoted for a message: 'tok', with non-printable bytes escaped as \xNN and
/// anything past 40 characters elided.
[[nodiscard]] std::string io_quote(std::string_view token);

/// Splits @p line on blanks (space, tab, CR, VT, FF) into @p tokens (cleared first).
void io_split(std::string_view line, std::vector<std::string_view>& tokens);

/// @p line up to its first '#'.
[[nodiscard]] std::string_view io_strip_comment(std::string_view line);

/// Parses the whole of @p token as a double ("nan" and "inf" included; one leading '+'
/// allowed). @throws InputError "FILE:LINE: invalid number 'tok'" or "... out of range".
[[nodiscard]] double io_to_double(std::string_view token, const std::string& file, long long line);

/// Parses the whole of @p token as a decimal integer (one leading '+' allowed).
/// @throws InputError "FILE:LINE: invalid integer 'tok'" or "... out of range".
[[nodiscard]] long long io_to_int(std::string_view token, const std::string& file, long long line);

/// How a line reader treats a carriage return that does not end a "\r\n".
enum class LoneCarriageReturn {
    EndsLine,  ///< classic Mac OS line endings: "\r" alone ends a line (OBJ, OFF, value files)
    Refused    ///< an error naming the line (a PLY header: its binary data must start right after it)
};

/// Reads lines ending in "\n", "\r\n" or (by default) a lone "\r"; the terminator is not
/// returned. A UTF-8 byte-order mark at the start of the stream is skipped. Counts lines and bytes.
class IoLineReader {
  public:
    explicit IoLineReader(std::istream& in, std::string file = {},
                          LoneCarriageReturn lone_cr = LoneCarriageReturn::EndsLine)
        : in_(in), file_(std::move(file)), lone_cr_(lone_cr) {}

    /// Next line into @p line; false at the end of the stream.
    /// @throws InputError for a lone carriage return under LoneCarriageReturn::Refused
    bool next(std::string& line);
    /// 1-based number of the last line returned (0 before the first).
    [[nodiscard]] long long line_number() const noexcept { return line_; }
    /// Bytes consumed from the stream so far, terminators and a byte-order mark included.
    [[nodiscard]] std::uint64_t bytes_consumed() const noexcept { return bytes_; }

  private:
    std::istream& in_;
    std::string file_;
    LoneCarriageReturn lone_cr_;
    long long line_ = 0;
    std::uint64_t bytes_ = 0;
    std::string pending_;  ///< what followed a lone "\r" in the last chunk read
    bool has_pending_ = false;
};

/// Bytes left between the stream's read position and its end, when the stream can seek.
[[nodiscard]] std::optional<std::uint64_t> io_remaining_bytes(std::istream& in);

/// Shortest text that reads back as exactly @p value ("nan", "inf", "-inf" for non-finite).
[[nodiscard]] std::string io_format_double(double value);

/// Writes io_format_double(value) to @p out.
void io_write_double(std::ostream& out, double value);

/// Writes each face as "n i0 i1 ..." (0-based) on its own line: the face list of OFF and ASCII PLY.
void io_write_counted_faces(std::ostream& out, const PolygonSoup& soup);

/// Checks that @p soup is structurally writable: offsets start at 0, increase and end at
/// face_vertices.size(), every corner names an existing vertex.
/// @throws InputError naming the first bad face
void io_check_soup(const PolygonSoup& soup);

/// "FORMAT cannot store subdivision tags: 3 creases, 1 corner dropped", or "" when the
/// soup has no tags or hints.
[[nodiscard]] std::string io_dropped_tags_warning(const char* format, const PolygonSoup& soup);

/// Throws InputError unless @p stream is good after writing.
void io_check_written(const std::ostream& stream, const char* what);

}  // namespace limsurf::detail
