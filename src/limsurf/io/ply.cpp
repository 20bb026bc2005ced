#include "limsurf/io/ply.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
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

enum class PlyType : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> parse_type(std::string_view name) {
    struct Entry {
        std::string_view name;
        PlyType type;
    };
    static constexpr std::array<Entry, 16> table{{{"char", PlyType::Int8},
                                                  {"int8", PlyType::Int8},
                                                  {"uchar", PlyType::UInt8},
                                                  {"uint8", PlyType::UInt8},
                                                  {"short", PlyType::Int16},
                                                  {"int16", PlyType::Int16},
                                                  {"ushort", PlyType::UInt16},
                                                  {"uint16", PlyType::UInt16},
                                                  {"int", PlyType::Int32},
                                                  {"int32", PlyType::Int32},
                                                  {"uint", PlyType::UInt32},
                                                  {"uint32", PlyType::UInt32},
                                                  {"float", PlyType::Float32},
                                                  {"float32", PlyType::Float32},
                                                  {"double", PlyType::Float64},
                                                  {"float64", PlyType::Float64}}};
    for (const Entry& entry : table) {
        if (entry.name == name) {
            return entry.type;
        }
    }
    return std::nullopt;
}

std::size_t type_size(PlyType type) {
    switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8:
        return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
        return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
        return 4;
    case PlyType::Float64:
        return 8;
    }
    return 8;
}

bool is_integral(PlyType type) {
    return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float64;  ///< scalar type, or the item type of a list
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    long long line = 0;
    std::vector<PlyProperty> properties;
};

enum class Encoding { Ascii, Little, Big };

/// Buffered binary reads that know their offset from the start of the file.
class ByteSource {
  public:
    ByteSource(std::istream& in, std::uint64_t offset) : in_(in), offset_(offset) {}

    bool read(unsigned char* out, std::size_t n) {
        while (n > 0) {
            if (pos_ == len_ && !refill()) {
                return false;
            }
            const std::size_t take = std::min(n, len_ - pos_);
            std::memcpy(out, buffer_.data() + pos_, take);
            pos_ += take;
            offset_ += take;
            out += take;
            n -= take;
        }
        return true;
    }

    bool skip(std::uint64_t n) {
        while (n > 0) {
            if (pos_ == len_ && !refill()) {
                return false;
            }
            const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(n, len_ - pos_));
            pos_ += take;
            offset_ += take;
            n -= take;
        }
        return true;
    }

    [[nodiscard]] std::uint64_t offset() const noexcept { return offset_; }

  private:
    bool refill() {
        in_.read(reinterpret_cast<char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
        len_ = static_cast<std::size_t>(in_.gcount());
        pos_ = 0;
        return len_ > 0;
    }

    std::istream& in_;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(std::size_t{1} << 16);
    std::size_t pos_ = 0;
    std::size_t len_ = 0;
    std::uint64_t offset_ = 0;
};

template <class T>
T load(const unsigned char* bytes, bool swap) {
    std::array<unsigned char, sizeof(T)> copy{};
    std::memcpy(copy.data(), bytes, sizeof(T));
    if (swap) {
        std::reverse(copy.begin(), copy.end());
    }
    T value{};
    std::memcpy(&value, copy.data(), sizeof(T));
    return value;
}

/// @pre is_integral(type)
long long decode_int(PlyType type, const unsigned char* bytes, bool swap) {
    switch (type) {
    case PlyType::Int8:
        return load<std::int8_t>(bytes, swap);
    case PlyType::UInt8:
        return load<std::uint8_t>(bytes, swap);
    case PlyType::Int16:
        return load<std::int16_t>(bytes, swap);
    case PlyType::UInt16:
        return load<std::uint16_t>(bytes, swap);
    case PlyType::Int32:
        return load<std::int32_t>(bytes, swap);
    case PlyType::UInt32:
        return load<std::uint32_t>(bytes, swap);
    case PlyType::Float32:
    case PlyType::Float64:
        break;
    }
    return 0;
}

double decode_double(PlyType type, const unsigned char* bytes, bool swap) {
    switch (type) {
    case PlyType::Float32:
        return static_cast<double>(load<float>(bytes, swap));
    case PlyType::Float64:
        return load<double>(bytes, swap);
    default:
        return static_cast<double>(decode_int(type, bytes, swap));
    }
}

constexpr std::size_t no_property = static_cast<std::size_t>(-1);

class PlyReader {
  public:
    PlyReader(std::istream& in, const std::string& file)
        : in_(in), reader_(in, file, detail::LoneCarriageReturn::Refused), file_(file) {
        soup_.source.file = file;
    }

    PolygonSoup run() {
        read_magic();
        read_header();
        assign_roles();
        check_sizes();
        if (encoding_ == Encoding::Ascii) {
            read_ascii();
        } else {
            read_binary();
        }
        const Index nv = num_vertices_;
        soup_.positions.resize(nv, 3);
        for (Index v = 0; v < nv; ++v) {
            for (Index c = 0; c < 3; ++c) {
                soup_.positions(v, c) = coordinates_[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(c)];
            }
        }
        return std::move(soup_);
    }

  private:
    // ---- header

    void read_magic() {
        if (!reader_.next(line_)) {
            io_fail(file_, 0, "empty file");
        }
        detail::io_split(line_, tokens_);
        if (tokens_.size() == 1 && tokens_[0] == "ply") {
            return;
        }
        if (tokens_.empty()) {
            // Blank so far: an all-blank file is empty, anything else lacks the magic.
            while (reader_.next(line_)) {
                detail::io_split(line_, tokens_);
                if (!tokens_.empty()) {
                    io_fail(file_, 1, "expected 'ply' on the first line");
                }
            }
            io_fail(file_, 0, "empty file");
        }
        io_fail(file_, 1, "expected 'ply' on the first line, found " + io_quote(line_));
    }

    void read_header() {
        bool have_format = false;
        while (true) {
            if (!reader_.next(line_)) {
                io_fail(file_, reader_.line_number(), "unexpected end of file in the header (no 'end_header')");
            }
            const long long line = reader_.line_number();
            detail::io_split(line_, tokens_);
            if (tokens_.empty()) {
                continue;
            }
            const std::string_view key = tokens_[0];
            if (key == "end_header") {
                if (!have_format) {
                    io_fail(file_, line, "the header has no 'format' line");
                }
                return;
            }
            if (key == "comment" || key == "obj_info") {
                continue;
            }
            if (key == "format") {
                if (have_format) {
                    io_fail(file_, line, "duplicate 'format' line");
                }
                read_format(line);
                have_format = true;
            } else if (key == "element") {
                read_element(line);
            } else if (key == "property") {
                read_property(line);
            } else {
                io_fail(file_, line, "unknown header keyword " + io_quote(key));
            }
        }
    }

    void read_format(long long line) {
        if (tokens_.size() != 3) {
            io_fail(file_, line, "expected 'format <encoding> 1.0'");
        }
        if (tokens_[1] == "ascii") {
            encoding_ = Encoding::Ascii;
        } else if (tokens_[1] == "binary_little_endian") {
            encoding_ = Encoding::Little;
        } else if (tokens_[1] == "binary_big_endian") {
            encoding_ = Encoding::Big;
        } else {
            io_fail(file_, line, "unknown PLY format " + io_quote(tokens_[1]));
        }
        if (tokens_[2] != "1.0") {
            io_fail(file_, line, "unsupported PLY version " + io_quote(tokens_[2]));
        }
    }

    void read_element(long long line) {
        if (tokens_.size() != 3) {
            io_fail(file_, line, "expected 'element <name> <count>'");
        }
        const long long count = detail::io_to_int(tokens_[2], file_, line);
        if (count < 0) {
            io_fail(file_, line, "element " + io_quote(tokens_[1]) + " has a negative count");
        }
        for (const PlyElement& element : elements_) {
            if (element.name == tokens_[1]) {
                io_fail(file_, line, "duplicate element " + io_quote(tokens_[1]));
            }
        }
        elements_.push_back(PlyElement{std::string(tokens_[1]), static_cast<std::uint64_t>(count), line, {}});
    }

    PlyType type_at(std::size_t i, long long line) {
        const auto type = parse_type(tokens_[i]);
        if (!type) {
            io_fail(file_, line, "unknown property type " + io_quote(tokens_[i]));
        }
        return *type;
    }

    void read_property(long long line) {
        if (elements_.empty()) {
            io_fail(file_, line, "'property' before any 'element'");
        }
        PlyProperty property;
        if (tokens_.size() >= 2 && tokens_[1] == "list") {
            if (tokens_.size() != 5) {
                io_fail(file_, line, "expected 'property list <count type> <item type> <name>'");
            }
            property.is_list = true;
            property.count_type = type_at(2, line);
            property.type = type_at(3, line);
            property.name = tokens_[4];
            if (!is_integral(property.count_type)) {
                io_fail(file_, line, "list count type " + io_quote(tokens_[2]) + " is not an integer type");
            }
        } else {
            if (tokens_.size() != 3) {
                io_fail(file_, line, "expected 'property <type> <name>'");
            }
            property.type = type_at(1, line);
            property.name = tokens_[2];
        }
        PlyElement& element = elements_.back();
        for (const PlyProperty& other : element.properties) {
            if (other.name == property.name) {
                io_fail(file_, line,
                        "duplicate property " + io_quote(property.name) + " in element " + io_quote(element.name));
            }
        }
        element.properties.push_back(std::move(property));
    }

    /// Finds the vertex and face elements and the properties we read.
    void assign_roles() {
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            if (elements_[e].name == "vertex") {
                vertex_element_ = e;
            } else if (elements_[e].name == "face") {
                face_element_ = e;
            }
        }
        if (vertex_element_ == no_property) {
            io_fail(file_, reader_.line_number(), "the header declares no 'vertex' element");
        }
        const PlyElement& vertex = elements_[vertex_element_];
        for (std::size_t p = 0; p < vertex.properties.size(); ++p) {
            const PlyProperty& property = vertex.properties[p];
            const int axis = property.name == "x" ? 0 : property.name == "y" ? 1 : property.name == "z" ? 2 : -1;
            if (axis < 0) {
                continue;
            }
            if (property.is_list) {
                io_fail(file_, vertex.line, "vertex property " + io_quote(property.name) + " must not be a list");
            }
            axis_property_[static_cast<std::size_t>(axis)] = p;
        }
        for (std::size_t axis = 0; axis < 3; ++axis) {
            if (axis_property_[axis] == no_property) {
                const char* names[] = {"x", "y", "z"};
                io_fail(file_, vertex.line, std::string("element 'vertex' has no property '") + names[axis] + "'");
            }
        }
        if (face_element_ != no_property) {
            const PlyElement& face = elements_[face_element_];
            for (const char* wanted : {"vertex_indices", "vertex_index"}) {
                for (std::size_t p = 0; p < face.properties.size(); ++p) {
                    if (face.properties[p].name == wanted && index_property_ == no_property) {
                        index_property_ = p;
                    }
                }
            }
            if (index_property_ == no_property) {
                io_fail(file_, face.line,
                        "element 'face' has no list property 'vertex_indices' (or "
                        "'vertex_index')");
            }
            const PlyProperty& indices = face.properties[index_property_];
            if (!indices.is_list || !is_integral(indices.type)) {
                io_fail(file_, face.line,
                        "face property " + io_quote(indices.name) + " must be a list of an integer type");
            }
        }
    }

    /// Refuses element counts the rest of the stream cannot hold, before allocating.
    void check_sizes() {
        const std::optional<std::uint64_t> remaining = detail::io_remaining_bytes(in_);
        std::uint64_t needed = 0;
        for (const PlyElement& element : elements_) {
            std::uint64_t per_element = 0;
            for (const PlyProperty& property : element.properties) {
                // ASCII: a value and a separator; binary: a scalar or a list count.
                per_element += encoding_ == Encoding::Ascii
                                   ? 2
                                   : type_size(property.is_list ? property.count_type : property.type);
            }
            if (remaining && per_element > 0) {
                const std::uint64_t cap = *remaining + (encoding_ == Encoding::Ascii ? 1 : 0) - needed;
                if (element.count > cap / per_element) {
                    io_fail(file_, element.line,
                            "element " + io_quote(element.name) + " declares " + std::to_string(element.count) +
                                " entries, more than the " + std::to_string(*remaining) +
                                " bytes after the header can hold");
                }
                needed += element.count * per_element;
            }
        }
        const PlyElement& vertex = elements_[vertex_element_];
        if (vertex.count > detail::io_max_count) {
            io_fail(file_, vertex.line,
                    "element 'vertex' count " + std::to_string(vertex.count) + " exceeds the supported maximum " +
                        std::to_string(detail::io_max_count));
        }
        num_vertices_ = static_cast<Index>(vertex.count);
        if (face_element_ != no_property && elements_[face_element_].count > detail::io_max_count) {
            io_fail(file_, elements_[face_element_].line,
                    "element 'face' count " + std::to_string(elements_[face_element_].count) +
                        " exceeds the supported maximum " + std::to_string(detail::io_max_count));
        }
        sizes_checked_ = remaining.has_value();
    }

    void reserve_for(const PlyElement& element, std::size_t e) {
        // Reserve only what the stream is known to hold.
        const auto n =
            static_cast<std::size_t>(sizes_checked_ ? element.count : std::min<std::uint64_t>(element.count, 1U << 16));
        if (e == vertex_element_) {
            coordinates_.reserve(3 * n);
            soup_.source.vertex_lines.reserve(n);
        } else if (e == face_element_) {
            soup_.face_offsets.reserve(n + 1);
            soup_.source.face_lines.reserve(n);
        }
    }

    void add_face(std::vector<Index>& corners, int line, const std::string& where) {
        if (soup_.face_vertices.size() + corners.size() > detail::io_max_count) {
            throw InputError(where + ": too many face corners");
        }
        soup_.add_face(corners, line);
    }

    std::string index_error(long long index) const {
        return "vertex index " + std::to_string(index) + " out of range [0, " + std::to_string(num_vertices_ - 1LL) +
               "]";
    }

    // ---- ASCII data

    void read_ascii() {
        std::vector<Index> corners;
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            const PlyElement& element = elements_[e];
            if (element.properties.empty()) {
                continue;
            }
            reserve_for(element, e);
            for (std::uint64_t i = 0; i < element.count; ++i) {
                if (!next_data_line()) {
                    io_fail(file_, reader_.line_number(),
                            "unexpected end of file: expected " + std::to_string(element.count) + " " +
                                io_quote(element.name) + " elements, found " + std::to_string(i));
                }
                read_ascii_element(element, e, corners);
            }
        }
        if (next_data_line()) {
            io_fail(file_, reader_.line_number(), "unexpected data after the last element");
        }
    }

    bool next_data_line() {
        while (reader_.next(line_)) {
            detail::io_split(line_, tokens_);
            if (!tokens_.empty()) {
                return true;
            }
        }
        return false;
    }

    void read_ascii_element(const PlyElement& element, std::size_t e, std::vector<Index>& corners) {
        const long long line = reader_.line_number();
        std::size_t next = 0;
        std::array<double, 3> xyz{};
        const auto need = [&](std::uint64_t n) {
            if (n > tokens_.size() - next) {
                io_fail(file_, line, "element " + io_quote(element.name) + " has too few values on this line");
            }
        };
        for (std::size_t p = 0; p < element.properties.size(); ++p) {
            const PlyProperty& property = element.properties[p];
            if (!property.is_list) {
                need(1);
                const std::string_view token = tokens_[next++];
                const double value = is_integral(property.type)
                                         ? static_cast<double>(detail::io_to_int(token, file_, line))
                                         : detail::io_to_double(token, file_, line);
                if (e == vertex_element_) {
                    for (std::size_t axis = 0; axis < 3; ++axis) {
                        if (axis_property_[axis] == p) {
                            xyz[axis] = value;
                        }
                    }
                }
                continue;
            }
            need(1);
            const long long count = detail::io_to_int(tokens_[next++], file_, line);
            if (count < 0) {
                io_fail(file_, line, "negative list length " + std::to_string(count));
            }
            need(static_cast<std::uint64_t>(count));
            const bool is_face_list = e == face_element_ && p == index_property_;
            if (is_face_list) {
                corners.clear();
            }
            for (long long k = 0; k < count; ++k) {
                const std::string_view token = tokens_[next++];
                if (!is_integral(property.type)) {
                    (void)detail::io_to_double(token, file_, line);
                    continue;
                }
                const long long value = detail::io_to_int(token, file_, line);
                if (is_face_list) {
                    if (value < 0 || value >= num_vertices_) {
                        io_fail(file_, line, index_error(value));
                    }
                    corners.push_back(static_cast<Index>(value));
                }
            }
            if (is_face_list) {
                add_face(corners, static_cast<int>(line), detail::io_where(file_, line));
            }
        }
        if (next != tokens_.size()) {
            io_fail(file_, line,
                    "element " + io_quote(element.name) + " has " + std::to_string(tokens_.size() - next) +
                        " more values than its properties");
        }
        if (e == vertex_element_) {
            coordinates_.insert(coordinates_.end(), xyz.begin(), xyz.end());
            soup_.source.vertex_lines.push_back(static_cast<int>(line));
        }
    }

    // ---- binary data

    void read_binary() {
        const bool swap = (encoding_ == Encoding::Little) != (std::endian::native == std::endian::little);
        ByteSource source(in_, reader_.bytes_consumed());
        std::vector<Index> corners;
        std::array<unsigned char, 8> bytes{};
        for (std::size_t e = 0; e < elements_.size(); ++e) {
            const PlyElement& element = elements_[e];
            if (element.properties.empty()) {
                continue;
            }
            reserve_for(element, e);
            for (std::uint64_t i = 0; i < element.count; ++i) {
                const std::uint64_t start = source.offset();
                const auto where = [&]() {
                    return detail::io_where(file_, 0) + ": element " + io_quote(element.name) + " " +
                           std::to_string(i) + " (byte offset " + std::to_string(start) + ")";
                };
                const auto truncated = [&]() { throw InputError(where() + ": unexpected end of file"); };
                std::array<double, 3> xyz{};
                for (std::size_t p = 0; p < element.properties.size(); ++p) {
                    const PlyProperty& property = element.properties[p];
                    if (!property.is_list) {
                        const std::size_t size = type_size(property.type);
                        if (!source.read(bytes.data(), size)) {
                            truncated();
                        }
                        if (e == vertex_element_) {
                            for (std::size_t axis = 0; axis < 3; ++axis) {
                                if (axis_property_[axis] == p) {
                                    xyz[axis] = decode_double(property.type, bytes.data(), swap);
                                }
                            }
                        }
                        continue;
                    }
                    if (!source.read(bytes.data(), type_size(property.count_type))) {
                        truncated();
                    }
                    const long long count = decode_int(property.count_type, bytes.data(), swap);
                    if (count < 0) {
                        throw InputError(where() + ": negative list length " + std::to_string(count));
                    }
                    const std::size_t size = type_size(property.type);
                    if (!(e == face_element_ && p == index_property_)) {
                        if (!source.skip(static_cast<std::uint64_t>(count) * size)) {
                            truncated();
                        }
                        continue;
                    }
                    if (static_cast<std::uint64_t>(count) > detail::io_max_count) {
                        throw InputError(where() + ": too many face corners");
                    }
                    corners.clear();
                    for (long long k = 0; k < count; ++k) {
                        if (!source.read(bytes.data(), size)) {
                            truncated();
                        }
                        const long long value = decode_int(property.type, bytes.data(), swap);
                        if (value < 0 || value >= num_vertices_) {
                            throw InputError(where() + ": " + index_error(value));
                        }
                        corners.push_back(static_cast<Index>(value));
                    }
                    add_face(corners, 0, where());
                }
                if (e == vertex_element_) {
                    coordinates_.insert(coordinates_.end(), xyz.begin(), xyz.end());
                    soup_.source.vertex_lines.push_back(0);
                }
            }
        }
    }

    std::istream& in_;
    detail::IoLineReader reader_;
    const std::string& file_;
    PolygonSoup soup_;
    std::string line_;
    std::vector<std::string_view> tokens_;
    std::vector<PlyElement> elements_;
    Encoding encoding_ = Encoding::Ascii;
    std::size_t vertex_element_ = no_property;
    std::size_t face_element_ = no_property;
    std::array<std::size_t, 3> axis_property_{no_property, no_property, no_property};
    std::size_t index_property_ = no_property;
    Index num_vertices_ = 0;
    bool sizes_checked_ = false;
    std::vector<double> coordinates_;
};

// ---- writing

/// Binary values gathered into blocks before they reach the stream: one ostream::write per value
/// (sentry, virtual calls) cost about as much as the refinement of a million-face mesh, so the
/// writer's share of `limsurf subdivide` was a third (docs/BENCHMARKS.md).
class BinaryStore {
  public:
    BinaryStore(std::ostream& out, bool swap) : out_(out), swap_(swap) { buffer_.reserve(block); }
    BinaryStore(const BinaryStore&) = delete;
    BinaryStore& operator=(const BinaryStore&) = delete;
    ~BinaryStore() = default;  // what is left unflushed is dropped: call flush() at the end

    template <class T>
    void put(T value) {
        std::array<unsigned char, sizeof(T)> bytes{};
        std::memcpy(bytes.data(), &value, sizeof(T));
        if (swap_) {
            std::reverse(bytes.begin(), bytes.end());
        }
        buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
        if (buffer_.size() >= block) {
            flush();
        }
    }
    void flush() {
        out_.write(reinterpret_cast<const char*>(buffer_.data()), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }

  private:
    static constexpr std::size_t block = std::size_t{1} << 16U;
    std::ostream& out_;
    bool swap_;
    std::vector<unsigned char> buffer_;
};

}  // namespace

PolygonSoup read_ply(std::istream& in, const std::string& source_name) {
    return PlyReader(in, source_name).run();
}

PolygonSoup read_ply(const std::filesystem::path& path) {
    std::ifstream in = open_input_file(path);
    return read_ply(in, path.string());
}

void write_ply(std::ostream& out, const PolygonSoup& soup, PlyEncoding encoding, std::span<const VertexField> fields) {
    detail::io_check_soup(soup);
    static constexpr std::array<std::string_view, 3> reserved{"x", "y", "z"};
    validate_vertex_fields(fields, soup.num_vertices(), reserved);

    std::size_t max_corners = 0;
    for (Index f = 0; f < soup.num_faces(); ++f) {
        max_corners = std::max(max_corners, soup.face(f).size());
    }
    const bool wide_counts = max_corners > 255;

    out << "ply\nformat ";
    switch (encoding) {
    case PlyEncoding::Ascii:
        out << "ascii";
        break;
    case PlyEncoding::BinaryLittleEndian:
        out << "binary_little_endian";
        break;
    case PlyEncoding::BinaryBigEndian:
        out << "binary_big_endian";
        break;
    }
    out << " 1.0\ncomment written by limsurf\n";
    out << "element vertex " << soup.num_vertices() << '\n';
    out << "property double x\nproperty double y\nproperty double z\n";
    for (const VertexField& field : fields) {
        const std::string name = sanitize_field_name(field.name);
        if (field.values.cols() == 1) {
            out << "property double " << name << '\n';
        } else {
            for (const char* axis : {"_x", "_y", "_z"}) {
                out << "property double " << name << axis << '\n';
            }
        }
    }
    out << "element face " << soup.num_faces() << '\n';
    out << "property list " << (wide_counts ? "uint" : "uchar") << " int vertex_indices\n";
    out << "end_header\n";

    if (encoding == PlyEncoding::Ascii) {
        for (Index v = 0; v < soup.num_vertices(); ++v) {
            for (Index c = 0; c < 3; ++c) {
                if (c > 0) {
                    out << ' ';
                }
                detail::io_write_double(out, soup.positions(v, c));
            }
            for (const VertexField& field : fields) {
                for (Eigen::Index c = 0; c < field.values.cols(); ++c) {
                    out << ' ';
                    detail::io_write_double(out, field.values(v, c));
                }
            }
            out << '\n';
        }
        detail::io_write_counted_faces(out, soup);
    } else {
        const bool swap = (encoding == PlyEncoding::BinaryLittleEndian) != (std::endian::native == std::endian::little);
        BinaryStore store(out, swap);
        for (Index v = 0; v < soup.num_vertices(); ++v) {
            for (Index c = 0; c < 3; ++c) {
                store.put<double>(soup.positions(v, c));
            }
            for (const VertexField& field : fields) {
                for (Eigen::Index c = 0; c < field.values.cols(); ++c) {
                    store.put<double>(field.values(v, c));
                }
            }
        }
        for (Index f = 0; f < soup.num_faces(); ++f) {
            const auto corners = soup.face(f);
            if (wide_counts) {
                store.put<std::uint32_t>(static_cast<std::uint32_t>(corners.size()));
            } else {
                store.put<std::uint8_t>(static_cast<std::uint8_t>(corners.size()));
            }
            for (const Index v : corners) {
                store.put<std::int32_t>(v);
            }
        }
        store.flush();
    }
    detail::io_check_written(out, "PLY");
}

}  // namespace limsurf
