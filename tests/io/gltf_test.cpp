// write_glb: every file is read back by tinygltf (an independent reader, test-only) and
// also taken apart byte by byte here, against the rules of the glTF 2.0 specification.
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "limsurf/core/error.h"
#include "limsurf/core/version.h"
#include "limsurf/io/gltf.h"
#include "support/paths.h"

namespace limsurf {
namespace {

namespace fs = std::filesystem;

constexpr int float_type = TINYGLTF_COMPONENT_TYPE_FLOAT;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string slurp(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

std::size_t entries(const fs::path& dir) {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) {
        ++n;
    }
    return n;
}

std::uint32_t le_u32(const unsigned char* bytes) {
    return static_cast<std::uint32_t>(bytes[0]) | (static_cast<std::uint32_t>(bytes[1]) << 8U) |
           (static_cast<std::uint32_t>(bytes[2]) << 16U) | (static_cast<std::uint32_t>(bytes[3]) << 24U);
}

std::uint32_t le_u32(const std::string& bytes, std::size_t offset) {
    return le_u32(reinterpret_cast<const unsigned char*>(bytes.data()) + offset);
}

/// The sRGB transfer function (IEC 61966-2-1), sRGB-encoded to linear.
double linear_from_srgb(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// A regular tetrahedron around the origin, faces counter-clockwise seen from outside,
/// with vertex normals, colours and a scalar. Coordinates 0.1 are not floats: rounding shows.
TriangleSurface tetrahedron() {
    TriangleSurface s;
    s.positions.resize(4, 3);
    s.positions << 0.1, 0.1, 0.1, 0.1, -0.1, -0.1, -0.1, 0.1, -0.1, -0.1, -0.1, 0.1;
    s.normals = s.positions.rowwise().normalized();
    s.triangles.resize(4, 3);
    s.triangles << 0, 1, 2, 1, 3, 2, 0, 2, 3, 0, 3, 1;
    s.colors.resize(4, 4);
    s.colors << 1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0.5F, 0.25F, 0.04F, 1;
    s.scalar.resize(4);
    s.scalar << -1.5, 0.1, 1e-3, 2.0 / 3.0;
    s.scalar_name = "mean curvature";
    return s;
}

/// The height field z = sin(x) cos(y) on [0, π]², n×n squares cut into 2n² triangles.
TriangleSurface grid(int n) {
    TriangleSurface s;
    const int side = n + 1;
    const Eigen::Index nv = Eigen::Index{side} * side;
    s.positions.resize(nv, 3);
    s.normals.resize(nv, 3);
    s.colors.resize(nv, 4);
    s.scalar.resize(nv);
    for (int i = 0; i < side; ++i) {
        for (int j = 0; j < side; ++j) {
            const int v = i * side + j;
            const double x = std::numbers::pi * i / n;
            const double y = std::numbers::pi * j / n;
            s.positions.row(v) << x, y, std::sin(x) * std::cos(y);
            s.normals.row(v) =
                Eigen::RowVector3d(-std::cos(x) * std::cos(y), std::sin(x) * std::sin(y), 1.0).normalized();
            s.colors.row(v) << static_cast<float>(i) / static_cast<float>(n),
                static_cast<float>(j) / static_cast<float>(n), 0.5F, 0.75F;
            s.scalar(v) = 1e3 * std::sin(x) * std::cos(y) + 0.1;
        }
    }
    s.triangles.resize(Eigen::Index{2} * n * n, 3);
    int t = 0;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const int a = i * side + j;
            const int b = (i + 1) * side + j;
            s.triangles.row(t++) << a, b, b + 1;
            s.triangles.row(t++) << a, b + 1, a + 1;
        }
    }
    s.scalar_name = "k";
    return s;
}

tinygltf::Model load(const fs::path& path) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const bool ok = loader.LoadBinaryFromFile(&model, &error, &warning, path.string(), tinygltf::REQUIRE_ALL);
    EXPECT_TRUE(ok) << error;
    EXPECT_EQ(warning, "");
    return model;
}

/// The components of an accessor of FLOAT (or UNSIGNED_INT, as doubles), row after row,
/// decoded from the buffer as little-endian values.
std::vector<double> accessor_values(const tinygltf::Model& model, int index) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(accessor.bufferView));
    const tinygltf::Buffer& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
    const int stride = accessor.ByteStride(view);
    EXPECT_GT(components, 0);
    EXPECT_EQ(stride, 4 * components);  // tightly packed, 4-byte components
    const std::size_t start = view.byteOffset + accessor.byteOffset;
    EXPECT_EQ(start % 4, 0U) << "accessor " << index;
    EXPECT_LE(accessor.byteOffset + accessor.count * static_cast<std::size_t>(stride), view.byteLength);
    EXPECT_LE(view.byteOffset + view.byteLength, buffer.data.size());
    std::vector<double> values;
    if (view.byteOffset + view.byteLength > buffer.data.size()) {
        return values;
    }
    for (std::size_t i = 0; i < accessor.count; ++i) {
        for (int c = 0; c < components; ++c) {
            const std::uint32_t bits = le_u32(buffer.data.data() + start + i * static_cast<std::size_t>(stride) +
                                              4 * static_cast<std::size_t>(c));
            if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
                values.push_back(static_cast<double>(std::bit_cast<float>(bits)));
            } else {
                values.push_back(static_cast<double>(bits));
            }
        }
    }
    return values;
}

void expect_accessor(const tinygltf::Model& model, int index, int component_type, int type, std::size_t count) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
    EXPECT_EQ(accessor.componentType, component_type) << "accessor " << index;
    EXPECT_EQ(accessor.type, type) << "accessor " << index;
    EXPECT_EQ(accessor.count, count) << "accessor " << index;
    EXPECT_FALSE(accessor.normalized) << "accessor " << index;
    EXPECT_FALSE(accessor.sparse.isSparse) << "accessor " << index;
}

/// The accessor's min and max are those of its data, exactly.
void expect_min_max(const tinygltf::Model& model, int index, const std::vector<double>& values, int components) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<std::size_t>(index));
    ASSERT_EQ(accessor.minValues.size(), static_cast<std::size_t>(components));
    ASSERT_EQ(accessor.maxValues.size(), static_cast<std::size_t>(components));
    for (int c = 0; c < components; ++c) {
        double lo = std::numeric_limits<double>::infinity();
        double hi = -lo;
        for (std::size_t i = static_cast<std::size_t>(c); i < values.size();
             i += static_cast<std::size_t>(components)) {
            lo = std::min(lo, values[i]);
            hi = std::max(hi, values[i]);
        }
        EXPECT_EQ(accessor.minValues[static_cast<std::size_t>(c)], lo) << "accessor " << index << " component " << c;
        EXPECT_EQ(accessor.maxValues[static_cast<std::size_t>(c)], hi) << "accessor " << index << " component " << c;
    }
}

/// Reads @p path with tinygltf and compares everything with @p s.
void expect_round_trip(const fs::path& path, const TriangleSurface& s, const std::string& scalar_attribute) {
    const tinygltf::Model model = load(path);
    const auto np = static_cast<std::size_t>(s.positions.rows());
    const auto nt = static_cast<std::size_t>(s.triangles.rows());

    EXPECT_EQ(model.asset.version, "2.0");
    EXPECT_EQ(model.asset.generator, "limsurf " + version());
    EXPECT_EQ(model.defaultScene, 0);
    ASSERT_EQ(model.scenes.size(), 1U);
    EXPECT_EQ(model.scenes[0].nodes, std::vector<int>{0});
    ASSERT_EQ(model.nodes.size(), 1U);
    EXPECT_EQ(model.nodes[0].mesh, 0);
    EXPECT_TRUE(model.nodes[0].matrix.empty() && model.nodes[0].rotation.empty() &&
                model.nodes[0].translation.empty() && model.nodes[0].scale.empty());
    ASSERT_EQ(model.meshes.size(), 1U);
    ASSERT_EQ(model.meshes[0].primitives.size(), 1U);
    const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
    EXPECT_TRUE(primitive.targets.empty());

    ASSERT_EQ(model.materials.size(), 1U);
    EXPECT_EQ(primitive.material, 0);
    const tinygltf::Material& material = model.materials[0];
    EXPECT_EQ(material.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1, 1, 1, 1}));
    EXPECT_EQ(material.pbrMetallicRoughness.metallicFactor, 0.0);
    EXPECT_TRUE(material.doubleSided);
    const bool translucent = s.colors.rows() > 0 && (s.colors.col(3).array() < 1.0F).any();
    EXPECT_EQ(material.alphaMode, translucent ? "BLEND" : "OPAQUE");

    // Exactly the attributes the surface has, under the names the specification fixes.
    std::set<std::string> expected_names{"POSITION"};
    if (s.normals.rows() > 0) {
        expected_names.insert("NORMAL");
    }
    if (s.colors.rows() > 0) {
        expected_names.insert("COLOR_0");
    }
    if (s.scalar.rows() > 0) {
        expected_names.insert(scalar_attribute);
    }
    std::set<std::string> names;
    for (const auto& [name, accessor] : primitive.attributes) {
        names.insert(name);
    }
    EXPECT_EQ(names, expected_names);

    // Buffer views: one buffer (the BIN chunk), 4-byte aligned, vertex data or indices.
    ASSERT_EQ(model.buffers.size(), 1U);
    EXPECT_TRUE(model.buffers[0].uri.empty());
    for (const tinygltf::BufferView& view : model.bufferViews) {
        EXPECT_EQ(view.buffer, 0);
        EXPECT_EQ(view.byteOffset % 4, 0U);
        EXPECT_EQ(view.byteStride, 0U);
        EXPECT_TRUE(view.target == TINYGLTF_TARGET_ARRAY_BUFFER || view.target == TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    }
    for (const auto& [name, accessor] : primitive.attributes) {
        const auto& view = model.bufferViews.at(static_cast<std::size_t>(model.accessors.at(accessor).bufferView));
        EXPECT_EQ(view.target, TINYGLTF_TARGET_ARRAY_BUFFER) << name;
    }

    // POSITION: the doubles rounded to float; min and max (required) exactly the data's.
    const int position = primitive.attributes.at("POSITION");
    expect_accessor(model, position, float_type, TINYGLTF_TYPE_VEC3, np);
    const std::vector<double> positions = accessor_values(model, position);
    ASSERT_EQ(positions.size(), 3 * np);
    for (std::size_t v = 0; v < np; ++v) {
        for (std::size_t c = 0; c < 3; ++c) {
            EXPECT_EQ(positions[3 * v + c], static_cast<double>(static_cast<float>(s.positions(
                                                static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(c)))))
                << "vertex " << v;
        }
    }
    expect_min_max(model, position, positions, 3);

    if (s.normals.rows() > 0) {
        const int normal = primitive.attributes.at("NORMAL");
        expect_accessor(model, normal, float_type, TINYGLTF_TYPE_VEC3, np);
        const std::vector<double> normals = accessor_values(model, normal);
        ASSERT_EQ(normals.size(), 3 * np);
        for (std::size_t v = 0; v < np; ++v) {
            const Eigen::Vector3d read(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
            const Eigen::Vector3d given = s.normals.row(static_cast<Eigen::Index>(v)).transpose();
            EXPECT_LE((read - given.normalized()).norm(), 2e-7) << "vertex " << v;
            EXPECT_LE(std::abs(read.norm() - 1.0), 2e-7) << "vertex " << v;  // unit, to float precision
        }
    }

    if (s.colors.rows() > 0) {
        const int color = primitive.attributes.at("COLOR_0");
        expect_accessor(model, color, float_type, TINYGLTF_TYPE_VEC4, np);
        const std::vector<double> colors = accessor_values(model, color);
        ASSERT_EQ(colors.size(), 4 * np);
        for (std::size_t v = 0; v < np; ++v) {
            for (std::size_t c = 0; c < 4; ++c) {
                const double given =
                    static_cast<double>(s.colors(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(c)));
                const double read = colors[4 * v + c];
                EXPECT_TRUE(read >= 0.0 && read <= 1.0);
                if (c == 3) {
                    EXPECT_EQ(read, given) << "vertex " << v << " alpha";
                } else {
                    EXPECT_NEAR(read, linear_from_srgb(given), 1e-7) << "vertex " << v << " component " << c;
                }
            }
        }
    }

    if (s.scalar.rows() > 0) {
        const int scalar = primitive.attributes.at(scalar_attribute);
        expect_accessor(model, scalar, float_type, TINYGLTF_TYPE_SCALAR, np);
        EXPECT_EQ(model.accessors.at(static_cast<std::size_t>(scalar)).name, s.scalar_name);
        const std::vector<double> values = accessor_values(model, scalar);
        ASSERT_EQ(values.size(), np);
        for (std::size_t v = 0; v < np; ++v) {
            EXPECT_EQ(values[v], static_cast<double>(static_cast<float>(s.scalar(static_cast<Eigen::Index>(v)))))
                << "vertex " << v;
        }
        expect_min_max(model, scalar, values, 1);
    }

    expect_accessor(model, primitive.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, 3 * nt);
    EXPECT_EQ(model.bufferViews.at(static_cast<std::size_t>(model.accessors.at(primitive.indices).bufferView)).target,
              TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    const std::vector<double> indices = accessor_values(model, primitive.indices);
    ASSERT_EQ(indices.size(), 3 * nt);
    for (std::size_t f = 0; f < nt; ++f) {
        for (std::size_t c = 0; c < 3; ++c) {
            EXPECT_EQ(indices[3 * f + c],
                      static_cast<double>(s.triangles(static_cast<Eigen::Index>(f), static_cast<Eigen::Index>(c))))
                << "triangle " << f;
        }
    }
}

/// The GLB container, byte by byte (glTF 2.0 §4.4): header, a JSON chunk padded with
/// spaces, a BIN chunk padded with zeros, nothing after it. Returns the JSON text.
std::string expect_container(const fs::path& path) {
    const std::string bytes = slurp(path);
    EXPECT_GE(bytes.size(), 28U);
    if (bytes.size() < 28) {
        return {};
    }
    EXPECT_EQ(bytes.substr(0, 4), "glTF");
    EXPECT_EQ(le_u32(bytes, 4), 2U);                                        // version
    EXPECT_EQ(le_u32(bytes, 8), static_cast<std::uint32_t>(bytes.size()));  // length: the whole file
    const std::uint32_t json_length = le_u32(bytes, 12);
    EXPECT_EQ(le_u32(bytes, 16), 0x4E4F534AU);  // "JSON"
    EXPECT_EQ(json_length % 4, 0U);
    EXPECT_LE(20U + json_length + 8U, bytes.size());
    const std::string json = bytes.substr(20, json_length);
    const std::size_t end = json.find_last_not_of(' ');
    EXPECT_NE(end, std::string::npos);
    EXPECT_EQ(json[end], '}');
    EXPECT_LT(json.size() - end - 1, 4U);  // padding: fewer than 4 spaces
    EXPECT_EQ(json.find_first_of("\r\n\t"), std::string::npos);
    const std::size_t bin = 20 + json_length;
    const std::uint32_t bin_length = le_u32(bytes, bin);
    EXPECT_EQ(le_u32(bytes, bin + 4), 0x004E4942U);  // "BIN\0"
    EXPECT_EQ(bin_length % 4, 0U);
    EXPECT_EQ(bin + 8 + bin_length, bytes.size());  // the BIN chunk ends the file
    EXPECT_EQ(bin % 4, 0U);
    return json.substr(0, end + 1);
}

TEST(Gltf, TetrahedronRoundTripsThroughTinygltf) {
    const fs::path dir = test::make_temp_dir("gltf");
    const fs::path path = dir / "tetrahedron.glb";
    const TriangleSurface s = tetrahedron();
    write_glb(path, s);
    expect_container(path);
    expect_round_trip(path, s, "_MEAN_CURVATURE");
    EXPECT_EQ(entries(dir), 1U);  // no temporary file left
    fs::remove_all(dir);
}

TEST(Gltf, GridRoundTripsThroughTinygltf) {
    const fs::path dir = test::make_temp_dir("gltf");
    const fs::path path = dir / "grid.glb";
    const TriangleSurface s = grid(12);  // 169 vertices, 288 triangles
    ASSERT_EQ(s.triangles.rows(), 288);
    write_glb(path, s);
    expect_container(path);
    expect_round_trip(path, s, "_K");
    fs::remove_all(dir);
}

TEST(Gltf, ContainerLengthsAndPaddingForEveryJsonLength) {
    // The name appears twice in the JSON (attribute and accessor name), a quote as '_' and as
    // '\"': these names add 2, 3, 4 and 5 bytes, so every amount of padding (0 to 3 spaces) occurs.
    const fs::path dir = test::make_temp_dir("gltf");
    std::set<std::size_t> residues;
    for (const auto& [name, attribute] :
         std::vector<std::pair<std::string, std::string>>{{"a", "_A"}, {"\"", "__"}, {"aa", "_AA"}, {"a\"", "_A_"}}) {
        TriangleSurface s = tetrahedron();
        s.scalar_name = name;
        const fs::path path = dir / (attribute + ".glb");
        write_glb(path, s);
        const std::string json = expect_container(path);
        residues.insert(json.size() % 4);
        EXPECT_NE(json.find("\"asset\":{\"version\":\"2.0\""), std::string::npos);
        expect_round_trip(path, s, attribute);
    }
    EXPECT_EQ(residues.size(), 4U);
    fs::remove_all(dir);
}

TEST(Gltf, OptionalAttributesAreLeftOut) {
    const fs::path dir = test::make_temp_dir("gltf");
    TriangleSurface s = tetrahedron();
    s.normals.resize(0, 3);
    s.colors.resize(0, 4);
    s.scalar.resize(0);
    s.scalar_name = "ignored without values";
    write_glb(dir / "bare.glb", s);
    expect_container(dir / "bare.glb");
    expect_round_trip(dir / "bare.glb", s, "");
    EXPECT_EQ(load(dir / "bare.glb").accessors.size(), 2U);  // POSITION and the indices

    // One translucent vertex makes the material blend.
    s = tetrahedron();
    s.colors(2, 3) = 0.5F;
    write_glb(dir / "translucent.glb", s);
    expect_round_trip(dir / "translucent.glb", s, "_MEAN_CURVATURE");
    fs::remove_all(dir);
}

TEST(Gltf, SrgbColoursBecomeLinear) {
    // glTF's COLOR_0 is linear: sRGB 0.5 is 0.21404114 (IEC 61966-2-1), black and white stay.
    const fs::path dir = test::make_temp_dir("gltf");
    TriangleSurface s = tetrahedron();
    s.colors << 0, 0.5F, 1, 0.25F, 0.04F, 0.2F, 0.8F, 1, 1, 1, 1, 1, 0, 0, 0, 0;
    write_glb(dir / "c.glb", s);
    const tinygltf::Model model = load(dir / "c.glb");
    const std::vector<double> c = accessor_values(model, model.meshes.at(0).primitives.at(0).attributes.at("COLOR_0"));
    ASSERT_EQ(c.size(), 16U);
    EXPECT_EQ(c[0], 0.0);
    EXPECT_NEAR(c[1], 0.21404114, 1e-7);
    EXPECT_EQ(c[2], 1.0);
    EXPECT_EQ(c[3], 0.25);                  // alpha as given
    EXPECT_NEAR(c[4], 0.04 / 12.92, 1e-8);  // the linear segment
    EXPECT_NEAR(c[5], 0.033104767, 1e-8);   // sRGB 0.2
    EXPECT_NEAR(c[6], 0.603827339, 1e-7);   // sRGB 0.8
    EXPECT_EQ(model.materials.at(0).alphaMode, "BLEND");
    fs::remove_all(dir);
}

TEST(Gltf, ScalarNamesAreSanitisedAndKeptAsAccessorNames) {
    const fs::path dir = test::make_temp_dir("gltf");
    struct Case {
        std::string name;
        std::string attribute;
        std::string accessor_name;
    };
    const std::vector<Case> cases{
        {"mean curvature", "_MEAN_CURVATURE", "mean curvature"},
        {"Gauss_K2", "_GAUSS_K2", "Gauss_K2"},
        {"\xce\xba-1", "____1", "\xce\xba-1"},         // κ-1: two UTF-8 bytes, then '-'
        {"a\"b\\c\nd", "_A_B_C_D", "a\"b\\c\nd"},      // JSON escapes in the accessor name
        {"bad\xff utf8", "_BAD__UTF8", "_BAD__UTF8"},  // not UTF-8: the attribute name instead
    };
    for (const Case& c : cases) {
        TriangleSurface s = tetrahedron();
        s.scalar_name = c.name;
        const fs::path path = dir / "s.glb";
        write_glb(path, s);
        const tinygltf::Model model = load(path);
        const auto& attributes = model.meshes.at(0).primitives.at(0).attributes;
        ASSERT_EQ(attributes.count(c.attribute), 1U) << c.attribute;
        EXPECT_EQ(model.accessors.at(static_cast<std::size_t>(attributes.at(c.attribute))).name, c.accessor_name);
    }
    fs::remove_all(dir);
}

TEST(Gltf, NearlyUnitNormalsAreRenormalised) {
    const fs::path dir = test::make_temp_dir("gltf");
    TriangleSurface s = tetrahedron();
    s.normals.row(0) << 0, 0, 1 + 9e-4;
    s.normals.row(1) << 0, 0.6 * (1 - 9e-4), 0.8 * (1 - 9e-4);
    write_glb(dir / "n.glb", s);
    const tinygltf::Model model = load(dir / "n.glb");
    const std::vector<double> n = accessor_values(model, model.meshes.at(0).primitives.at(0).attributes.at("NORMAL"));
    ASSERT_EQ(n.size(), 12U);
    EXPECT_EQ(n[0], 0.0);
    EXPECT_EQ(n[1], 0.0);
    EXPECT_EQ(n[2], 1.0);
    EXPECT_EQ(n[4], static_cast<double>(0.6F));
    EXPECT_EQ(n[5], static_cast<double>(0.8F));
    fs::remove_all(dir);
}

TEST(Gltf, ReplacesAnExistingFile) {
    const fs::path dir = test::make_temp_dir("gltf");
    const fs::path path = dir / "out.glb";
    { std::ofstream(path) << "old contents"; }
    write_glb(path, tetrahedron());
    expect_round_trip(path, tetrahedron(), "_MEAN_CURVATURE");
    EXPECT_EQ(entries(dir), 1U);
    fs::remove_all(dir);
}

/// The message write_glb throws for @p s, or "no error".
std::string glb_error(const fs::path& path, const TriangleSurface& s) {
    try {
        write_glb(path, s);
    } catch (const InputError& error) {
        EXPECT_FALSE(error.element().has_value());
        return error.what();
    }
    return "no error";
}

TEST(GltfErrors, BadSurfacesAreRefusedByNameAndCreateNothing) {
    const fs::path dir = test::make_temp_dir("gltf");
    const fs::path path = dir / "bad.glb";
    const std::string p = path.string() + ": ";
    struct Case {
        std::function<void(TriangleSurface&)> change;
        std::string message;
    };
    const std::vector<Case> cases{
        {[](TriangleSurface& s) { s.triangles(2, 1) = 4; }, "triangle 2: vertex index 4 out of range [0, 4)"},
        {[](TriangleSurface& s) { s.triangles(0, 0) = -1; }, "triangle 0: vertex index -1 out of range [0, 4)"},
        {[](TriangleSurface& s) { s.positions(1, 2) = nan; }, "vertex 1: position component 2 is not finite (nan)"},
        {[](TriangleSurface& s) { s.positions(3, 0) = -std::numeric_limits<double>::infinity(); },
         "vertex 3: position component 0 is not finite (-inf)"},
        {[](TriangleSurface& s) { s.positions(0, 1) = 1e39; },
         "vertex 0: position component 1 is 1e+39, beyond the range of a float (glTF stores 32-bit floats)"},
        {[](TriangleSurface& s) { s.normals.conservativeResize(3, 3); },
         "normals has 3 rows, expected 4 (one per position) or none"},
        {[](TriangleSurface& s) { s.colors.conservativeResize(5, 4); },
         "colors has 5 rows, expected 4 (one per position) or none"},
        {[](TriangleSurface& s) { s.scalar.conservativeResize(2); },
         "scalar has 2 rows, expected 4 (one per position) or none"},
        {[](TriangleSurface& s) { s.normals.row(3) << nan, 0, 1; }, "vertex 3: normal (nan, 0, 1) is not finite"},
        {[](TriangleSurface& s) { s.normals.row(0).setZero(); },
         "vertex 0: normal (0, 0, 0) has length 0, expected a unit vector (within 0.001)"},
        {[](TriangleSurface& s) { s.normals.row(1) << 0, 0, 1.5; },
         "vertex 1: normal (0, 0, 1.5) has length 1.5, expected a unit vector (within 0.001)"},
        {[](TriangleSurface& s) { s.colors(2, 1) = 1.5F; },
         "vertex 2: colour component 1 is 1.5, expected a value in [0, 1]"},
        {[](TriangleSurface& s) { s.colors(0, 3) = -0.25F; },
         "vertex 0: colour component 3 is -0.25, expected a value in [0, 1]"},
        {[](TriangleSurface& s) { s.colors(1, 0) = std::numeric_limits<float>::quiet_NaN(); },
         "vertex 1: colour component 0 is nan, expected a value in [0, 1]"},
        {[](TriangleSurface& s) { s.scalar(1) = nan; }, "vertex 1: scalar 'mean curvature' is not finite (nan)"},
        {[](TriangleSurface& s) { s.scalar(2) = -1e300; },
         "vertex 2: scalar 'mean curvature' is -1e+300, beyond the range of a float (glTF stores 32-bit floats)"},
        {[](TriangleSurface& s) { s.scalar_name.clear(); }, "the scalar has no name (scalar_name names its attribute)"},
        {[](TriangleSurface& s) { s.triangles.resize(0, 3); }, "no triangles (a glTF mesh needs at least one)"},
        {[](TriangleSurface& s) { s.positions.resize(0, 3); },
         "no positions (a glTF mesh needs at least one triangle)"},
    };
    for (const Case& c : cases) {
        TriangleSurface s = tetrahedron();
        c.change(s);
        EXPECT_EQ(glb_error(path, s), p + c.message);
    }
    EXPECT_EQ(entries(dir), 0U);  // nothing written, no temporary file left

    // An existing file is left as it was.
    { std::ofstream(path) << "old contents"; }
    TriangleSurface s = tetrahedron();
    s.triangles(0, 0) = 7;
    EXPECT_THROW(write_glb(path, s), InputError);
    EXPECT_EQ(slurp(path), "old contents");
    EXPECT_EQ(entries(dir), 1U);
    fs::remove_all(dir);
}

TEST(GltfErrors, UnwritablePathsAreNamed) {
    const fs::path dir = test::make_temp_dir("gltf");
    const fs::path missing = dir / "no" / "such" / "dir" / "out.glb";
    const std::string message = glb_error(missing, tetrahedron());
    EXPECT_EQ(message.rfind(missing.string() + ": ", 0), 0U) << message;
    EXPECT_EQ(glb_error(dir, tetrahedron()), dir.string() + ": cannot write: is a directory");
    EXPECT_EQ(entries(dir), 0U);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace limsurf
