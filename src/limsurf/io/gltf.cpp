#include "limsurf/io/gltf.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/version.h"
#include "limsurf/io/atomic_file.h"

namespace limsurf {
namespace {

// GLB container (glTF 2.0 §4.4): a 12-byte header, then chunks of (length, type, data).
constexpr std::uint32_t glb_magic = 0x46546C67;  // "glTF"
constexpr std::uint32_t glb_version = 2;
constexpr std::uint32_t chunk_json = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t chunk_bin = 0x004E4942;   // "BIN\0"
constexpr std::uint64_t glb_header_bytes = 12;
constexpr std::uint64_t chunk_header_bytes = 8;

constexpr int component_float = 5126;
constexpr int component_unsigned_int = 5125;
constexpr int target_array_buffer = 34962;
constexpr int target_element_array_buffer = 34963;
constexpr int mode_triangles = 4;

/// How far a normal's length may be from 1 before it is refused rather than renormalised.
constexpr double normal_tolerance = 1e-3;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what) {
    throw InputError(path.string() + ": " + what);
}

std::string number(double value) {
    std::array<char, 32> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return {buffer.data(), result.ptr};
}

/// A float as the JSON number of its exact double value (shortest text that reads back to
/// that double), so that readers parsing min/max as double or as float get the stored value.
std::string float_number(float value) {
    return number(static_cast<double>(value));
}

bool is_valid_utf8(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        const auto byte = static_cast<unsigned char>(text[i]);
        std::size_t length = 0;
        std::uint32_t code = 0;
        if (byte < 0x80U) {
            ++i;
            continue;
        }
        if ((byte & 0xE0U) == 0xC0U) {
            length = 2;
            code = byte & 0x1FU;
        } else if ((byte & 0xF0U) == 0xE0U) {
            length = 3;
            code = byte & 0x0FU;
        } else if ((byte & 0xF8U) == 0xF0U) {
            length = 4;
            code = byte & 0x07U;
        } else {
            return false;
        }
        if (i + length > text.size()) {
            return false;
        }
        for (std::size_t k = 1; k < length; ++k) {
            const auto next = static_cast<unsigned char>(text[i + k]);
            if ((next & 0xC0U) != 0x80U) {
                return false;
            }
            code = (code << 6U) | (next & 0x3FU);
        }
        static constexpr std::array<std::uint32_t, 5> smallest{0, 0, 0x80, 0x800, 0x10000};
        if (code < smallest[length] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) {
            return false;  // overlong, beyond Unicode, or a surrogate
        }
        i += length;
    }
    return true;
}

/// A JSON string literal; @p text must be valid UTF-8 (control characters are escaped).
std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (byte < 0x20U) {
            static constexpr char digits[] = "0123456789abcdef";
            out += "\\u00";
            out += digits[byte >> 4U];
            out += digits[byte & 0xFU];
        } else {
            out += c;
        }
    }
    out += '"';
    return out;
}

std::string attribute_name(std::string_view name) {
    std::string out = "_";
    for (const char c : name) {
        if (c >= 'a' && c <= 'z') {
            out += static_cast<char>(c - 'a' + 'A');
        } else if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_') {
            out += c;
        } else {
            out += '_';
        }
    }
    return out;
}

/// Little-endian bytes whatever the host's byte order.
void put_u32(std::string& bytes, std::uint32_t value) {
    for (unsigned shift = 0; shift < 32; shift += 8) {
        bytes += static_cast<char>((value >> shift) & 0xFFU);
    }
}

void put_f32(std::string& bytes, float value) {
    put_u32(bytes, std::bit_cast<std::uint32_t>(value));
}

std::uint64_t padded(std::uint64_t size) {
    return (size + 3U) & ~std::uint64_t{3};
}

/// Checks that @p value is finite and within the range of a float, then converts it.
/// @p what() names the value in a message (built only on failure: this runs per component).
template <class What>
float to_float(const std::filesystem::path& path, double value, const What& what) {
    if (!std::isfinite(value)) {
        fail(path, what() + " is not finite (" + number(value) + ")");
    }
    if (std::abs(value) > static_cast<double>(std::numeric_limits<float>::max())) {
        fail(path, what() + " is " + number(value) + ", beyond the range of a float (glTF stores 32-bit floats)");
    }
    return static_cast<float>(value);
}

double srgb_to_linear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// One bufferView with its accessor, in the order the data lie in the BIN chunk.
struct View {
    std::uint64_t offset = 0;
    std::uint64_t length = 0;
    int target = target_array_buffer;
    int component_type = component_float;
    const char* type = "VEC3";
    std::uint64_t count = 0;
    std::string name;
    std::vector<float> min;
    std::vector<float> max;
};

/// The float values of a #P×columns block, with their per-column min and max.
struct FloatBlock {
    std::vector<float> values;  // row-major
    std::vector<float> min;
    std::vector<float> max;

    void finish(std::size_t c) {
        min.assign(c, std::numeric_limits<float>::infinity());
        max.assign(c, -std::numeric_limits<float>::infinity());
        for (std::size_t i = 0; i < values.size(); ++i) {
            min[i % c] = std::min(min[i % c], values[i]);
            max[i % c] = std::max(max[i % c], values[i]);
        }
    }
};

/// An optional per-position block: empty, or one row per position.
void check_rows(const std::filesystem::path& path, Eigen::Index rows, Index num_positions, const char* what) {
    if (rows != 0 && rows != num_positions) {
        fail(path,
             detail::concat(what, " has ", rows, " rows, expected ", num_positions, " (one per position) or none"));
    }
}

}  // namespace

void write_glb(const std::filesystem::path& path, const TriangleSurface& surface) {
    // ---- validation and conversion to float (nothing is created before this is done)
    const Eigen::Index np = surface.positions.rows();
    const Eigen::Index nt = surface.triangles.rows();
    if (np == 0) {
        fail(path, "no positions (a glTF mesh needs at least one triangle)");
    }
    if (nt == 0) {
        fail(path, "no triangles (a glTF mesh needs at least one)");
    }
    if (np > std::numeric_limits<Index>::max()) {
        fail(path, detail::concat(np, " positions, more than 32-bit indices can number"));
    }
    const auto num_positions = static_cast<Index>(np);
    check_rows(path, surface.normals.rows(), num_positions, "normals");
    check_rows(path, surface.colors.rows(), num_positions, "colors");
    check_rows(path, surface.scalar.rows(), num_positions, "scalar");
    const bool has_normals = surface.normals.rows() > 0;
    const bool has_colors = surface.colors.rows() > 0;
    const bool has_scalar = surface.scalar.rows() > 0;
    if (has_scalar && surface.scalar_name.empty()) {
        fail(path, "the scalar has no name (scalar_name names its attribute)");
    }

    // Counts and sizes in 64 bits: the GLB's lengths are 32-bit, checked below.
    const auto p = static_cast<std::uint64_t>(np);
    const auto t = static_cast<std::uint64_t>(nt);

    FloatBlock positions;
    positions.values.reserve(3 * p);
    for (Index v = 0; v < num_positions; ++v) {
        for (Eigen::Index c = 0; c < 3; ++c) {
            positions.values.push_back(to_float(path, surface.positions(v, c), [&] {
                return detail::concat("vertex ", v, ": position component ", c);
            }));
        }
    }
    positions.finish(3);

    FloatBlock normals;
    if (has_normals) {
        normals.values.reserve(3 * p);
        for (Index v = 0; v < num_positions; ++v) {
            const Eigen::RowVector3d n = surface.normals.row(v);
            if (!n.allFinite()) {
                fail(path, detail::concat("vertex ", v, ": normal (", n(0), ", ", n(1), ", ", n(2), ") is not finite"));
            }
            const double length = n.norm();
            if (std::abs(length - 1.0) > normal_tolerance) {
                fail(path, detail::concat("vertex ", v, ": normal (", n(0), ", ", n(1), ", ", n(2), ") has length ",
                                          length, ", expected a unit vector (within ", normal_tolerance, ")"));
            }
            for (Eigen::Index c = 0; c < 3; ++c) {
                normals.values.push_back(static_cast<float>(n(c) / length));
            }
        }
        normals.finish(3);
    }

    FloatBlock colors;
    bool translucent = false;
    if (has_colors) {
        colors.values.reserve(4 * p);
        for (Index v = 0; v < num_positions; ++v) {
            for (Eigen::Index c = 0; c < 4; ++c) {
                const float value = surface.colors(v, c);
                if (!(value >= 0.0F && value <= 1.0F)) {  // NaN fails too
                    fail(path, detail::concat("vertex ", v, ": colour component ", c, " is ",
                                              number(static_cast<double>(value)), ", expected a value in [0, 1]"));
                }
                if (c < 3) {
                    colors.values.push_back(static_cast<float>(srgb_to_linear(static_cast<double>(value))));
                } else {
                    colors.values.push_back(value);
                    translucent = translucent || value < 1.0F;
                }
            }
        }
        colors.finish(4);
    }

    FloatBlock scalar;
    if (has_scalar) {
        scalar.values.reserve(p);
        for (Index v = 0; v < num_positions; ++v) {
            scalar.values.push_back(to_float(path, surface.scalar(v), [&] {
                return detail::concat("vertex ", v, ": scalar '", surface.scalar_name, "'");
            }));
        }
        scalar.finish(1);
    }

    for (Eigen::Index f = 0; f < nt; ++f) {
        for (Eigen::Index c = 0; c < 3; ++c) {
            const Index index = surface.triangles(f, c);
            if (index < 0 || index >= num_positions) {
                fail(path, detail::concat("triangle ", f, ": vertex index ", index, " out of range [0, ", num_positions,
                                          ")"));
            }
        }
    }

    // ---- layout of the BIN chunk: each view starts on a multiple of 4 bytes
    std::vector<View> views;
    std::uint64_t bin_length = 0;
    const auto add_view = [&](std::uint64_t bytes, int target, int component_type, const char* type,
                              std::uint64_t count, std::string name, const FloatBlock* block) {
        View view;
        view.offset = bin_length;
        view.length = bytes;
        view.target = target;
        view.component_type = component_type;
        view.type = type;
        view.count = count;
        view.name = std::move(name);
        if (block != nullptr) {
            view.min = block->min;
            view.max = block->max;
        }
        bin_length = padded(bin_length + bytes);
        views.push_back(std::move(view));
        return static_cast<int>(views.size()) - 1;
    };
    const int position_accessor =
        add_view(12 * p, target_array_buffer, component_float, "VEC3", p, "POSITION", &positions);
    const int normal_accessor =
        has_normals ? add_view(12 * p, target_array_buffer, component_float, "VEC3", p, "NORMAL", nullptr) : -1;
    const int color_accessor =
        has_colors ? add_view(16 * p, target_array_buffer, component_float, "VEC4", p, "COLOR_0", nullptr) : -1;
    const std::string scalar_attribute = attribute_name(surface.scalar_name);
    const std::string scalar_label = is_valid_utf8(surface.scalar_name) ? surface.scalar_name : scalar_attribute;
    const int scalar_accessor =
        has_scalar ? add_view(4 * p, target_array_buffer, component_float, "SCALAR", p, scalar_label, &scalar) : -1;
    const int index_accessor =
        add_view(12 * t, target_element_array_buffer, component_unsigned_int, "SCALAR", 3 * t, "indices", nullptr);

    // ---- JSON chunk
    std::string json = "{\"asset\":{\"version\":\"2.0\",\"generator\":" + json_string("limsurf " + version()) + "}";
    json += ",\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"limsurf\"}]";
    json += ",\"meshes\":[{\"name\":\"limsurf surface\",\"primitives\":[{\"attributes\":{";
    json += "\"POSITION\":" + std::to_string(position_accessor);
    if (has_normals) {
        json += ",\"NORMAL\":" + std::to_string(normal_accessor);
    }
    if (has_colors) {
        json += ",\"COLOR_0\":" + std::to_string(color_accessor);
    }
    if (has_scalar) {
        json += "," + json_string(scalar_attribute) + ":" + std::to_string(scalar_accessor);
    }
    json += "},\"indices\":" + std::to_string(index_accessor) +
            ",\"material\":0,\"mode\":" + std::to_string(mode_triangles) + "}]}]";
    json += ",\"materials\":[{\"name\":\"limsurf\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,1,1,1],"
            "\"metallicFactor\":0,\"roughnessFactor\":0.5},\"doubleSided\":true";
    if (translucent) {
        json += ",\"alphaMode\":\"BLEND\"";
    }
    json += "}]";
    json += ",\"buffers\":[{\"byteLength\":" + std::to_string(bin_length) + "}]";
    json += ",\"bufferViews\":[";
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& view = views[i];
        json += (i > 0 ? ",{" : "{");
        json += "\"buffer\":0,\"byteOffset\":" + std::to_string(view.offset) +
                ",\"byteLength\":" + std::to_string(view.length) + ",\"target\":" + std::to_string(view.target) + "}";
    }
    json += "],\"accessors\":[";
    for (std::size_t i = 0; i < views.size(); ++i) {
        const View& view = views[i];
        json += (i > 0 ? ",{" : "{");
        json += "\"bufferView\":" + std::to_string(i) + ",\"componentType\":" + std::to_string(view.component_type) +
                ",\"count\":" + std::to_string(view.count) + ",\"type\":\"" + view.type + "\"";
        json += ",\"name\":" + json_string(view.name);
        if (!view.min.empty()) {
            json += ",\"min\":[";
            for (std::size_t c = 0; c < view.min.size(); ++c) {
                json += (c > 0 ? "," : "") + float_number(view.min[c]);
            }
            json += "],\"max\":[";
            for (std::size_t c = 0; c < view.max.size(); ++c) {
                json += (c > 0 ? "," : "") + float_number(view.max[c]);
            }
            json += "]";
        }
        json += "}";
    }
    json += "]}";
    const std::uint64_t json_length = padded(json.size());
    json.resize(json_length, ' ');

    const std::uint64_t total = glb_header_bytes + chunk_header_bytes + json_length + chunk_header_bytes + bin_length;
    if (total > std::numeric_limits<std::uint32_t>::max()) {
        fail(path, detail::concat("the surface needs ", total, " bytes, more than a GLB file can hold (2^32 - 1)"));
    }

    // ---- the bytes
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(total));
    put_u32(bytes, glb_magic);
    put_u32(bytes, glb_version);
    put_u32(bytes, static_cast<std::uint32_t>(total));
    put_u32(bytes, static_cast<std::uint32_t>(json_length));
    put_u32(bytes, chunk_json);
    bytes += json;
    put_u32(bytes, static_cast<std::uint32_t>(bin_length));
    put_u32(bytes, chunk_bin);
    const std::size_t bin_start = bytes.size();
    const auto put_block = [&](const FloatBlock& block) {
        for (const float value : block.values) {
            put_f32(bytes, value);
        }
        bytes.resize(bin_start + static_cast<std::size_t>(padded(bytes.size() - bin_start)), '\0');
    };
    put_block(positions);
    if (has_normals) {
        put_block(normals);
    }
    if (has_colors) {
        put_block(colors);
    }
    if (has_scalar) {
        put_block(scalar);
    }
    for (Eigen::Index f = 0; f < nt; ++f) {
        for (Eigen::Index c = 0; c < 3; ++c) {
            put_u32(bytes, static_cast<std::uint32_t>(surface.triangles(f, c)));
        }
    }
    bytes.resize(static_cast<std::size_t>(total), '\0');
    LIMSURF_ASSERT(bytes.size() - bin_start == bin_length, "BIN chunk length");

    write_file_atomically(
        path, [&](std::ostream& out) { out.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
}

}  // namespace limsurf
