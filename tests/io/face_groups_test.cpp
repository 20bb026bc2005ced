// Face groups: OBJ `g` / `usemtl`, their round trip through write_obj, the per-face group file,
// and the groups through build_control_mesh().
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/face_groups.h"
#include "limsurf/io/obj.h"
#include "limsurf/mesh/control_mesh.h"
#include "support/soup_helpers.h"

namespace limsurf {
namespace {

/// A strip of @p n unit quads along x, each face on its own line after the header.
std::string strip(int n) {
    std::string text;
    for (int i = 0; i <= n; ++i) {
        text += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\n";
    }
    return text;
}

std::string quad(int i) {
    const int a = 2 * i + 1;
    return "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + " " +
           std::to_string(a + 1) + "\n";
}

PolygonSoup parse(const std::string& text) {
    std::istringstream in(text);
    return read_obj(in, "mem.obj");
}

FaceGroups parse_groups(const std::string& text, Index num_faces) {
    std::istringstream in(text);
    return read_face_groups(in, "groups.txt", num_faces);
}

std::string groups_error(const std::string& text, Index num_faces) {
    try {
        (void)parse_groups(text, num_faces);
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

TEST(ObjGroups, FilesWithoutGroupsHaveNone) {
    const PolygonSoup soup = parse(strip(2) + quad(0) + quad(1));
    EXPECT_TRUE(soup.groups.empty());
    EXPECT_TRUE(soup.groups.face_group.empty());
    EXPECT_EQ(soup.groups.group_of(0), -1);
    // A bare `g` (and `o`, `s`) names no group either.
    EXPECT_TRUE(parse(strip(1) + "o thing\ng\ns 1\n" + quad(0)).groups.empty());
}

TEST(ObjGroups, GroupNamesTheFacesBelowIt) {
    // Several names: the first; a bare g ends the group; names unused by faces are dropped.
    const PolygonSoup soup = parse(strip(5) + "g unused\ng left\n" + quad(0) + quad(1) + "g\n" + quad(2) +
                                   "g right extra\n" + quad(3) + "g left\n" + quad(4));
    EXPECT_EQ(soup.groups.names, (std::vector<std::string>{"left", "right"}));
    EXPECT_EQ(soup.groups.face_group, (std::vector<Index>{0, 0, -1, 1, 0}));
    EXPECT_EQ(soup.groups.find("right"), 1);
    EXPECT_EQ(soup.groups.find("unused"), -1);
}

TEST(ObjGroups, MaterialsWinOverGroups) {
    const PolygonSoup soup =
        parse(strip(4) + quad(0) + "g a\nusemtl steel\n" + quad(1) + "g b\n" + quad(2) + "usemtl glass\n" + quad(3));
    EXPECT_EQ(soup.groups.names, (std::vector<std::string>{"steel", "glass"}));
    EXPECT_EQ(soup.groups.face_group, (std::vector<Index>{-1, 0, 0, 1}));
}

TEST(ObjGroups, TheCubeFixtureIsAllGrey) {
    // cube_forms.obj: `g bottom`, then `usemtl grey` before every face, then more `g` lines.
    const PolygonSoup soup = read_obj(test::io_fixture("cube_forms.obj"));
    EXPECT_EQ(soup.groups.names, (std::vector<std::string>{"grey"}));
    EXPECT_EQ(soup.groups.face_group, (std::vector<Index>(6, 0)));
}

TEST(ObjGroups, WriteAndReadGiveTheSameGroups) {
    PolygonSoup soup = parse(strip(5) + quad(0) + quad(1) + quad(2) + quad(3) + quad(4));
    soup.groups.names = {"matrix", "grain"};
    soup.groups.face_group = {-1, 0, 0, 1, 0};
    std::ostringstream out;
    write_obj(out, soup);
    const std::string text = out.str();
    EXPECT_NE(text.find("\ng matrix\nf 3 5 6 4\nf 5 7 8 6\ng grain\n"), std::string::npos) << text;
    const PolygonSoup back = parse(text);
    EXPECT_EQ(back.groups.names, soup.groups.names);
    EXPECT_EQ(back.groups.face_group, soup.groups.face_group);
    EXPECT_EQ(test::faces_of(back), test::faces_of(soup));
    // Without groups nothing changes: no `g` line.
    soup.groups = {};
    std::ostringstream plain;
    write_obj(plain, soup);
    EXPECT_EQ(plain.str().find("\ng"), std::string::npos);
}

TEST(ObjGroups, WriterRefusesWhatCannotRoundTrip) {
    PolygonSoup soup = parse(strip(2) + quad(0) + quad(1));
    for (const std::string bad : {"two words", "a#b", "tab\there", ""}) {
        soup.groups.names = {bad};
        soup.groups.face_group = {0, 0};
        std::ostringstream out;
        EXPECT_THROW(write_obj(out, soup), InputError) << bad;
    }
    soup.groups.names = {"a"};
    soup.groups.face_group = {0};  // one entry for two faces
    std::ostringstream out;
    EXPECT_THROW(write_obj(out, soup), InputError);
    soup.groups.face_group = {0, 1};  // no group 1
    EXPECT_THROW(write_obj(out, soup), InputError);
    soup.groups.names = {"a", "a"};
    soup.groups.face_group = {0, 1};
    EXPECT_THROW(write_obj(out, soup), InputError);
}

TEST(PolygonSoupGroups, AddFaceUsesTheCurrentGroup) {
    PolygonSoup soup;
    soup.positions = Points::Zero(4, 3);
    const std::vector<Index> corners{0, 1, 2};
    soup.add_face(corners);
    soup.set_group("a");
    soup.add_face(corners);
    soup.set_group("b");
    soup.add_face(corners);
    soup.set_group("");
    soup.add_face(corners);
    soup.set_group("a");
    soup.add_face(corners);
    EXPECT_EQ(soup.groups.names, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(soup.groups.face_group, (std::vector<Index>{-1, 0, 1, -1, 0}));
    EXPECT_NO_THROW(soup.groups.check(soup.num_faces()));
}

TEST(BuildControlMesh, FacesKeepTheirGroups) {
    PolygonSoup soup = parse(strip(3) + "usemtl x\n" + quad(0) + "usemtl y\n" + quad(1) + quad(2));
    const BuildResult built = build_control_mesh(soup);
    EXPECT_EQ(built.groups.names, (std::vector<std::string>{"x", "y"}));
    EXPECT_EQ(built.groups.face_group, (std::vector<Index>{0, 1, 1}));
    soup.groups.face_group.pop_back();
    EXPECT_THROW((void)build_control_mesh(soup), InputError);
}

TEST(FaceGroupFile, NamesInOrderOfFirstUse) {
    const FaceGroups groups = parse_groups("# materials\nsoft\nhard  # the second face\n\nsoft\n-1\n", 4);
    EXPECT_EQ(groups.names, (std::vector<std::string>{"soft", "hard", "-1"}));
    EXPECT_EQ(groups.face_group, (std::vector<Index>{0, 1, 0, 2}));
}

TEST(FaceGroupFile, IntegersAreTheGroupNumbers) {
    const FaceGroups groups = parse_groups("2\n0\n-1\n2\n", 4);
    EXPECT_EQ(groups.names, (std::vector<std::string>{"0", "1", "2"}));
    EXPECT_EQ(groups.face_group, (std::vector<Index>{2, 0, -1, 2}));
    EXPECT_NO_THROW(groups.check(4));
    EXPECT_TRUE(parse_groups("-1\n-1\n", 2).empty());
    EXPECT_TRUE(parse_groups("", 0).face_group.empty());
}

TEST(FaceGroupFile, ErrorsNameFileAndLine) {
    EXPECT_EQ(groups_error("a\nb c\n", 2), "groups.txt:2: expected one group (a name or an integer) per line, found 2 "
                                           "tokens");
    EXPECT_EQ(groups_error("a\n\nb\nc\n", 2), "groups.txt:4: entry 3 'c', but the mesh has 2 faces");
    EXPECT_EQ(groups_error("a\n# b\n", 2), "groups.txt: 1 entries, the mesh has 2 faces");
    EXPECT_EQ(groups_error("", 2), "groups.txt: empty file");
    EXPECT_EQ(groups_error("1\n-2\n", 2), "groups.txt:2: group '-2' out of range (-1 for no group, else 0 to 65535)");
    EXPECT_EQ(groups_error("1\n70000\n", 2),
              "groups.txt:2: group '70000' out of range (-1 for no group, else 0 to 65535)");
    try {
        (void)read_face_groups(test::io_fixture("no_such_file.txt"), 1);
        ADD_FAILURE() << "no error";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("no_such_file.txt: cannot open"), std::string::npos) << error.what();
    }
}

}  // namespace
}  // namespace limsurf
