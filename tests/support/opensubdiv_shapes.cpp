#include "support/opensubdiv_shapes.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "support/paths.h"

namespace limsurf::test {
namespace {

/// Why limsurf refuses a shape: the fragment of its reader's message. OpenSubdiv accepts all of
/// them; limsurf's model is an oriented 2-manifold (docs/conventions.md) and hierarchical edits
/// change the surface after refinement (docs/io.md), so both stay refused.
const std::map<std::string, std::string>& refusals() {
    static const std::map<std::string, std::string> table = {
        // an edge shared by more than two faces
        {"catmark_fan", "non-manifold"},
        {"catmark_nonman_edge100", "non-manifold"},
        {"catmark_val2_nonman", "non-manifold"},
        {"loop_nonman_edge100", "non-manifold"},
        {"loop_val2_interior", "non-manifold"},
        // faces meeting only at a vertex
        {"catmark_gregory_test4", "bow-tie"},
        {"catmark_nonman_verts", "bow-tie"},
        {"loop_nonman_verts", "bow-tie"},
        // a face that visits a vertex twice
        {"catmark_nonman_edges", "repeats vertex"},
        {"catmark_nonman_quadpole360", "repeats vertex"},
        {"catmark_nonman_quadpole64", "repeats vertex"},
        {"catmark_nonman_quadpole8", "repeats vertex"},
        {"loop_nonman_edges", "repeats vertex"},
        // hierarchical edits
        {"catmark_square_hedit0", "hierarchical edit"},
        {"catmark_square_hedit1", "hierarchical edit"},
        {"catmark_square_hedit2", "hierarchical edit"},
        {"catmark_square_hedit3", "hierarchical edit"},
        {"catmark_square_hedit4", "hierarchical edit"},
    };
    return table;
}

SchemeKind scheme_of(const std::string& name) {
    if (name.rfind("catmark_", 0) == 0) {
        return SchemeKind::CatmullClark;
    }
    if (name.rfind("loop_", 0) == 0) {
        return SchemeKind::Loop;
    }
    if (name.rfind("bilinear_", 0) == 0) {
        return SchemeKind::Bilinear;
    }
    throw std::runtime_error("opensubdiv shape '" + name + "': unknown scheme prefix");
}

[[noreturn]] void fail(const std::filesystem::path& path, int line, const std::string& what) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line) + ": " + what);
}

/// `t name nints/nfloats/nstrings ints... floats... strings...`
void read_tag(std::istringstream& in, const std::filesystem::path& path, int line, OpenSubdivShapeFile& shape) {
    std::string name, counts;
    in >> name >> counts;
    int ni = 0, nf = 0, ns = 0;
    char slash1 = 0, slash2 = 0;
    std::istringstream c(counts);
    if (!(c >> ni >> slash1 >> nf >> slash2 >> ns) || slash1 != '/' || slash2 != '/') {
        fail(path, line, "bad tag counts '" + counts + "'");
    }
    std::vector<Index> ints(static_cast<std::size_t>(ni));
    std::vector<double> floats(static_cast<std::size_t>(nf));
    std::vector<std::string> strings(static_cast<std::size_t>(ns));
    for (auto& i : ints) {
        in >> i;
    }
    for (auto& f : floats) {
        in >> f;
    }
    for (auto& s : strings) {
        in >> s;
    }
    if (!in) {
        fail(path, line, "tag '" + name + "' has fewer arguments than its counts say");
    }
    const auto value = [&](std::size_t k) { return floats.size() > 1 ? floats.at(k) : floats.at(0); };
    if (name == "crease") {
        for (std::size_t k = 0; 2 * k + 1 < ints.size(); ++k) {
            shape.creases.push_back({ints[2 * k], ints[2 * k + 1], value(k)});
        }
    } else if (name == "corner") {
        for (std::size_t k = 0; k < ints.size(); ++k) {
            shape.corners.emplace_back(ints[k], value(k));
        }
    } else if (name == "hole") {
        shape.holes.insert(shape.holes.end(), ints.begin(), ints.end());
    } else if (name == "interpolateboundary") {
        const BoundaryInterpolation rules[] = {BoundaryInterpolation::None, BoundaryInterpolation::EdgeAndCorner,
                                               BoundaryInterpolation::EdgeOnly};
        shape.hints.boundary = rules[ints.at(0)];
    } else if (name == "creasemethod") {
        shape.hints.creasing = strings.at(0) == "chaikin" ? CreasingMethod::Chaikin : CreasingMethod::Uniform;
    } else if (name == "smoothtriangles") {
        shape.hints.triangles =
            strings.at(0) == "smooth" ? TriangleSubdivision::Smooth : TriangleSubdivision::CatmullClark;
    }
    // face-varying tags and hierarchical edits carry nothing the vertex surface needs here
}

}  // namespace

std::vector<OpenSubdivShape> opensubdiv_shapes() {
    std::vector<OpenSubdivShape> shapes;
    for (const auto& entry : std::filesystem::directory_iterator(test_data_dir() / "opensubdiv_shapes")) {
        if (entry.path().extension() != ".obj") {
            continue;
        }
        const std::string name = entry.path().stem().string();
        const auto refused = refusals().find(name);
        shapes.push_back({name, entry.path(), scheme_of(name), refused == refusals().end() ? "" : refused->second});
    }
    std::sort(shapes.begin(), shapes.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    return shapes;
}

OpenSubdivShapeFile read_opensubdiv_shape(const std::filesystem::path& path) {
    std::ifstream file(path);
    if (!file) {
        throw std::runtime_error(path.string() + ": cannot open");
    }
    OpenSubdivShapeFile shape;
    std::string text;
    for (int line = 1; std::getline(file, text); ++line) {
        std::istringstream in(text);
        std::string key;
        in >> key;
        if (key == "v") {
            std::array<double, 3> p{};
            if (!(in >> p[0] >> p[1] >> p[2])) {
                fail(path, line, "bad vertex");
            }
            shape.positions.push_back(p);
        } else if (key == "f") {
            std::vector<Index> face;
            for (std::string corner; in >> corner;) {
                face.push_back(std::stoi(corner.substr(0, corner.find('/'))) - 1);
            }
            shape.faces.push_back(std::move(face));
        } else if (key == "t") {
            read_tag(in, path, line, shape);
        }
    }
    return shape;
}

Topology with_float_sharpness(const Topology& t) {
    SharpnessTags tags;
    for (Index e = 0; e < t.num_edges(); ++e) {
        if (t.edge_sharpness(e) > 0.0) {
            const auto ends = t.edge_vertices(e);
            tags.creases.push_back({ends[0], ends[1], static_cast<float>(t.edge_sharpness(e)), 0});
        }
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (t.vertex_sharpness(v) > 0.0) {
            tags.corners.push_back({v, static_cast<float>(t.vertex_sharpness(v)), 0});
        }
    }
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (t.is_hole(f)) {
            tags.holes.push_back({f, 0});
        }
    }
    return Topology(t.num_vertices(), t.face_offsets(), t.all_face_vertices(), tags);
}

}  // namespace limsurf::test
