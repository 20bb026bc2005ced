#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <sstream>
#include <streambuf>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/ply.h"
#include "support/paths.h"
#include "support/soup_helpers.h"

namespace limsurf {
namespace {

using test::faces_of;

PolygonSoup parse(const std::string& bytes) {
    std::istringstream in(bytes, std::ios::in | std::ios::binary);
    return read_ply(in, "mem.ply");
}

std::string parse_error(const std::string& bytes) {
    try {
        (void)parse(bytes);
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

PolygonSoup random_soup(unsigned seed, Index nv) {
    std::mt19937_64 random(seed);
    PolygonSoup soup;
    soup.positions.resize(nv, 3);
    for (Index v = 0; v < nv; ++v) {
        for (Index c = 0; c < 3; ++c) {
            double value = 0.0;
            do {
                value = std::bit_cast<double>(random());
            } while (!std::isfinite(value));
            soup.positions(v, c) = value;
        }
    }
    soup.positions(0, 0) = -0.0;
    soup.positions(0, 1) = 5e-324;
    for (Index f = 0; f + 3 < nv; f += 2) {
        soup.add_face(std::vector<Index>{f, f + 1, f + 3, f + 2});
    }
    soup.add_face(std::vector<Index>{0, 2, 1});
    return soup;
}

void expect_same_soup(const PolygonSoup& a, const PolygonSoup& b) {
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    for (Index v = 0; v < a.num_vertices(); ++v) {
        for (Index c = 0; c < 3; ++c) {
            EXPECT_EQ(std::bit_cast<std::uint64_t>(a.positions(v, c)), std::bit_cast<std::uint64_t>(b.positions(v, c)))
                << "vertex " << v;
        }
    }
    EXPECT_EQ(a.face_offsets, b.face_offsets);
    EXPECT_EQ(a.face_vertices, b.face_vertices);
}

TEST(PlyRead, AsciiWithExtraElementsListsAndTheVertexIndexAlias) {
    const PolygonSoup soup = read_ply(test::io_fixture("extra_element.ply"));
    ASSERT_EQ(soup.num_vertices(), 4);
    EXPECT_EQ(soup.positions.row(0), Eigen::RowVector3d(0, 0, 0));
    EXPECT_EQ(soup.positions.row(1), Eigen::RowVector3d(1, 0, 0));
    EXPECT_EQ(soup.positions.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(soup.positions.row(3), Eigen::RowVector3d(0, 1, 0));
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1, 2}, {0, 2, 3}}));
    EXPECT_EQ(soup.source.vertex_lines, (std::vector<int>{24, 25, 26, 27}));
    EXPECT_EQ(soup.source.face_lines, (std::vector<int>{28, 29}));
}

TEST(PlyRead, HandMadeBinaryWithExtraPropertiesAndElements) {
    const PolygonSoup little = read_ply(test::io_fixture("extra_props_le.ply"));
    const PolygonSoup big = read_ply(test::io_fixture("extra_props_be.ply"));
    ASSERT_EQ(little.num_vertices(), 5);
    EXPECT_EQ(little.positions.row(4), Eigen::RowVector3d(0.5, 0.5, 0.75));
    EXPECT_EQ(little.positions.row(2), Eigen::RowVector3d(1, 1, 0));
    EXPECT_EQ(faces_of(little),
              (std::vector<std::vector<Index>>{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}, {0, 3, 2, 1}}));
    EXPECT_EQ(little.source.vertex_lines, std::vector<int>(5, 0));
    EXPECT_EQ(little.source.face_lines, std::vector<int>(5, 0));
    expect_same_soup(little, big);
}

TEST(PlyRead, ScalarTypesOfEveryKind) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 1\nproperty char x\nproperty ushort y\n"
                               "property int32 z\nproperty uint8 w\nend_header\n";
    const PolygonSoup soup = parse(header + "-3 65535 -100000 7\n");
    EXPECT_EQ(soup.positions.row(0), Eigen::RowVector3d(-3, 65535, -100000));
    EXPECT_EQ(parse_error(header + "-3 1.5 0 0\n"), "mem.ply:9: invalid integer '1.5'");
}

TEST(PlyRead, NoFaceElementIsNotAParseError) {
    const PolygonSoup soup =
        parse("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty "
              "float z\nend_header\n0 0 0\n");
    EXPECT_EQ(soup.num_vertices(), 1);
    EXPECT_EQ(soup.num_faces(), 0);
}

TEST(PlyRead, HeaderErrors) {
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
              "mem.ply:3: 'property' before any 'element'");
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty double x\n"),
              "mem.ply:5: duplicate property 'x' in element 'vertex'");
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nend_header\n"), "mem.ply:3: the header declares no 'vertex' element");
    EXPECT_EQ(parse_error("ply\nend_header\n"), "mem.ply:2: the header has no 'format' line");
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n"),
              "mem.ply:4: list count type 'float' is not an integer type");
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 0\nproperty list uchar float vertex_indices\n"
                          "end_header\n"),
              "mem.ply:7: face property 'vertex_indices' must be a list of an integer type");
    EXPECT_EQ(parse_error("ply\nformat ascii 1.0\nelementary\n"), "mem.ply:3: unknown header keyword 'elementary'");
    EXPECT_EQ(parse_error("\n\n"), "mem.ply: empty file");
    EXPECT_EQ(parse_error("\nply\n"), "mem.ply:1: expected 'ply' on the first line");
}

TEST(PlyWrite, RoundTripEveryEncodingIsExact) {
    const PolygonSoup soup = random_soup(3, 24);
    for (const auto encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian, PlyEncoding::BinaryBigEndian}) {
        std::ostringstream out(std::ios::out | std::ios::binary);
        write_ply(out, soup, encoding);
        const PolygonSoup back = parse(out.str());
        expect_same_soup(soup, back);
    }
}

TEST(PlyWrite, BigEndianBytesAreBigEndian) {
    PolygonSoup soup;
    soup.positions.resize(3, 3);
    soup.positions << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0;
    soup.add_face(std::vector<Index>{0, 1, 2});
    std::ostringstream out(std::ios::out | std::ios::binary);
    write_ply(out, soup, PlyEncoding::BinaryBigEndian);
    const std::string bytes = out.str();
    ASSERT_NE(bytes.find("format binary_big_endian 1.0\n"), std::string::npos);
    const std::size_t data = bytes.find("end_header\n") + 11;
    const std::size_t faces = data + std::size_t{9} * 8;  // after nine doubles
    ASSERT_EQ(bytes.size(), faces + 1 + 3 * sizeof(std::int32_t));
    // 1.0 is 3f f0 00 ... in big-endian IEEE 754.
    EXPECT_EQ(static_cast<unsigned char>(bytes[data]), 0x3fU);
    EXPECT_EQ(static_cast<unsigned char>(bytes[data + 1]), 0xf0U);
    EXPECT_EQ(static_cast<unsigned char>(bytes[faces]), 3U);              // corner count
    EXPECT_EQ(static_cast<unsigned char>(bytes[faces + 1 + 4 + 3]), 1U);  // index 1
    expect_same_soup(soup, parse(bytes));
}

TEST(PlyWrite, FacesWithMoreThan255CornersUseWideCounts) {
    PolygonSoup soup;
    const Index n = 300;
    soup.positions.resize(n, 3);
    std::vector<Index> ring;
    for (Index v = 0; v < n; ++v) {
        const double angle = 2.0 * 3.141592653589793 * v / n;
        soup.positions.row(v) << std::cos(angle), std::sin(angle), 0.0;
        ring.push_back(v);
    }
    soup.add_face(ring);
    for (const auto encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryLittleEndian}) {
        std::ostringstream out(std::ios::out | std::ios::binary);
        write_ply(out, soup, encoding);
        EXPECT_NE(out.str().find("property list uint int vertex_indices"), std::string::npos);
        expect_same_soup(soup, parse(out.str()));
    }
}

TEST(PlyWrite, VertexFieldsBecomeDoubleProperties) {
    const PolygonSoup soup = random_soup(5, 6);
    VertexField scalar{"mean curvature", Eigen::MatrixXd::Constant(6, 1, 0.5)};
    VertexField vector{"normal", Eigen::MatrixXd::Ones(6, 3)};
    const std::vector<VertexField> fields{scalar, vector};
    for (const auto encoding : {PlyEncoding::Ascii, PlyEncoding::BinaryBigEndian}) {
        std::ostringstream out(std::ios::out | std::ios::binary);
        write_ply(out, soup, encoding, fields);
        const std::string text = out.str();
        EXPECT_NE(text.find("property double z\nproperty double mean_curvature\n"
                            "property double normal_x\nproperty double normal_y\n"
                            "property double normal_z\nelement face"),
                  std::string::npos);
        expect_same_soup(soup, parse(text));
    }
    std::ostringstream out;
    const std::vector<VertexField> clash{{"x", Eigen::MatrixXd::Zero(6, 1)}};
    EXPECT_THROW(write_ply(out, soup, PlyEncoding::Ascii, clash), InputError);
}

TEST(PlyRead, BinaryErrorsNameTheElementAndByteOffset) {
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\n"
        "property uchar z\nelement face 1\nproperty list uchar uchar vertex_indices\nend_header\n";
    const std::string ok = header + std::string("\x00\x00\x00\x03\x00\x00\x00", 7);
    EXPECT_EQ(parse(ok).num_faces(), 1);
    const std::string bad = header + std::string("\x00\x00\x00\x03\x00\x05\x00", 7);
    EXPECT_EQ(parse_error(bad), "mem.ply: element 'face' 0 (byte offset " + std::to_string(header.size() + 3) +
                                    "): vertex index 5 out of range [0, 0]");
    const std::string list_truncated = header + std::string("\x00\x00\x00\x09\x00\x00", 6);
    EXPECT_EQ(parse_error(list_truncated), "mem.ply: element 'face' 0 (byte offset " +
                                               std::to_string(header.size() + 3) + "): unexpected end of file");
}

TEST(PlyRead, ByteOrderMarkIsSkippedAndAClassicMacHeaderIsNamed) {
    const std::string ascii =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    EXPECT_EQ(parse("\xEF\xBB\xBF" + ascii).num_faces(), 1);
    std::string cr = ascii;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    EXPECT_EQ(parse_error(cr), "mem.ply:1: a carriage return (\\r) ends a line without a line feed (classic Mac OS "
                               "line endings): this format needs LF or CRLF line endings");
}

}  // namespace
}  // namespace limsurf
