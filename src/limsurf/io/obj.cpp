#include "limsurf/io/obj.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/core/input_file.h"
#include "limsurf/detail/io_text.h"

namespace limsurf {
namespace {

using detail::io_fail;
using detail::io_quote;

/// Keywords that carry nothing limsurf uses; accepted and ignored.
/// (`g` and `usemtl` are read: they name the face groups.)
constexpr std::string_view ignored_keywords[] = {"vp",    "o",        "s",        "mtllib",     "l",
                                                 "p",     "mg",       "usemap",   "maplib",     "lod",
                                                 "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj"};

/// Free-form geometry: it describes surfaces limsurf cannot represent.
constexpr std::string_view freeform_keywords[] = {"cstype", "deg",  "bmat", "step", "curv", "curv2", "surf",  "parm",
                                                  "trim",   "hole", "scrv", "sp",   "end",  "con",   "ctech", "stech"};

template <std::size_t N>
bool contains(const std::string_view (&list)[N], std::string_view word) {
    for (const auto& item : list) {
        if (item == word) {
            return true;
        }
    }
    return false;
}

/// Sentinel stored for a positive index too large for Index (always out of range).
constexpr Index huge_index = std::numeric_limits<Index>::max();

/// The largest (1-based, resolved) texture or normal index a face used, and its line.
struct AttributeReference {
    long long value = 0;
    long long line = 0;
};

class ObjReader {
  public:
    ObjReader(std::istream& in, const std::string& file) : reader_(in), file_(file) { soup_.source.file = file; }

    PolygonSoup run() {
        std::string line;
        std::string continued;
        while (reader_.next(line)) {
            const long long first_line = reader_.line_number();
            // Join continuation lines ("...\" + next line).
            while (!line.empty() && line.back() == '\\') {
                line.pop_back();
                if (!reader_.next(continued)) {
                    break;
                }
                line += ' ';
                line += continued;
            }
            parse_line(line, first_line);
        }
        if (!saw_content_) {
            io_fail(file_, 0, "empty file");
        }
        finish();
        return std::move(soup_);
    }

  private:
    void parse_line(std::string_view text, long long line) {
        detail::io_split(detail::io_strip_comment(text), tokens_);
        if (tokens_.empty()) {
            return;
        }
        saw_content_ = true;
        const std::string_view key = tokens_[0];
        if (key == "v") {
            parse_vertex(line);
        } else if (key == "f" || key == "fo") {
            parse_face(line);
        } else if (key == "vt") {
            ++num_texcoords_;
        } else if (key == "vn") {
            ++num_normals_;
        } else if (key == "t") {
            parse_tag(line);
        } else if (key == "g") {
            by_group_.current = group_number(by_group_);
        } else if (key == "usemtl") {
            by_material_.current = group_number(by_material_);
            saw_material_ = saw_material_ || by_material_.current >= 0;
        } else if (contains(ignored_keywords, key)) {
            return;
        } else if (contains(freeform_keywords, key)) {
            io_fail(file_, line, "free-form geometry keyword " + io_quote(key) + " is not supported");
        } else {
            io_fail(file_, line, "unknown keyword " + io_quote(key));
        }
    }

    void parse_vertex(long long line) {
        const std::size_t n = tokens_.size() - 1;
        if (n != 3 && n != 4 && n != 6 && n != 7) {
            io_fail(file_, line,
                    "'v' needs 3 coordinates (optionally followed by w and/or r g b), found " + std::to_string(n) +
                        " values");
        }
        double x = detail::io_to_double(tokens_[1], file_, line);
        double y = detail::io_to_double(tokens_[2], file_, line);
        double z = detail::io_to_double(tokens_[3], file_, line);
        for (std::size_t i = 4; i <= n; ++i) {
            (void)detail::io_to_double(tokens_[i], file_, line);  // colours: checked, unused
        }
        if (n == 4 || n == 7) {
            const double w = detail::io_to_double(tokens_[4], file_, line);
            if (w == 0.0) {
                io_fail(file_, line, "homogeneous coordinate w is 0");
            }
            if (w != 1.0) {
                x /= w;
                y /= w;
                z /= w;
            }
        }
        if (coordinates_.size() / 3 >= detail::io_max_count) {
            io_fail(file_, line, "too many vertices");
        }
        coordinates_.push_back(x);
        coordinates_.push_back(y);
        coordinates_.push_back(z);
        soup_.source.vertex_lines.push_back(static_cast<int>(line));
    }

    [[nodiscard]] Index num_vertices() const { return static_cast<Index>(coordinates_.size() / 3); }

    /// Resolves one index of a face corner; @p count is the number of elements defined so
    /// far. Returns the 1-based index (negative indices made absolute), which may exceed
    /// @p count for a positive index.
    long long resolve(std::string_view token, std::string_view what, long long count, long long line) {
        const long long value = detail::io_to_int(token, file_, line);
        if (value == 0) {
            io_fail(file_, line, std::string(what) + " index 0 is invalid (OBJ indices start at 1)");
        }
        if (value > 0) {
            return value;
        }
        const long long resolved = count + 1 + value;
        if (resolved < 1) {
            io_fail(file_, line,
                    std::string(what) + " index " + std::to_string(value) + " resolves to " + std::to_string(resolved) +
                        ", out of range [1, " + std::to_string(count) + "]");
        }
        return resolved;
    }

    /// A vertex index; positive ones may name vertices defined later and are checked by
    /// finish(). Returns the 0-based index, or huge_index beyond what Index can hold.
    Index vertex_index(std::string_view token, long long line) {
        const long long value = resolve(token, "vertex", num_vertices(), line);
        if (value > static_cast<long long>(detail::io_max_count)) {
            if (first_huge_line_ == 0) {
                first_huge_line_ = line;
                first_huge_value_ = value;
            }
            return huge_index;
        }
        return static_cast<Index>(value - 1);
    }

    void parse_face(long long line) {
        corners_.clear();
        for (std::size_t i = 1; i < tokens_.size(); ++i) {
            const std::string_view corner = tokens_[i];
            const auto slash1 = corner.find('/');
            const std::string_view vertex = corner.substr(0, slash1);
            if (slash1 != std::string_view::npos) {
                const std::string_view rest = corner.substr(slash1 + 1);
                const auto slash2 = rest.find('/');
                const std::string_view texcoord = rest.substr(0, slash2);
                const std::string_view normal =
                    slash2 == std::string_view::npos ? std::string_view() : rest.substr(slash2 + 1);
                const bool bad_form = vertex.empty() || (slash2 == std::string_view::npos && texcoord.empty()) ||
                                      (slash2 != std::string_view::npos && normal.empty()) ||
                                      normal.find('/') != std::string_view::npos;
                if (bad_form) {
                    io_fail(file_, line,
                            "malformed face corner " + io_quote(corner) + " (expected v, v/vt, v//vn or v/vt/vn)");
                }
                if (!texcoord.empty()) {
                    check_attribute(texcoord, "texture coordinate", num_texcoords_, line, largest_texcoord_);
                }
                if (!normal.empty()) {
                    check_attribute(normal, "normal", num_normals_, line, largest_normal_);
                }
            }
            corners_.push_back(vertex_index(vertex, line));
        }
        if (soup_.face_vertices.size() + corners_.size() > detail::io_max_count) {
            io_fail(file_, line, "too many face corners");
        }
        soup_.add_face(corners_, static_cast<int>(line));
        by_group_.face_group.push_back(by_group_.current);
        by_material_.face_group.push_back(by_material_.current);
    }

    /// The group named by a `g` or `usemtl` line: its first name, or -1 (none) without one.
    Index group_number(FaceGroups& groups) const {
        return tokens_.size() < 2 ? Index{-1} : groups.add_name(tokens_[1]);
    }

    /// The face groups: by `usemtl` when the file names a material, else by `g`; names are
    /// numbered in the order faces first use them, and names no face uses are dropped.
    void finish_groups() {
        const FaceGroups& read = saw_material_ ? by_material_ : by_group_;
        std::vector<Index> renumber(read.names.size(), -1);
        FaceGroups groups;
        groups.face_group.reserve(read.face_group.size());
        for (const Index g : read.face_group) {
            if (g >= 0 && renumber[static_cast<std::size_t>(g)] < 0) {
                renumber[static_cast<std::size_t>(g)] = groups.add_name(read.names[static_cast<std::size_t>(g)]);
            }
            groups.face_group.push_back(g >= 0 ? renumber[static_cast<std::size_t>(g)] : Index{-1});
        }
        if (!groups.names.empty()) {
            soup_.groups = std::move(groups);
        }
    }

    /// Texture and normal indices are not used, but must be valid integers in range.
    /// Texture and normal indices are not used, but must be valid integers naming an element of the file. Like
    /// vertex indices, positive ones may name elements defined later: the largest is checked by finish().
    void check_attribute(std::string_view token, std::string_view what, long long count, long long line,
                         AttributeReference& largest) {
        const long long value = resolve(token, what, count, line);
        if (value > largest.value) {
            largest = AttributeReference{value, line};
        }
    }

    // ---- tags: t NAME nints/nfloats/nstrings ints... floats... strings...

    struct TagArgs {
        std::vector<long long> ints;
        std::vector<double> floats;
        std::vector<std::string_view> strings;
    };

    std::size_t count_field(std::string_view text, std::string_view header, long long line) {
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string_view::npos;
        if (!digits) {
            io_fail(file_, line,
                    "malformed tag argument counts " + io_quote(header) + " (expected nints/nfloats/nstrings)");
        }
        return static_cast<std::size_t>(detail::io_to_int(text, file_, line));
    }

    void parse_tag(long long line) {
        if (tokens_.size() >= 2 &&
            (tokens_[1] == "vertexedit" || tokens_[1] == "edgeedit" || tokens_[1] == "faceedit")) {
            io_fail(file_, line, "hierarchical edit tag " + io_quote(tokens_[1]) + " is not supported");
        }
        if (tokens_.size() < 3) {
            io_fail(file_, line, "a tag needs a name and argument counts: t NAME nints/nfloats/nstrings ...");
        }
        const std::string_view name = tokens_[1];
        const std::string_view header = tokens_[2];
        const auto s1 = header.find('/');
        const auto s2 = s1 == std::string_view::npos ? s1 : header.find('/', s1 + 1);
        if (s1 == std::string_view::npos || s2 == std::string_view::npos ||
            header.find('/', s2 + 1) != std::string_view::npos) {
            io_fail(file_, line,
                    "malformed tag argument counts " + io_quote(header) + " (expected nints/nfloats/nstrings)");
        }
        const std::size_t nints = count_field(header.substr(0, s1), header, line);
        const std::size_t nfloats = count_field(header.substr(s1 + 1, s2 - s1 - 1), header, line);
        const std::size_t nstrings = count_field(header.substr(s2 + 1), header, line);
        const std::size_t available = tokens_.size() - 3;
        // Compare without overflow: each count is at most what the line holds.
        if (nints > available || nfloats > available || nstrings > available ||
            nints + nfloats + nstrings != available) {
            io_fail(file_, line,
                    "tag " + io_quote(name) + " declares " + std::string(header) + " = " +
                        std::to_string(nints + nfloats + nstrings) + " arguments but has " + std::to_string(available));
        }
        TagArgs args;
        std::size_t next = 3;
        for (std::size_t i = 0; i < nints; ++i) {
            args.ints.push_back(detail::io_to_int(tokens_[next++], file_, line));
        }
        for (std::size_t i = 0; i < nfloats; ++i) {
            args.floats.push_back(detail::io_to_double(tokens_[next++], file_, line));
        }
        for (std::size_t i = 0; i < nstrings; ++i) {
            args.strings.push_back(tokens_[next++]);
        }
        apply_tag(name, args, line);
    }

    void expect_counts(std::string_view name, const TagArgs& args, std::size_t nints, std::size_t nfloats,
                       std::size_t nstrings, long long line) {
        if (args.ints.size() != nints || args.floats.size() != nfloats || args.strings.size() != nstrings) {
            io_fail(file_, line,
                    "tag " + io_quote(name) + " takes " + std::to_string(nints) + "/" + std::to_string(nfloats) + "/" +
                        std::to_string(nstrings) + " arguments, found " + std::to_string(args.ints.size()) + "/" +
                        std::to_string(args.floats.size()) + "/" + std::to_string(args.strings.size()));
        }
    }

    Index tag_index(long long value, long long line) {
        if (value < std::numeric_limits<Index>::min() || value > std::numeric_limits<Index>::max()) {
            io_fail(file_, line, "tag index " + std::to_string(value) + " is out of range");
        }
        return static_cast<Index>(value);
    }

    void apply_tag(std::string_view name, const TagArgs& args, long long line) {
        const int tag_line = static_cast<int>(line);
        if (name == "crease") {
            const std::size_t pairs = args.ints.size() / 2;
            if (args.ints.empty() || args.ints.size() % 2 != 0) {
                io_fail(file_, line,
                        "tag 'crease' needs an even, non-zero number of vertex indices, found " +
                            std::to_string(args.ints.size()));
            }
            if (args.floats.size() != 1 && args.floats.size() != pairs) {
                io_fail(file_, line,
                        "tag 'crease' needs 1 sharpness or one per edge (" + std::to_string(pairs) + "), found " +
                            std::to_string(args.floats.size()));
            }
            if (!args.strings.empty()) {
                io_fail(file_, line, "tag 'crease' takes no strings");
            }
            for (std::size_t p = 0; p < pairs; ++p) {
                const double sharpness = args.floats.size() == 1 ? args.floats[0] : args.floats[p];
                soup_.sharpness.creases.push_back(CreaseTag{
                    tag_index(args.ints[2 * p], line), tag_index(args.ints[2 * p + 1], line), sharpness, tag_line});
            }
        } else if (name == "corner") {
            if (args.ints.empty()) {
                io_fail(file_, line, "tag 'corner' needs at least one vertex index");
            }
            if (args.floats.size() != 1 && args.floats.size() != args.ints.size()) {
                io_fail(file_, line,
                        "tag 'corner' needs 1 sharpness or one per vertex (" + std::to_string(args.ints.size()) +
                            "), found " + std::to_string(args.floats.size()));
            }
            if (!args.strings.empty()) {
                io_fail(file_, line, "tag 'corner' takes no strings");
            }
            for (std::size_t i = 0; i < args.ints.size(); ++i) {
                const double sharpness = args.floats.size() == 1 ? args.floats[0] : args.floats[i];
                soup_.sharpness.corners.push_back(CornerTag{tag_index(args.ints[i], line), sharpness, tag_line});
            }
        } else if (name == "hole") {
            if (args.ints.empty() || !args.floats.empty() || !args.strings.empty()) {
                io_fail(file_, line, "tag 'hole' needs one or more face indices and nothing else");
            }
            for (const long long face : args.ints) {
                soup_.sharpness.holes.push_back(HoleTag{tag_index(face, line), tag_line});
            }
        } else if (name == "interpolateboundary") {
            expect_counts(name, args, 1, 0, 0, line);
            switch (args.ints[0]) {
            case 0:
                soup_.hints.boundary = BoundaryInterpolation::None;
                break;
            case 1:
                soup_.hints.boundary = BoundaryInterpolation::EdgeAndCorner;
                break;
            case 2:
                soup_.hints.boundary = BoundaryInterpolation::EdgeOnly;
                break;
            default:
                io_fail(file_, line,
                        "tag 'interpolateboundary' value " + std::to_string(args.ints[0]) +
                            " is not 0 (none), 1 (edge-and-corner) or 2 (edge-only)");
            }
        } else if (name == "creasemethod") {
            expect_counts(name, args, 0, 0, 1, line);
            if (args.strings[0] == "normal") {
                soup_.hints.creasing = CreasingMethod::Uniform;
            } else if (args.strings[0] == "chaikin") {
                soup_.hints.creasing = CreasingMethod::Chaikin;
            } else {
                io_fail(file_, line,
                        "tag 'creasemethod' value " + io_quote(args.strings[0]) + " is not 'normal' or 'chaikin'");
            }
        } else if (name == "smoothtriangles") {
            expect_counts(name, args, 0, 0, 1, line);
            if (args.strings[0] == "catmark") {
                soup_.hints.triangles = TriangleSubdivision::CatmullClark;
            } else if (args.strings[0] == "smooth") {
                soup_.hints.triangles = TriangleSubdivision::Smooth;
            } else {
                io_fail(file_, line,
                        "tag 'smoothtriangles' value " + io_quote(args.strings[0]) + " is not 'catmark' or 'smooth'");
            }
        } else if (name == "facevaryinginterpolateboundary" || name == "facevaryingpropagatecorners") {
            return;  // face-varying data is not read
        } else {
            io_fail(file_, line, "unknown tag " + io_quote(name));
        }
    }

    void check_largest(const AttributeReference& largest, const char* what, long long count) {
        if (largest.value > count) {
            io_fail(file_, largest.line,
                    std::string(what) + " index " + std::to_string(largest.value) + " out of range [1, " +
                        std::to_string(count) + "]");
        }
    }

    /// Positive indices may name vertices defined later in the file: check them at the end.
    void finish() {
        const Index nv = num_vertices();
        for (Index f = 0; f < soup_.num_faces(); ++f) {
            for (const Index v : soup_.face(f)) {
                if (v < nv) {
                    continue;
                }
                const long long line = soup_.source.face_lines[static_cast<std::size_t>(f)];
                const long long token = v == huge_index ? first_huge_value_ : v + 1LL;
                if (nv == 0) {
                    io_fail(file_, line,
                            "vertex index " + std::to_string(token) + " out of range: the file has no vertices");
                }
                io_fail(file_, line,
                        "vertex index " + std::to_string(token) + " out of range [1, " + std::to_string(nv) + "]");
            }
        }
        check_largest(largest_texcoord_, "texture coordinate", num_texcoords_);
        check_largest(largest_normal_, "normal", num_normals_);
        finish_groups();
        soup_.positions.resize(nv, 3);
        for (Index v = 0; v < nv; ++v) {
            for (Index c = 0; c < 3; ++c) {
                soup_.positions(v, c) = coordinates_[3 * static_cast<std::size_t>(v) + static_cast<std::size_t>(c)];
            }
        }
    }

    detail::IoLineReader reader_;
    const std::string& file_;
    PolygonSoup soup_;
    std::vector<double> coordinates_;
    std::vector<std::string_view> tokens_;
    std::vector<Index> corners_;
    long long num_texcoords_ = 0;
    long long num_normals_ = 0;
    AttributeReference largest_texcoord_;
    AttributeReference largest_normal_;
    long long first_huge_line_ = 0;
    long long first_huge_value_ = 0;
    bool saw_content_ = false;
    FaceGroups by_group_;     ///< faces' groups by `g`
    FaceGroups by_material_;  ///< faces' groups by `usemtl`
    bool saw_material_ = false;
};

void write_tag_counts(std::ostream& out, const char* name, std::size_t nints, std::size_t nfloats,
                      std::size_t nstrings) {
    out << "t " << name << ' ' << nints << '/' << nfloats << '/' << nstrings;
}

}  // namespace

PolygonSoup read_obj(std::istream& in, const std::string& source_name) {
    return ObjReader(in, source_name).run();
}

PolygonSoup read_obj(const std::filesystem::path& path) {
    std::ifstream in = open_input_file(path);
    return read_obj(in, path.string());
}

namespace {

void write_obj_tags(std::ostream& out, const PolygonSoup& soup);

/// Group names go on `g` lines: one token, nothing a reader would split or cut at.
void check_group_names(const FaceGroups& groups, Index num_faces) {
    groups.check(num_faces);
    for (const std::string& name : groups.names) {
        for (const char c : name) {
            const auto byte = static_cast<unsigned char>(c);
            LIMSURF_CHECK(byte > ' ' && byte != 0x7f && c != '#' && c != '\\', InputError,
                          "cannot write face group name ", detail::io_quote(name),
                          " to OBJ: a name must not contain blanks, control characters, '#' or '\\'");
        }
    }
}

/// The `v` (and with texture coordinates `vt`) and `f` lines, then the tags.
void write_obj_lines(std::ostream& out, const PolygonSoup& soup, const Eigen::MatrixXd* texcoords) {
    detail::io_check_soup(soup);
    check_group_names(soup.groups, soup.num_faces());
    if (texcoords != nullptr) {
        LIMSURF_CHECK(texcoords->rows() == soup.num_vertices() && texcoords->cols() == 2, InputError,
                      "texture coordinates: expected ", soup.num_vertices(), " × 2 values, got ", texcoords->rows(),
                      " × ", texcoords->cols());
        LIMSURF_CHECK(texcoords->allFinite(), InputError, "texture coordinates: a value is not finite");
    }
    out << "# written by limsurf\n";
    for (Index v = 0; v < soup.num_vertices(); ++v) {
        out << 'v';
        for (Index c = 0; c < 3; ++c) {
            out << ' ';
            detail::io_write_double(out, soup.positions(v, c));
        }
        out << '\n';
    }
    if (texcoords != nullptr) {
        for (Index v = 0; v < soup.num_vertices(); ++v) {
            out << "vt ";
            detail::io_write_double(out, (*texcoords)(v, 0));
            out << ' ';
            detail::io_write_double(out, (*texcoords)(v, 1));
            out << '\n';
        }
    }
    for (Index f = 0; f < soup.num_faces(); ++f) {
        if (!soup.groups.empty() && (f == 0 || soup.groups.group_of(f) != soup.groups.group_of(f - 1))) {
            const Index g = soup.groups.group_of(f);
            out << (g >= 0 ? "g " + soup.groups.names[static_cast<std::size_t>(g)] : std::string("g")) << '\n';
        }
        out << 'f';
        for (const Index v : soup.face(f)) {
            const long long index = static_cast<long long>(v) + 1;
            out << ' ' << index;
            if (texcoords != nullptr) {
                out << '/' << index;
            }
        }
        out << '\n';
    }
    write_obj_tags(out, soup);
}

void write_obj_tags(std::ostream& out, const PolygonSoup& soup) {
    for (const CreaseTag& crease : soup.sharpness.creases) {
        write_tag_counts(out, "crease", 2, 1, 0);
        out << ' ' << crease.v0 << ' ' << crease.v1 << ' ';
        detail::io_write_double(out, crease.sharpness);
        out << '\n';
    }
    for (const CornerTag& corner : soup.sharpness.corners) {
        write_tag_counts(out, "corner", 1, 1, 0);
        out << ' ' << corner.vertex << ' ';
        detail::io_write_double(out, corner.sharpness);
        out << '\n';
    }
    for (const HoleTag& hole : soup.sharpness.holes) {
        write_tag_counts(out, "hole", 1, 0, 0);
        out << ' ' << hole.face << '\n';
    }
    if (soup.hints.boundary) {
        int value = 0;
        switch (*soup.hints.boundary) {
        case BoundaryInterpolation::None:
            value = 0;
            break;
        case BoundaryInterpolation::EdgeAndCorner:
            value = 1;
            break;
        case BoundaryInterpolation::EdgeOnly:
            value = 2;
            break;
        }
        write_tag_counts(out, "interpolateboundary", 1, 0, 0);
        out << ' ' << value << '\n';
    }
    if (soup.hints.creasing) {
        write_tag_counts(out, "creasemethod", 0, 0, 1);
        out << (*soup.hints.creasing == CreasingMethod::Chaikin ? " chaikin\n" : " normal\n");
    }
    if (soup.hints.triangles) {
        write_tag_counts(out, "smoothtriangles", 0, 0, 1);
        out << (*soup.hints.triangles == TriangleSubdivision::Smooth ? " smooth\n" : " catmark\n");
    }
    detail::io_check_written(out, "OBJ");
}

}  // namespace

void write_obj(std::ostream& out, const PolygonSoup& soup) {
    write_obj_lines(out, soup, nullptr);
}

void write_obj(std::ostream& out, const PolygonSoup& soup, const Eigen::MatrixXd& texcoords) {
    write_obj_lines(out, soup, &texcoords);
}

}  // namespace limsurf
