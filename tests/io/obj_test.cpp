#include <bit>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/obj.h"
#include "support/paths.h"
#include "support/soup_helpers.h"

namespace limsurf {
namespace {

using test::faces_of;

PolygonSoup parse(const std::string& text, const std::string& name = "mem.obj") {
    std::istringstream in(text);
    return read_obj(in, name);
}

std::string parse_error(const std::string& text, const std::string& name = "mem.obj") {
    try {
        (void)parse(text, name);
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

bool same_bits(double a, double b) {
    return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

TEST(ObjRead, EveryFaceFormGroupsMaterialsAndComments) {
    const PolygonSoup soup = read_obj(test::io_fixture("cube_forms.obj"));
    EXPECT_EQ(soup.source.file, test::io_fixture("cube_forms.obj").string());
    ASSERT_EQ(soup.num_vertices(), 8);
    EXPECT_EQ(soup.positions.row(6), Eigen::RowVector3d(1, 1, 1));
    EXPECT_EQ(soup.positions.row(7), Eigen::RowVector3d(0, 1, 1));
    const std::vector<std::vector<Index>> expected{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                   {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    EXPECT_EQ(faces_of(soup), expected);
    EXPECT_EQ(soup.source.vertex_lines, (std::vector<int>{4, 5, 6, 7, 8, 9, 10, 11}));
    EXPECT_EQ(soup.source.face_lines, (std::vector<int>{26, 28, 31, 32, 33, 34}));
    EXPECT_TRUE(soup.sharpness.empty());
    EXPECT_TRUE(soup.hints.empty());
}

TEST(ObjRead, NegativeIndicesAreRelativeToTheElementsAbove) {
    const PolygonSoup soup = read_obj(test::io_fixture("negative.obj"));
    const std::vector<std::vector<Index>> expected{{0, 1, 2}, {0, 1, 3}, {1, 3, 2}};
    EXPECT_EQ(faces_of(soup), expected);
}

TEST(ObjRead, CrlfLineEndings) {
    const PolygonSoup soup = read_obj(test::io_fixture("crlf.obj"));
    ASSERT_EQ(soup.num_vertices(), 4);
    EXPECT_EQ(soup.positions.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1, 2, 3}}));
    EXPECT_EQ(soup.source.face_lines, std::vector<int>{7});
}

TEST(ObjRead, ContinuationLinesJoinAndKeepTheFirstLineNumber) {
    const PolygonSoup soup = read_obj(test::io_fixture("continuation.obj"));
    ASSERT_EQ(soup.num_vertices(), 4);
    EXPECT_EQ(soup.positions.row(1), Eigen::RowVector3d(1, 0, 0));
    EXPECT_EQ(soup.source.vertex_lines, (std::vector<int>{1, 2, 4, 5}));
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1, 2, 3}}));
    EXPECT_EQ(soup.source.face_lines, std::vector<int>{6});
}

TEST(ObjRead, HomogeneousCoordinatesAreDividedAndColoursIgnored) {
    const PolygonSoup soup = read_obj(test::io_fixture("homogeneous.obj"));
    ASSERT_EQ(soup.num_vertices(), 5);
    EXPECT_EQ(soup.positions.row(0), Eigen::RowVector3d(1, 2, 3));
    EXPECT_EQ(soup.positions.row(2), Eigen::RowVector3d(0, 2, 0));
    EXPECT_EQ(soup.positions.row(3), Eigen::RowVector3d(0, 0, 0));
    EXPECT_EQ(soup.positions.row(4), Eigen::RowVector3d(0, 0, 1));
}

TEST(ObjRead, OpenSubdivShapeStringWithTags) {
    const std::string shape = "v 0 0 0\n"
                              "v 1 0 0\n"
                              "v 1 1 0\n"
                              "v 0 1 0\n"
                              "f 1 2 3 4\n"
                              "t crease 2/1/0 0 1 6.0\n"
                              "t corner 1/1/0 3 10.0\n"
                              "t interpolateboundary 1/0/0 2\n"
                              "t creasemethod 0/0/1 chaikin\n";
    const PolygonSoup soup = parse(shape);
    ASSERT_EQ(soup.sharpness.creases.size(), 1U);
    EXPECT_EQ(soup.sharpness.creases[0].v0, 0);
    EXPECT_EQ(soup.sharpness.creases[0].v1, 1);
    EXPECT_EQ(soup.sharpness.creases[0].sharpness, 6.0);
    EXPECT_EQ(soup.sharpness.creases[0].line, 6);
    ASSERT_EQ(soup.sharpness.corners.size(), 1U);
    EXPECT_EQ(soup.sharpness.corners[0].vertex, 3);
    EXPECT_EQ(soup.sharpness.corners[0].sharpness, 10.0);
    EXPECT_EQ(soup.sharpness.corners[0].line, 7);
    EXPECT_EQ(soup.hints.boundary, BoundaryInterpolation::EdgeOnly);
    EXPECT_EQ(soup.hints.creasing, CreasingMethod::Chaikin);
    EXPECT_FALSE(soup.hints.triangles.has_value());
}

TEST(ObjRead, EveryTagOfTheShapeFixture) {
    const PolygonSoup soup = read_obj(test::io_fixture("shape_tags.obj"));
    ASSERT_EQ(soup.num_faces(), 6);
    const auto& creases = soup.sharpness.creases;
    ASSERT_EQ(creases.size(), 3U);
    EXPECT_EQ(creases[1].v0, 2);
    EXPECT_EQ(creases[1].v1, 3);
    EXPECT_EQ(creases[1].sharpness, 1.5);
    EXPECT_EQ(creases[2].v0, 4);
    EXPECT_EQ(creases[2].v1, 5);
    EXPECT_EQ(creases[2].sharpness, 2.5);
    EXPECT_EQ(creases[2].line, 20);
    const auto& corners = soup.sharpness.corners;
    ASSERT_EQ(corners.size(), 3U);
    EXPECT_EQ(corners[1].vertex, 6);
    EXPECT_EQ(corners[2].vertex, 7);
    EXPECT_EQ(corners[2].sharpness, 3.0);
    ASSERT_EQ(soup.sharpness.holes.size(), 1U);
    EXPECT_EQ(soup.sharpness.holes[0].face, 5);
    EXPECT_EQ(soup.sharpness.holes[0].line, 22);
    EXPECT_EQ(soup.hints.boundary, BoundaryInterpolation::EdgeOnly);
    EXPECT_EQ(soup.hints.creasing, CreasingMethod::Chaikin);
    EXPECT_EQ(soup.hints.triangles, TriangleSubdivision::Smooth);
}

TEST(ObjRead, OtherTagValues) {
    const PolygonSoup soup =
        parse("t interpolateboundary 1/0/0 0\nt creasemethod 0/0/1 normal\nt smoothtriangles 0/0/1 "
              "catmark\nt crease 4/1/0 0 1 1 2 3\nt corner 2/2/0 0 1 1 2\n");
    EXPECT_EQ(soup.hints.boundary, BoundaryInterpolation::None);
    EXPECT_EQ(soup.hints.creasing, CreasingMethod::Uniform);
    EXPECT_EQ(soup.hints.triangles, TriangleSubdivision::CatmullClark);
    ASSERT_EQ(soup.sharpness.creases.size(), 2U);
    EXPECT_EQ(soup.sharpness.creases[1].sharpness, 3.0);  // one value for every pair
    ASSERT_EQ(soup.sharpness.corners.size(), 2U);
    EXPECT_EQ(soup.sharpness.corners[1].sharpness, 2.0);  // one value per vertex
    EXPECT_EQ(parse("t interpolateboundary 1/0/0 1\n").hints.boundary, BoundaryInterpolation::EdgeAndCorner);
}

TEST(ObjRead, TagIndicesAreStoredAsGivenForValidation) {
    const PolygonSoup soup = parse("t crease 2/1/0 -1 70 2.0\nt hole 1/0/0 9\n");
    EXPECT_EQ(soup.sharpness.creases[0].v0, -1);
    EXPECT_EQ(soup.sharpness.creases[0].v1, 70);
    EXPECT_EQ(soup.sharpness.holes[0].face, 9);
}

TEST(ObjRead, SmallFacesArePassedOnToValidation) {
    const PolygonSoup soup = parse("v 0 0 0\nv 1 0 0\nf 1 2\nf\nf 1\n");
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1}, {}, {0}}));
    EXPECT_EQ(soup.source.face_lines, (std::vector<int>{3, 4, 5}));
}

TEST(ObjRead, PositiveIndicesMayNameLaterVertices) {
    const PolygonSoup soup = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1, 2}}));
    EXPECT_EQ(parse("f 1/1/1 2/2/1 3/1/1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvn 0 0 1\n").num_faces(), 1);
    EXPECT_EQ(parse_error("f 1/3 2/2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\n"),
              "mem.obj:1: texture coordinate index 3 out of range [1, 2]");
}

TEST(ObjRead, NonFiniteNumbersAreLeftToValidation) {
    const PolygonSoup soup = parse("v nan inf -inf\n");
    EXPECT_TRUE(std::isnan(soup.positions(0, 0)));
    EXPECT_EQ(soup.positions(0, 1), std::numeric_limits<double>::infinity());
    EXPECT_EQ(soup.positions(0, 2), -std::numeric_limits<double>::infinity());
}

TEST(ObjRead, FilesWithoutFacesAreNotAParseError) {
    const PolygonSoup soup = parse("v 0 0 0\n");
    EXPECT_EQ(soup.num_vertices(), 1);
    EXPECT_EQ(soup.num_faces(), 0);
}

TEST(ObjRead, ErrorsNameTheSourceAndLine) {
    EXPECT_EQ(parse_error("v 0 0 0\nv 1 +2 3e\n"), "mem.obj:2: invalid number '3e'");
    EXPECT_EQ(parse_error("v 0 0 1e999\n"), "mem.obj:1: number '1e999' is out of range for a double");
    EXPECT_EQ(parse_error("v 0 0 0\nf 1 2 3\n"), "mem.obj:2: vertex index 2 out of range [1, 1]");
    EXPECT_EQ(parse_error("f 1 2 3\n"), "mem.obj:1: vertex index 1 out of range: the file has no vertices");
    EXPECT_EQ(parse_error("f 1 2 99999999999\nv 0 0 0\n"), "mem.obj:1: vertex index 2 out of range [1, 1]");
    EXPECT_EQ(parse_error("v 0 0 0\nf 1 1 99999999999\n"), "mem.obj:2: vertex index 99999999999 out of range [1, 1]");
    EXPECT_EQ(parse_error("v 0 0 0\nf 1/1 1 1\n"), "mem.obj:2: texture coordinate index 1 out of range [1, 0]");
    EXPECT_EQ(parse_error("v 0 0 0\nf 1//-2 1 1\n"), "mem.obj:2: normal index -2 resolves to -1, out of range [1, 0]");
    EXPECT_EQ(parse_error("v 0 0 0\nf 1/ 1 1\n"),
              "mem.obj:2: malformed face corner '1/' (expected v, v/vt, v//vn or v/vt/vn)");
    EXPECT_EQ(parse_error("v 0 0 0\nf /1 1 1\n"),
              "mem.obj:2: malformed face corner '/1' (expected v, v/vt, v//vn or v/vt/vn)");
    EXPECT_EQ(parse_error("bogus\x01 1\n"), "mem.obj:1: unknown keyword 'bogus\\x01'");
    EXPECT_EQ(parse_error("t crease 2/1/0 0 1 x\n"), "mem.obj:1: invalid number 'x'");
    EXPECT_EQ(parse_error("t corner 2/3/0 0 1 1 2 3\n"),
              "mem.obj:1: tag 'corner' needs 1 sharpness or one per vertex (2), found 3");
    EXPECT_EQ(parse_error("t hole 1/1/0 0 1.0\n"),
              "mem.obj:1: tag 'hole' needs one or more face indices and nothing else");
    EXPECT_EQ(parse_error("t creasemethod 0/0/1 sharp\n"),
              "mem.obj:1: tag 'creasemethod' value 'sharp' is not 'normal' or 'chaikin'");
    EXPECT_EQ(parse_error("t smoothtriangles 1/0/0 1\n"),
              "mem.obj:1: tag 'smoothtriangles' takes 0/0/1 arguments, found 1/0/0");
    EXPECT_EQ(parse_error("t edgeedit\n"), "mem.obj:1: hierarchical edit tag 'edgeedit' is not supported");
    EXPECT_EQ(parse_error("t crease 99999999999999999999/0/0\n"),
              "mem.obj:1: integer '99999999999999999999' is out of range");
    EXPECT_EQ(parse_error("t crease 2/1/0 0 5000000000 1\n"), "mem.obj:1: tag index 5000000000 is out of range");
    EXPECT_EQ(parse_error("\n\nv 1\n", ""), "line 3: 'v' needs 3 coordinates (optionally followed by w "
                                            "and/or r g b), found 1 values");
}

/// A soup whose coordinates exercise every corner of double formatting.
PolygonSoup awkward_soup() {
    std::mt19937_64 random(7);
    PolygonSoup soup;
    const std::vector<double> specials{0.1,
                                       1.0 / 3.0,
                                       -0.0,
                                       1e-300,
                                       5e-324,
                                       2.2250738585072014e-308,
                                       1.7976931348623157e308,
                                       -123456789.125,
                                       1e22,
                                       0.30000000000000004,
                                       std::numeric_limits<double>::quiet_NaN(),
                                       -std::numeric_limits<double>::infinity()};
    const Index nv = 40;
    soup.positions.resize(nv, 3);
    for (Index i = 0; i < nv * 3; ++i) {
        const auto k = static_cast<std::size_t>(i);
        double value = k < specials.size() ? specials[k] : 0.0;
        if (k >= specials.size()) {
            do {
                value = std::bit_cast<double>(random());
            } while (!std::isfinite(value));
        }
        soup.positions(i / 3, i % 3) = value;
    }
    for (Index f = 0; f + 3 < nv; f += 2) {
        const std::vector<Index> corners{f, f + 1, f + 3, f + 2};
        soup.add_face(corners);
    }
    soup.add_face(std::vector<Index>{0, 5});
    soup.sharpness.creases = {{0, 1, 2.5, 0}, {3, 4, 0.1, 0}};
    soup.sharpness.corners = {{7, 10.0, 0}};
    soup.sharpness.holes = {{2, 0}};
    soup.hints.boundary = BoundaryInterpolation::None;
    soup.hints.creasing = CreasingMethod::Chaikin;
    soup.hints.triangles = TriangleSubdivision::Smooth;
    return soup;
}

TEST(ObjWrite, RoundTripIsExact) {
    const PolygonSoup soup = awkward_soup();
    std::ostringstream out;
    write_obj(out, soup);
    const PolygonSoup back = parse(out.str(), "back.obj");
    ASSERT_EQ(back.num_vertices(), soup.num_vertices());
    for (Index v = 0; v < soup.num_vertices(); ++v) {
        for (Index c = 0; c < 3; ++c) {
            const double a = soup.positions(v, c);
            const double b = back.positions(v, c);
            EXPECT_TRUE(same_bits(a, b) || (std::isnan(a) && std::isnan(b))) << v << "," << c;
        }
    }
    EXPECT_EQ(back.face_offsets, soup.face_offsets);
    EXPECT_EQ(back.face_vertices, soup.face_vertices);
    ASSERT_EQ(back.sharpness.creases.size(), 2U);
    EXPECT_EQ(back.sharpness.creases[1].v0, 3);
    EXPECT_EQ(back.sharpness.creases[1].v1, 4);
    EXPECT_TRUE(same_bits(back.sharpness.creases[1].sharpness, 0.1));
    ASSERT_EQ(back.sharpness.corners.size(), 1U);
    EXPECT_EQ(back.sharpness.corners[0].vertex, 7);
    EXPECT_EQ(back.sharpness.corners[0].sharpness, 10.0);
    ASSERT_EQ(back.sharpness.holes.size(), 1U);
    EXPECT_EQ(back.sharpness.holes[0].face, 2);
    EXPECT_EQ(back.hints.boundary, soup.hints.boundary);
    EXPECT_EQ(back.hints.creasing, soup.hints.creasing);
    EXPECT_EQ(back.hints.triangles, soup.hints.triangles);

    // Writing what was read gives the same text.
    std::ostringstream again;
    write_obj(again, back);
    EXPECT_EQ(again.str(), out.str());
}

TEST(ObjWrite, EveryBoundaryHintRoundTrips) {
    for (const auto boundary :
         {BoundaryInterpolation::None, BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::EdgeAndCorner}) {
        PolygonSoup soup;
        soup.hints.boundary = boundary;
        soup.hints.creasing = CreasingMethod::Uniform;
        soup.hints.triangles = TriangleSubdivision::CatmullClark;
        std::ostringstream out;
        write_obj(out, soup);
        const PolygonSoup back = parse(out.str());
        EXPECT_EQ(back.hints.boundary, boundary);
        EXPECT_EQ(back.hints.creasing, CreasingMethod::Uniform);
        EXPECT_EQ(back.hints.triangles, TriangleSubdivision::CatmullClark);
    }
}

TEST(ObjWrite, RefusesAMalformedSoup) {
    PolygonSoup soup;
    soup.positions.setZero(2, 3);
    soup.add_face(std::vector<Index>{0, 1, 2});
    std::ostringstream out;
    EXPECT_THROW(write_obj(out, soup), InputError);
}

TEST(ObjRead, ByteOrderMarkAndClassicMacLineEndings) {
    // A UTF-8 byte-order mark is skipped; a lone CR ends a line, numbered as such.
    const PolygonSoup bom = parse("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(bom.num_vertices(), 3);
    EXPECT_EQ(bom.source.vertex_lines[0], 1);
    const PolygonSoup cr = parse("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r");
    EXPECT_EQ(cr.num_vertices(), 3);
    EXPECT_EQ(cr.num_faces(), 1);
    EXPECT_EQ(cr.source.face_lines[0], 4);
    EXPECT_EQ(parse_error("v 0 0 0\rv 1 0 x\r"), "mem.obj:2: invalid number 'x'");
    // Mixed: CRLF lines with a lone CR inside one of them.
    EXPECT_EQ(parse("v 0 0 0\r\nv 1 0 0\rv 0 1 0\r\nf 1 2 3\r\n").source.face_lines[0], 4);
}

}  // namespace
}  // namespace limsurf
