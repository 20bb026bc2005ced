#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/vtk.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

/// Two quads sharing an edge, and a triangle: 7 vertices, 3 faces, 11 corners.
PolygonSoup strip() {
    PolygonSoup soup;
    soup.positions.resize(7, 3);
    soup.positions << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 1, 2, 0.5;
    soup.add_face(std::vector<Index>{0, 1, 4, 3});
    soup.add_face(std::vector<Index>{1, 2, 5, 4});
    soup.add_face(std::vector<Index>{3, 4, 6});
    return soup;
}

std::vector<VertexField> fields() {
    Eigen::MatrixXd k(7, 1);
    k << 0.5, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5;
    Eigen::MatrixXd n = Eigen::MatrixXd::Zero(7, 3);
    n.col(2).setOnes();
    return {{"mean curvature", k}, {"normal", n}};
}

std::string field_error(const VertexField& field, Index nv) {
    try {
        validate_vertex_field(field, nv);
    } catch (const InputError& error) {
        return error.what();
    }
    return "no error";
}

TEST(VertexField, Validation) {
    EXPECT_EQ(sanitize_field_name("mean curvature"), "mean_curvature");
    EXPECT_EQ(sanitize_field_name("a<b>&\"c\"\t.d-e"), "a_b___c__.d-e");
    Eigen::MatrixXd bad = Eigen::MatrixXd::Zero(4, 1);
    bad(2, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(field_error({"k", bad}, 4), "field 'k': row 2 is not finite (nan)");
    Eigen::MatrixXd bad3 = Eigen::MatrixXd::Zero(4, 3);
    bad3(3, 1) = std::numeric_limits<double>::infinity();
    EXPECT_EQ(field_error({"n", bad3}, 4), "field 'n': row 3, column 1 is not finite (inf)");
    EXPECT_EQ(field_error({"k", Eigen::MatrixXd::Zero(3, 1)}, 4), "field 'k': expected 4x1 or 4x3 values, got 3x1");
    EXPECT_EQ(field_error({"k", Eigen::MatrixXd::Zero(4, 2)}, 4), "field 'k': expected 4x1 or 4x3 values, got 4x2");
    EXPECT_EQ(field_error({"", Eigen::MatrixXd::Zero(4, 1)}, 4), "vertex field with an empty name");
    EXPECT_EQ(field_error({"k", Eigen::MatrixXd::Zero(4, 1)}, 4), "no error");

    const std::vector<VertexField> clash{{"a b", Eigen::MatrixXd::Zero(4, 1)}, {"a_b", Eigen::MatrixXd::Zero(4, 1)}};
    EXPECT_THROW(validate_vertex_fields(clash, 4), InputError);
    const std::vector<VertexField> vector_clash{{"n", Eigen::MatrixXd::Zero(4, 3)},
                                                {"n_x", Eigen::MatrixXd::Zero(4, 1)}};
    EXPECT_THROW(validate_vertex_fields(vector_clash, 4), InputError);
}

TEST(Vtk, LegacyPolydataStructure) {
    std::ostringstream out;
    write_vtk(out, strip(), fields());
    std::istringstream in(out.str());
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "# vtk DataFile Version 3.0");
    std::getline(in, line);  // title
    std::getline(in, line);
    EXPECT_EQ(line, "ASCII");
    std::getline(in, line);
    EXPECT_EQ(line, "DATASET POLYDATA");

    std::string word;
    std::string type;
    int count = 0;
    in >> word >> count >> type;
    EXPECT_EQ(word, "POINTS");
    EXPECT_EQ(count, 7);
    EXPECT_EQ(type, "double");
    double value = 0.0;
    for (int i = 0; i < 3 * count; ++i) {
        ASSERT_TRUE(in >> value);
    }
    EXPECT_EQ(value, 0.5);
    int size = 0;
    in >> word >> count >> size;
    EXPECT_EQ(word, "POLYGONS");
    EXPECT_EQ(count, 3);
    EXPECT_EQ(size, 3 + 11);
    int corners = 0;
    for (int f = 0; f < count; ++f) {
        int n = 0;
        ASSERT_TRUE(in >> n);
        for (int k = 0; k < n; ++k) {
            int v = -1;
            ASSERT_TRUE(in >> v);
            EXPECT_GE(v, 0);
            EXPECT_LT(v, 7);
        }
        corners += n + 1;
    }
    EXPECT_EQ(corners, size);
    in >> word >> count;
    EXPECT_EQ(word, "POINT_DATA");
    EXPECT_EQ(count, 7);
    std::string name;
    int components = 0;
    in >> word >> name >> type >> components;
    EXPECT_EQ(word, "SCALARS");
    EXPECT_EQ(name, "mean_curvature");
    EXPECT_EQ(components, 1);
    in >> word >> name;
    EXPECT_EQ(word, "LOOKUP_TABLE");
    EXPECT_EQ(name, "default");
    for (int i = 0; i < 7; ++i) {
        ASSERT_TRUE(in >> value);
    }
    EXPECT_EQ(value, 6.5);
    in >> word >> name >> type;
    EXPECT_EQ(word, "VECTORS");
    EXPECT_EQ(name, "normal");
    for (int i = 0; i < 21; ++i) {
        ASSERT_TRUE(in >> value);
    }
    EXPECT_FALSE(in >> word);  // nothing after the last field
}

/// The text between <DataArray ... Name="NAME" ...> and </DataArray>, split into tokens.
std::vector<std::string> data_array(const std::string& xml, const std::string& marker) {
    const auto start = xml.find(marker);
    if (start == std::string::npos) {
        return {};
    }
    const auto begin = xml.find('>', start) + 1;
    const auto end = xml.find("</DataArray>", begin);
    std::istringstream in(xml.substr(begin, end - begin));
    std::vector<std::string> tokens;
    for (std::string token; in >> token;) {
        tokens.push_back(token);
    }
    return tokens;
}

TEST(Vtk, XmlUnstructuredGridStructure) {
    std::ostringstream out;
    write_vtu(out, strip(), fields());
    const std::string xml = out.str();
    EXPECT_EQ(xml.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\"", 0), 0U);
    EXPECT_NE(xml.find("<Piece NumberOfPoints=\"7\" NumberOfCells=\"3\">"), std::string::npos);
    EXPECT_NE(xml.find("<PointData Scalars=\"mean_curvature\" Vectors=\"normal\">"), std::string::npos);
    EXPECT_EQ(data_array(xml, "NumberOfComponents=\"3\" format").size(), 21U);  // points
    EXPECT_EQ(data_array(xml, "Name=\"mean_curvature\"").size(), 7U);
    EXPECT_EQ(data_array(xml, "Name=\"normal\"").size(), 21U);
    EXPECT_EQ(data_array(xml, "Name=\"connectivity\""),
              (std::vector<std::string>{"0", "1", "4", "3", "1", "2", "5", "4", "3", "4", "6"}));
    EXPECT_EQ(data_array(xml, "Name=\"offsets\""), (std::vector<std::string>{"4", "8", "11"}));
    EXPECT_EQ(data_array(xml, "Name=\"types\""), (std::vector<std::string>{"7", "7", "7"}));
    EXPECT_EQ(xml.substr(xml.size() - 11), "</VTKFile>\n");
}

TEST(Vtk, WriteVertexDataDispatchesOnTheExtension) {
    const fs::path dir = test::make_temp_dir("vtk");
    const auto soup = strip();
    const auto data = fields();
    write_vertex_data(dir / "a.vtk", soup, data);
    write_vertex_data(dir / "a.VTU", soup, data);
    write_vertex_data(dir / "a.ply", soup, data, WriteOptions{PlyEncoding::BinaryLittleEndian});
    std::ifstream vtk(dir / "a.vtk");
    std::string first;
    std::getline(vtk, first);
    EXPECT_EQ(first, "# vtk DataFile Version 3.0");
    EXPECT_TRUE(fs::file_size(dir / "a.VTU") > 0);
    std::ifstream ply(dir / "a.ply", std::ios::binary);
    std::string magic;
    std::string format;
    std::getline(ply, magic);
    std::getline(ply, format);
    EXPECT_EQ(format, "format binary_little_endian 1.0");
    try {
        write_vertex_data(dir / "a.csv", soup, data);
        FAIL() << "no error";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()),
                  (dir / "a.csv").string() + ": unknown vertex data format '.csv' (expected .ply, .vtk or .vtu)");
    }
    // An invalid field leaves no file behind.
    std::vector<VertexField> bad = data;
    bad[0].values(3, 0) = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(write_vertex_data(dir / "b.vtu", soup, bad), InputError);
    EXPECT_FALSE(fs::exists(dir / "b.vtu"));
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) {
        ++n;
    }
    EXPECT_EQ(n, 3U);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace limsurf
