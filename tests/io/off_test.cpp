#include <algorithm>
#include <bit>
#include <cstdint>
#include <random>
#include <sstream>
#include <streambuf>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/off.h"
#include "support/paths.h"
#include "support/soup_helpers.h"

namespace limsurf {
namespace {

using test::faces_of;

PolygonSoup parse(const std::string& text) {
    std::istringstream in(text);
    return read_off(in, "mem.off");
}

std::string parse_error(const std::string& text) {
    try {
        (void)parse(text);
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

/// A stream buffer that cannot seek, like a pipe.
class PipeBuffer : public std::streambuf {
  public:
    explicit PipeBuffer(std::string data) : data_(std::move(data)) {
        setg(data_.data(), data_.data(), data_.data() + data_.size());
    }

  private:
    std::string data_;
};

TEST(OffRead, Cube) {
    const auto path = test::test_data_dir() / "io" / "cube.off";
    const PolygonSoup soup = read_off(path);
    EXPECT_EQ(soup.source.file, path.string());
    ASSERT_EQ(soup.num_vertices(), 8);
    ASSERT_EQ(soup.num_faces(), 6);
    EXPECT_EQ(soup.positions.row(6), Eigen::RowVector3d(1, 1, 1));
    EXPECT_EQ(faces_of(soup)[5], (std::vector<Index>{3, 0, 4, 7}));
    EXPECT_EQ(soup.source.vertex_lines.front(), 4);
    EXPECT_EQ(soup.source.face_lines.front(), 12);
    EXPECT_EQ(soup.source.face_lines.back(), 17);
}

TEST(OffRead, ColoursCommentsCrlfAndCountsOnTheHeaderLine) {
    const PolygonSoup soup = read_off(test::test_data_dir() / "io" / "colors.coff.off");
    ASSERT_EQ(soup.num_vertices(), 4);
    EXPECT_EQ(soup.positions.row(3), Eigen::RowVector3d(0, 1, 0));
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1, 2}, {0, 2, 3}}));
    EXPECT_EQ(soup.source.vertex_lines, (std::vector<int>{2, 3, 4, 6}));
    EXPECT_EQ(soup.source.face_lines, (std::vector<int>{7, 8}));
}

TEST(OffRead, HeaderVariants) {
    const std::string body = "3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
    for (const char* header : {"OFF", "COFF", "NOFF", "CNOFF", "STOFF", "STCNOFF"}) {
        EXPECT_EQ(parse(std::string(header) + "\n" + body).num_faces(), 1) << header;
    }
    EXPECT_EQ(parse_error("4OFF\n" + body),
              "mem.off:1: OFF variant '4OFF' is not supported (expected OFF, COFF, NOFF, CNOFF or "
              "STOFF)");
}

TEST(OffRead, SmallFacesAndNoFacesAreLeftToValidation) {
    const PolygonSoup soup = parse("OFF\n2 2 0\n0 0 0\n1 0 0\n2 0 1\n0\n");
    EXPECT_EQ(faces_of(soup), (std::vector<std::vector<Index>>{{0, 1}, {}}));
    EXPECT_EQ(parse("OFF\n1 0 0\n0 0 0\n").num_faces(), 0);
}

TEST(OffRead, Errors) {
    EXPECT_EQ(parse_error("OFF\n2 1\n0 0 0\n1 0 0\n-1\n"), "mem.off:5: face 0 has a negative corner count");
    EXPECT_EQ(parse_error("OFF\n-2 1\n"), "mem.off:2: negative vertex or face count");
    EXPECT_EQ(parse_error("OFF\n1 0\n0.0 0.0\n"), "mem.off:3: vertex 0 needs 3 coordinates, found 2");
    EXPECT_EQ(parse_error("OFF\n1 1 0\n0 0 0\n3 0 0 -1\n"), "mem.off:4: vertex index -1 out of range [0, 0]");
    EXPECT_EQ(parse_error("OFF\n1 1 0 7\n"), "mem.off:2: expected the counts 'nv nf ne', found 4 values");
    EXPECT_EQ(parse_error("OFF\n"), "mem.off:1: unexpected end of file: expected the counts line 'nv nf ne'");
    EXPECT_EQ(parse_error("OFF\n1 1 0\n0 0 0\n1000000000 0\n"),
              "mem.off:4: face 0 declares 1000000000 corners but the line has 1 values");
}

TEST(OffRead, UnseekableStreamsNeverAllocateFromTheCounts) {
    PipeBuffer pipe("OFF\n2000000000 2000000000\n0 0 0\n");
    std::istream in(&pipe);
    try {
        (void)read_off(in, "pipe");
        FAIL() << "no error";
    } catch (const InputError& error) {
        EXPECT_STREQ(error.what(), "pipe:3: unexpected end of file: expected 2000000000 vertices, found 1");
    }
    PipeBuffer huge("OFF\n1000000000000 1\n");
    std::istream in_huge(&huge);
    EXPECT_THROW((void)read_off(in_huge, "pipe"), InputError);
}

TEST(OffWrite, RoundTripIsExact) {
    std::mt19937_64 random(11);
    PolygonSoup soup;
    soup.positions.resize(30, 3);
    for (Index v = 0; v < 30; ++v) {
        for (Index c = 0; c < 3; ++c) {
            double value = 0.0;
            do {
                value = std::bit_cast<double>(random());
            } while (!std::isfinite(value));
            soup.positions(v, c) = value;
        }
    }
    soup.positions(0, 0) = -0.0;
    soup.positions(0, 1) = 0.1;
    for (Index f = 0; f + 4 < 30; f += 3) {
        soup.add_face(std::vector<Index>{f, f + 1, f + 4, f + 2, f + 3});
    }
    std::ostringstream out;
    write_off(out, soup);
    const PolygonSoup back = parse(out.str());
    ASSERT_EQ(back.num_vertices(), 30);
    for (Index v = 0; v < 30; ++v) {
        for (Index c = 0; c < 3; ++c) {
            EXPECT_EQ(std::bit_cast<std::uint64_t>(back.positions(v, c)),
                      std::bit_cast<std::uint64_t>(soup.positions(v, c)));
        }
    }
    EXPECT_EQ(back.face_offsets, soup.face_offsets);
    EXPECT_EQ(back.face_vertices, soup.face_vertices);
}

TEST(OffRead, ByteOrderMarkAndClassicMacLineEndings) {
    const std::string cube_like = "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
    EXPECT_EQ(parse("\xEF\xBB\xBF" + cube_like).num_faces(), 1);
    std::string cr = cube_like;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    const PolygonSoup soup = parse(cr);
    EXPECT_EQ(soup.num_vertices(), 4);
    EXPECT_EQ(soup.face(0).size(), 4U);
}

}  // namespace
}  // namespace limsurf
