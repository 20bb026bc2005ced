// validate(): one test per defect class, on the exact message and location.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "limsurf/mesh/validate.h"
#include "support/shapes.h"

namespace limsurf {
namespace {

/// A soup whose face f sits on line 100 + f and vertex v on line 1 + v of "m.obj".
PolygonSoup soup_of(const Points& positions, const std::vector<std::vector<Index>>& faces) {
    PolygonSoup soup;
    soup.positions = positions;
    soup.source.file = "m.obj";
    for (Index v = 0; v < positions.rows(); ++v) {
        soup.source.vertex_lines.push_back(1 + v);
    }
    for (std::size_t f = 0; f < faces.size(); ++f) {
        soup.add_face(faces[f], 100 + static_cast<int>(f));
    }
    return soup;
}

Points points(Index n) {
    Points x(n, 3);
    for (Index i = 0; i < n; ++i) {
        x.row(i) << std::cos(i), std::sin(i), 0.1 * i;
    }
    return x;
}

std::vector<std::string> messages(const ValidationReport& report) {
    std::vector<std::string> out;
    for (const Issue& issue : report.issues) {
        out.push_back(issue.to_string());
    }
    return out;
}

TEST(Validate, CleanCubeHasNoIssues) {
    const auto report = validate(soup_of(test::cube_positions(), test::cube_faces()));
    EXPECT_TRUE(report.issues.empty()) << report.summary();
    EXPECT_EQ(report.summary(), "no problems");
}

TEST(Validate, NoFaces) {
    const auto report = validate(soup_of(points(3), {}));
    EXPECT_EQ(messages(report), (std::vector<std::string>{"m.obj: no faces (3 vertices and no face)",
                                                          "m.obj:1: vertex 0 is in no face (isolated)",
                                                          "m.obj:2: vertex 1 is in no face (isolated)",
                                                          "m.obj:3: vertex 2 is in no face (isolated)"}));
    EXPECT_EQ(report.num_errors(), 1U);
    EXPECT_EQ(report.num_warnings(), 3U);
}

TEST(Validate, FaceTooSmallRepeatedVertexAndOutOfRange) {
    const auto report = validate(soup_of(points(4), {{0, 1}, {0, 1, 1, 2}, {0, 2, 9}, {0, 2, 3}}));
    EXPECT_EQ(messages(report), (std::vector<std::string>{
                                    "m.obj:100: face 0 has 2 vertices (a face needs at least 3)",
                                    "m.obj:101: face 1 repeats vertex 1",
                                    "m.obj:102: face 2 refers to vertex 9, out of range [0, 3]",
                                }));
    EXPECT_EQ(report.summary(), "m.obj:100: face 0 has 2 vertices (a face needs at least 3) (and 2 more errors)");
    EXPECT_THROW(report.throw_if_errors(), InputError);
}

TEST(Validate, NonManifoldEdge) {
    const auto report = validate(soup_of(points(5), {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
    ASSERT_FALSE(report.issues.empty());
    EXPECT_EQ(report.issues[0].problem, Problem::NonManifoldEdge);
    EXPECT_EQ(report.issues[0].to_string(),
              "m.obj:102: edge (0, 1) is shared by 3 faces (non-manifold): faces 0, 1, 2");
    EXPECT_THROW(report.throw_if_errors(), TopologyError);
}

TEST(Validate, NonManifoldVertex) {
    const auto report = validate(soup_of(points(5), {{0, 1, 2}, {0, 3, 4}}));
    EXPECT_EQ(messages(report),
              (std::vector<std::string>{
                  "m.obj:1: vertex 0 is non-manifold: its faces form 2 fans that meet only at this vertex (bow-tie)"}));
}

TEST(Validate, InconsistentOrientationSuggestsTheFacesToFlip) {
    auto faces = test::cube_faces();
    std::reverse(faces[3].begin(), faces[3].end());
    const auto report = validate(soup_of(test::cube_positions(), faces));
    ASSERT_EQ(report.issues.size(), 4U);  // face 3 disagrees with its 4 neighbours
    for (const Issue& issue : report.issues) {
        EXPECT_EQ(issue.problem, Problem::InconsistentOrientation);
        EXPECT_NE(issue.message.find("; reversing face 3 makes it consistent)"), std::string::npos) << issue.message;
    }
    EXPECT_EQ(report.issues[0].to_string(),
              "m.obj:103: faces 0 and 3 both traverse edge (2, 3) in the same direction (inconsistent orientation; "
              "reversing face 3 makes it consistent)");
}

TEST(Validate, MoebiusBandIsNonOrientable) {
    // A strip of 5 quads whose ends are glued with a half twist.
    const Index n = 5;
    std::vector<std::vector<Index>> faces;
    for (Index i = 0; i < n; ++i) {
        const Index a = i;
        const Index b = i + n;
        if (i + 1 < n) {
            faces.push_back({a, a + 1, b + 1, b});
        } else {
            faces.push_back({a, n, 0, b});  // twist: top of the last column meets the bottom of the first
        }
    }
    const auto report = validate(soup_of(points(2 * n), faces));
    ASSERT_EQ(report.num_errors(), 1U) << report.summary();
    EXPECT_EQ(report.issues[0].problem, Problem::NonOrientable);
    EXPECT_NE(report.issues[0].message.find("not orientable"), std::string::npos);
}

TEST(Validate, NonFiniteCoordinatesAndDegenerateFaces) {
    Points x = test::cube_positions();
    x(5, 1) = std::numeric_limits<double>::quiet_NaN();
    const auto report = validate(soup_of(x, test::cube_faces()));
    EXPECT_EQ(messages(report),
              (std::vector<std::string>{"m.obj:6: vertex 5 has a non-finite coordinate (1, nan, 1)"}));

    Points flat = test::cube_positions();
    flat.row(3) = flat.row(0);  // face {0, 2, 3, 1} keeps area; collapse a triangle instead
    const auto degenerate = validate(soup_of(points(4), {{0, 1, 2}, {0, 2, 3}}));
    EXPECT_EQ(degenerate.num_warnings(), 0U);
    Points line(3, 3);
    line << 0, 0, 0, 1, 0, 0, 2, 0, 0;
    const auto collinear = validate(soup_of(line, {{0, 1, 2}}));
    EXPECT_EQ(messages(collinear), (std::vector<std::string>{"m.obj:100: face 0 has zero area (degenerate)"}));
    EXPECT_FALSE(collinear.has_errors());
}

TEST(Validate, DuplicateFacesAreWarnings) {
    const auto report = validate(soup_of(points(3), {{0, 1, 2}, {0, 2, 1}}));
    EXPECT_EQ(messages(report),
              (std::vector<std::string>{"m.obj:101: face 1 has the same vertices as face 0 (duplicate face)"}));
}

TEST(Validate, TagsMustNameExistingElements) {
    PolygonSoup soup = soup_of(test::cube_positions(), test::cube_faces());
    soup.sharpness.creases.push_back({0, 7, 1.0, 200});
    soup.sharpness.creases.push_back({0, 1, -1.0, 201});
    soup.sharpness.corners.push_back({8, 10.0, 202});
    soup.sharpness.holes.push_back({6, 203});
    EXPECT_EQ(messages(validate(soup)),
              (std::vector<std::string>{"m.obj:200: crease (0, 7): no edge joins vertices 0 and 7",
                                        "m.obj:201: crease (0, 1): sharpness -1 is not a finite number >= 0",
                                        "m.obj:202: corner 8: vertex out of range [0, 7]",
                                        "m.obj:203: hole 6: face out of range [0, 5]"}));
}

// Before: a second tag of the same edge or vertex replaced the first without a word (and a later 0
// did not replace it at all); the file most likely holds a mistake, so both lines are named.
TEST(Validate, ConflictingRepeatedTagsAreWarnings) {
    PolygonSoup soup = soup_of(test::cube_positions(), test::cube_faces());
    soup.sharpness.creases.push_back({0, 1, 2.0, 200});
    soup.sharpness.creases.push_back({1, 0, 2.0, 201});  // the same sharpness again: harmless
    soup.sharpness.creases.push_back({1, 0, 0.0, 202});
    soup.sharpness.corners.push_back({3, 10.0, 203});
    soup.sharpness.corners.push_back({3, 1.5, 204});
    const auto report = validate(soup);
    EXPECT_EQ(messages(report),
              (std::vector<std::string>{
                  "m.obj:202: crease (1, 0) has sharpness 0 here and 2 at line 201; the last tag is used",
                  "m.obj:204: corner 3 has sharpness 1.5 here and 10 at line 203; the last tag is used"}));
    EXPECT_FALSE(report.has_errors());
    EXPECT_EQ(report.issues[0].problem, Problem::ConflictingTag);
    EXPECT_STREQ(problem_name(Problem::ConflictingTag), "conflicting-tag");

    PolygonSoup in_memory = soup_of(test::cube_positions(), test::cube_faces());
    in_memory.sharpness.corners.push_back({3, 10.0, 0});
    in_memory.sharpness.corners.push_back({3, 1.5, 0});
    EXPECT_EQ(
        messages(validate(in_memory)),
        (std::vector<std::string>{"m.obj: corner 3 has sharpness 1.5 here and 10 at tag 0; the last tag is used"}));
}

TEST(Validate, InMemoryDataHasNoLocation) {
    PolygonSoup soup;
    soup.positions = points(4);
    soup.add_face(std::vector<Index>{0, 1, 2});
    soup.source.face_lines.clear();
    const auto report = validate(soup);
    ASSERT_EQ(report.issues.size(), 1U);
    EXPECT_EQ(report.issues[0].to_string(), "vertex 3 is in no face (isolated)");
}

TEST(Validate, ProblemNamesAreStable) {
    EXPECT_STREQ(problem_name(Problem::NonManifoldEdge), "non-manifold-edge");
    EXPECT_EQ(severity_of(Problem::IsolatedVertex), Severity::Warning);
    EXPECT_EQ(severity_of(Problem::NonOrientable), Severity::Error);
}

}  // namespace
}  // namespace limsurf
