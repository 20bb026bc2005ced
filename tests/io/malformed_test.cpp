// One test per parse-level defect: tests/data/malformed/parse_*.{obj,off,ply}. Each file has
// exactly one problem, and the reader must name it with the file and line (or, in binary
// PLY data, the element and byte offset).
#include <algorithm>
#include <filesystem>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "support/paths.h"

namespace limsurf {
namespace {

struct Defect {
    const char* file;
    const char* expected;  ///< the message after the path
};

std::filesystem::path malformed(const std::string& name) {
    return test::test_data_dir() / "malformed" / name;
}

class ParseDefect : public ::testing::TestWithParam<Defect> {};

TEST_P(ParseDefect, IsReportedWithFileAndLine) {
    const Defect& defect = GetParam();
    const auto path = malformed(defect.file);
    ASSERT_TRUE(std::filesystem::exists(path)) << path;
    try {
        (void)read_polygon_soup(path);
        FAIL() << defect.file << " was accepted";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()), path.string() + defect.expected);
    }
}

const Defect defects[] = {
    // OBJ
    {"parse_empty.obj", ": empty file"},
    {"parse_only_comments.obj", ": empty file"},
    {"parse_bad_number.obj", ":4: invalid number '1.5x'"},
    {"parse_bad_index_token.obj", ":5: invalid integer '3x'"},
    {"parse_index_out_of_range.obj", ":5: vertex index 99 out of range [1, 3]"},
    {"parse_index_zero.obj", ":5: vertex index 0 is invalid (OBJ indices start at 1)"},
    {"parse_negative_index.obj", ":5: vertex index -5 resolves to -1, out of range [1, 3]"},
    {"parse_unknown_keyword.obj", ":3: unknown keyword 'vx'"},
    {"parse_vertex_arity.obj", ":2: 'v' needs 3 coordinates (optionally followed by w and/or r g b), found 2 values"},
    {"parse_w_zero.obj", ":2: homogeneous coordinate w is 0"},
    {"parse_face_corner_form.obj", ":5: malformed face corner '1/1/1/1' (expected v, v/vt, v//vn or v/vt/vn)"},
    {"parse_tag_arity.obj", ":6: tag 'crease' declares 2/1/0 = 3 arguments but has 2"},
    {"parse_tag_crease_odd.obj", ":6: tag 'crease' needs an even, non-zero number of vertex indices, found 3"},
    {"parse_tag_crease_floats.obj", ":6: tag 'crease' needs 1 sharpness or one per edge (2), found 3"},
    {"parse_tag_counts.obj", ":2: malformed tag argument counts '2/1' (expected nints/nfloats/nstrings)"},
    {"parse_unknown_tag.obj", ":2: unknown tag 'sharpness'"},
    {"parse_tag_value.obj",
     ":2: tag 'interpolateboundary' value 5 is not 0 (none), 1 (edge-and-corner) or 2 (edge-only)"},
    {"parse_hierarchical_edit.obj", ":6: hierarchical edit tag 'vertexedit' is not supported"},
    {"parse_freeform.obj", ":2: free-form geometry keyword 'cstype' is not supported"},
    // OFF
    {"parse_empty.off", ": empty file"},
    {"parse_only_comments.off", ": empty file"},
    {"parse_missing_header.off", ":1: expected the 'OFF' header, found '3'"},
    {"parse_bad_counts.off", ":2: expected the counts 'nv nf ne', found 1 values"},
    {"parse_truncated.off", ":5: unexpected end of file: expected 4 vertices, found 3"},
    {"parse_truncated_faces.off", ":7: unexpected end of file: expected 2 faces, found 1"},
    {"parse_absurd_counts.off", ":2: 1000000000000 vertices and 1 faces cannot fit in the remaining 6 bytes"},
    {"parse_bad_number.off", ":4: invalid number 'zero'"},
    {"parse_index_out_of_range.off", ":6: vertex index 3 out of range [0, 2]"},
    {"parse_face_short.off", ":6: face 0 declares 4 corners but the line has 3 values"},
    {"parse_binary.off", ":1: binary OFF is not supported"},
    // PLY
    {"parse_empty.ply", ": empty file"},
    {"parse_bad_magic.ply", ":1: expected 'ply' on the first line, found 'plx'"},
    {"parse_no_end_header.ply", ":4: unexpected end of file in the header (no 'end_header')"},
    {"parse_bad_format.ply", ":2: unsupported PLY version '2.0'"},
    {"parse_unknown_type.ply", ":4: unknown property type 'float128'"},
    {"parse_missing_z.ply", ":3: element 'vertex' has no property 'z'"},
    {"parse_missing_vertex_indices.ply",
     ":7: element 'face' has no list property 'vertex_indices' (or 'vertex_index')"},
    {"parse_too_few_values.ply", ":9: element 'vertex' has too few values on this line"},
    {"parse_too_many_values.ply", ":9: element 'vertex' has 1 more values than its properties"},
    {"parse_ascii_index_out_of_range.ply", ":13: vertex index 3 out of range [0, 2]"},
    {"parse_truncated_ascii.ply", ":9: unexpected end of file: expected 3 'vertex' elements, found 2"},
    {"parse_truncated_binary.ply", ": element 'face' 1 (byte offset 218): unexpected end of file"},
    {"parse_absurd_count.ply", ":3: element 'vertex' declares 1000000000000 entries, more than the 20 bytes after the "
                               "header can hold"},
    {"parse_binary_index_out_of_range.ply", ": element 'face' 1 (byte offset 254): vertex index 7 out of range [0, 2]"},
};

INSTANTIATE_TEST_SUITE_P(EveryParseDefect, ParseDefect, ::testing::ValuesIn(defects),
                         [](const ::testing::TestParamInfo<Defect>& param) {
                             std::string name = param.param.file;
                             std::replace(name.begin(), name.end(), '.', '_');
                             return name;
                         });

TEST(ParseDefects, EveryParseFixtureHasATest) {
    std::set<std::string> tested;
    for (const Defect& defect : defects) {
        tested.insert(defect.file);
    }
    for (const auto& entry : std::filesystem::directory_iterator(malformed(""))) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("parse_")) {
            EXPECT_TRUE(tested.contains(name)) << name << " has no expected message";
        }
    }
}

}  // namespace
}  // namespace limsurf
