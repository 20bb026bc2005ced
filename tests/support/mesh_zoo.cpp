#include "support/mesh_zoo.h"

#include <algorithm>
#include <charconv>
#include <cstddef>
#include <fstream>
#include <functional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "limsurf/io/mesh_io.h"
#include "support/paths.h"

namespace limsurf::test {

namespace {

constexpr std::string_view kExpectedHeader = "name,file,num_vertices,num_edges,num_faces,euler_characteristic,genus,"
                                             "num_boundary_loops,num_components,closed,triangles_only,quads_only,"
                                             "extraordinary_valences,description";
constexpr std::size_t kNumFields = 14;

[[noreturn]] void fail(const std::filesystem::path& csv, int line, const std::string& what) {
    throw std::runtime_error(csv.string() + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string_view> split_fields(std::string_view line) {
    // The description is the last field and may not contain commas (the
    // generator refuses them), but take the rest of the line to be safe.
    std::vector<std::string_view> fields;
    while (fields.size() + 1 < kNumFields) {
        const auto comma = line.find(',');
        if (comma == std::string_view::npos) {
            break;
        }
        fields.push_back(line.substr(0, comma));
        line.remove_prefix(comma + 1);
    }
    fields.push_back(line);
    return fields;
}

int parse_int(std::string_view text, const std::filesystem::path& csv, int line) {
    int value = 0;
    const auto* const end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc{} || ptr != end || text.empty()) {
        fail(csv, line, "not an integer: '" + std::string(text) + "'");
    }
    return value;
}

bool parse_bool(std::string_view text, const std::filesystem::path& csv, int line) {
    if (text == "1" || text == "true") {
        return true;
    }
    if (text == "0" || text == "false") {
        return false;
    }
    fail(csv, line, "not a boolean: '" + std::string(text) + "'");
}

std::vector<int> parse_int_list(std::string_view text, const std::filesystem::path& csv, int line) {
    std::vector<int> values;
    while (!text.empty()) {
        const auto space = text.find(' ');
        const auto token = text.substr(0, space);
        if (!token.empty()) {
            values.push_back(parse_int(token, csv, line));
        }
        if (space == std::string_view::npos) {
            break;
        }
        text.remove_prefix(space + 1);
    }
    return values;
}

std::vector<BundledMesh> load_bundled_meshes() {
    const auto csv = test_data_dir() / "bundled_meshes.csv";
    std::ifstream in(csv);
    if (!in) {
        throw std::runtime_error("cannot open " + csv.string());
    }
    std::vector<BundledMesh> meshes;
    std::string line;
    int line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        if (line_number == 1) {
            if (line != kExpectedHeader) {
                fail(csv, line_number, "unexpected header '" + line + "'");
            }
            continue;
        }
        if (line.empty()) {
            continue;
        }
        const auto fields = split_fields(line);
        if (fields.size() != kNumFields) {
            fail(csv, line_number,
                 "expected " + std::to_string(kNumFields) + " fields, got " + std::to_string(fields.size()));
        }
        BundledMesh mesh;
        mesh.name = std::string(fields[0]);
        mesh.path = mesh_dir() / std::string(fields[1]);
        mesh.num_vertices = parse_int(fields[2], csv, line_number);
        mesh.num_edges = parse_int(fields[3], csv, line_number);
        mesh.num_faces = parse_int(fields[4], csv, line_number);
        mesh.euler_characteristic = parse_int(fields[5], csv, line_number);
        mesh.genus = parse_int(fields[6], csv, line_number);
        mesh.num_boundary_loops = parse_int(fields[7], csv, line_number);
        mesh.num_components = parse_int(fields[8], csv, line_number);
        mesh.closed = parse_bool(fields[9], csv, line_number);
        mesh.triangles_only = parse_bool(fields[10], csv, line_number);
        mesh.quads_only = parse_bool(fields[11], csv, line_number);
        mesh.extraordinary_valences = parse_int_list(fields[12], csv, line_number);
        mesh.description = std::string(fields[13]);
        if (mesh.name.empty()) {
            fail(csv, line_number, "empty mesh name");
        }
        meshes.push_back(std::move(mesh));
    }
    if (meshes.empty()) {
        throw std::runtime_error(csv.string() + ": no meshes listed");
    }
    return meshes;
}

std::vector<BundledMesh> select(const std::function<bool(const BundledMesh&)>& keep) {
    std::vector<BundledMesh> result;
    for (const auto& mesh : bundled_meshes()) {
        if (keep(mesh)) {
            result.push_back(mesh);
        }
    }
    return result;
}

}  // namespace

const std::vector<BundledMesh>& bundled_meshes() {
    static const std::vector<BundledMesh> meshes = load_bundled_meshes();
    return meshes;
}

std::vector<BundledMesh> closed_meshes() {
    return select([](const BundledMesh& mesh) { return mesh.closed; });
}

std::vector<BundledMesh> meshes_with_boundary() {
    return select([](const BundledMesh& mesh) { return mesh.num_boundary_loops > 0; });
}

std::vector<BundledMesh> triangle_meshes() {
    return select([](const BundledMesh& mesh) { return mesh.triangles_only; });
}

std::vector<BundledMesh> quad_meshes() {
    return select([](const BundledMesh& mesh) { return mesh.quads_only; });
}

const BundledMesh& find_bundled(std::string_view name) {
    const auto& meshes = bundled_meshes();
    const auto it =
        std::find_if(meshes.begin(), meshes.end(), [name](const BundledMesh& mesh) { return mesh.name == name; });
    if (it == meshes.end()) {
        throw std::runtime_error("no bundled mesh named '" + std::string(name) + "'");
    }
    return *it;
}

FinestLevel refined_bundled(std::string_view name, SchemeKind scheme, int levels) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = levels;
    return refine_finest(built.mesh.topology(), built.mesh.positions(), refine);
}

void PrintTo(const BundledMesh& mesh, std::ostream* os) {
    *os << mesh.name;
}

std::vector<SchemeCase> form_subdivision_cases() {
    std::vector<SchemeCase> out;
    for (const auto& mesh : triangle_meshes()) {
        out.push_back({mesh.name, SchemeKind::Loop});
    }
    for (const auto& mesh : quad_meshes()) {
        // Form subdivision has no crease rules (the SEC paper leaves them to future work).
        if (!read_mesh(mesh.path).mesh.topology().has_sharpness()) {
            out.push_back({mesh.name, SchemeKind::CatmullClark});
        }
    }
    return out;
}

}  // namespace limsurf::test
