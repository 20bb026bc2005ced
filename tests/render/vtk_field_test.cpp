// Reading a per-point scalar back from legacy VTK (io/vtk.h read_vtk_point_scalar), the field source of
// `limsurf render --field FILE.vtk:NAME`: write_vtk's own output read back bit for bit, FIELD arrays,
// VTK 5.1 cell sections, and every refusal naming the file and line.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/vtk.h"
#include "support/paths.h"

namespace limsurf::test {
namespace {

namespace fs = std::filesystem;

const fs::path& dir() {
    static const fs::path d = make_temp_dir("render_vtk");
    return d;
}

fs::path write(const std::string& name, const std::string& text) {
    fs::path path = dir() / name;
    std::ofstream(path) << text;
    return path;
}

const std::string header = "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET POLYDATA\n"
                           "POINTS 3 double\n0 0 0 1 0 0\n0 1 0\nPOLYGONS 1 4\n3 0 1 2\n";

std::string error_of(const fs::path& path, const std::string& name) {
    try {
        (void)read_vtk_point_scalar(path, name);
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(VtkPointScalar, ReadsBackWhatWriteVtkWrote) {
    PolygonSoup soup;
    soup.positions = Points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
    soup.face_vertices = {0, 1, 3, 2};
    soup.face_offsets = {0, 4};
    const Eigen::VectorXd u = Eigen::Vector4d{0.1, -2.5e-300, 1.0 / 3.0, 7e15};
    const std::vector<VertexField> fields{{"v", Eigen::MatrixXd::Ones(4, 3)}, {"u", u}, {"f", 2.0 * u}};
    write_vertex_data(dir() / "w.vtk", soup, fields);
    EXPECT_EQ(read_vtk_point_scalar(dir() / "w.vtk", "u"), u);  // shortest round-trip text: bit for bit
    EXPECT_EQ(read_vtk_point_scalar(dir() / "w.vtk", "f"), 2.0 * u);
    EXPECT_NE(error_of(dir() / "w.vtk", "v").find("no point scalar 'v' (the file's point scalars: u, f)"),
              std::string::npos);
}

TEST(VtkPointScalar, ReadsFieldArraysAndVtk51Cells) {
    const fs::path field = write("field.vtk", header + "CELL_DATA 1\nSCALARS c float\nLOOKUP_TABLE default\n5\n"
                                                       "POINT_DATA 3\nNORMALS n float\n0 0 1 0 0 1 0 0 1\n"
                                                       "FIELD FieldData 2\nw 3 3 double\n1 2 3 4 5 6 7 8 9\n"
                                                       "u 1 3 double\n4 5 6\n");
    EXPECT_EQ(read_vtk_point_scalar(field, "u"), Eigen::Vector3d(4, 5, 6));
    EXPECT_NE(error_of(field, "c").find("field.vtk: 'c' is cell data, not point data"), std::string::npos);
    EXPECT_NE(error_of(field, "w").find("field.vtk:18: 'w' has 3 components: expected a scalar"), std::string::npos);
    const fs::path v51 =
        write("v51.vtk", "# vtk DataFile Version 5.1\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
                         "POLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\nCONNECTIVITY vtktypeint64\n0 1 2\n"
                         "POINT_DATA 3\nSCALARS u double 1\nLOOKUP_TABLE default\n1 2 3\n");
    EXPECT_EQ(read_vtk_point_scalar(v51, "u"), Eigen::Vector3d(1, 2, 3));
}

TEST(VtkPointScalar, RefusesWithFileAndLine) {
    const auto expect = [](const std::string& name, const std::string& text, const std::string& array,
                           const std::string& message) {
        const std::string what = error_of(write(name, text), array);
        EXPECT_NE(what.find(message), std::string::npos) << what;
    };
    expect("plain.txt", "hello\n", "u", "plain.txt:1: not a legacy VTK file");
    expect("binary.vtk", "# vtk DataFile Version 3.0\nt\nBINARY\n", "u", "binary.vtk:3: binary VTK is not supported");
    expect("count.vtk", header + "POINT_DATA 4\n", "u", "count.vtk:10: POINT_DATA 4 differs from POINTS 3");
    expect("vector.vtk", header + "POINT_DATA 3\nSCALARS u double 3\nLOOKUP_TABLE default\n", "u",
           "vector.vtk:12: 'u' has 3 components: expected a scalar");
    expect("short.vtk", header + "POINT_DATA 3\nSCALARS u double\nLOOKUP_TABLE default\n1 2\n", "u",
           "short.vtk:13: unexpected end of file: expected value 2 of 'u'");
    expect("word.vtk", header + "POINT_DATA 3\nSCALARS u double\nLOOKUP_TABLE default\n1\nx\n3\n", "u",
           "word.vtk:14: invalid number 'x'");
    expect("inf.vtk", header + "POINT_DATA 3\nSCALARS u double\nLOOKUP_TABLE default\n1\n2\ninf\n", "u",
           "inf.vtk:15: 'u' at point 2: value 'inf' is not finite");
    expect("odd.vtk", header + "POINT_DATA 3\nMETADATA\nINFORMATION 0\n", "u",
           "odd.vtk:11: unsupported VTK section 'METADATA' before the point scalar 'u'");
    EXPECT_THROW((void)read_vtk_point_scalar(dir() / "missing.vtk", "u"), InputError);
}

}  // namespace
}  // namespace limsurf::test
