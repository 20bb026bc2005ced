#include "limsurf/mesh/control_mesh.h"

#include <cstddef>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/detail/huge_pages.h"

namespace limsurf {
namespace {

using std::size_t;

size_t at(Index i) {
    return static_cast<size_t>(i);
}

void check_positions(const Topology& topology, const Points& positions) {
    LIMSURF_CHECK(positions.rows() == topology.num_vertices(), InputError, "positions have ", positions.rows(),
                  " rows but the topology has ", topology.num_vertices(), " vertices");
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK(positions.row(v).allFinite(), InputError, "vertex ", v, " has a non-finite coordinate (",
                      positions(v, 0), ", ", positions(v, 1), ", ", positions(v, 2), ")");
    }
}

/// Old -> new vertex numbers with unused vertices removed (invalid_index for those).
std::vector<Index> compact_vertices(const PolygonSoup& soup, std::vector<Index>& kept) {
    std::vector<std::uint8_t> used(at(soup.num_vertices()), 0);
    for (const Index v : soup.face_vertices) {
        used[at(v)] = 1;
    }
    std::vector<Index> renumber(at(soup.num_vertices()), invalid_index);
    for (Index v = 0; v < soup.num_vertices(); ++v) {
        if (used[at(v)] != 0) {
            renumber[at(v)] = static_cast<Index>(kept.size());
            kept.push_back(v);
        }
    }
    return renumber;
}

}  // namespace

ControlMesh::ControlMesh(Topology topology, Points positions, SchemeHints hints)
    : topology_(std::move(topology)), positions_(std::move(positions)), hints_(hints) {
    check_positions(topology_, positions_);
}

ControlMesh ControlMesh::with_positions(Points positions) const {
    return ControlMesh(topology_, std::move(positions), hints_);
}

BuildResult build_control_mesh(const PolygonSoup& soup, const BuildOptions& options) {
    ValidationReport report = validate(soup, options.validation);
    for (Issue& issue : report.issues) {
        if (issue.problem != Problem::IsolatedVertex) {
            continue;
        }
        if (options.isolated_vertices == IsolatedVertices::Error) {
            issue.severity = Severity::Error;
        } else {
            issue.message += "; dropped";
        }
    }
    report.throw_if_errors();
    soup.groups.check(soup.num_faces());

    BuildResult result;
    const std::vector<Index> renumber = compact_vertices(soup, result.source_vertex);
    std::vector<Index> corners(soup.face_vertices.size());
    for (size_t c = 0; c < corners.size(); ++c) {
        corners[c] = renumber[at(soup.face_vertices[c])];
    }
    SharpnessTags sharpness = soup.sharpness;
    for (CreaseTag& crease : sharpness.creases) {
        crease.v0 = renumber[at(crease.v0)];
        crease.v1 = renumber[at(crease.v1)];
    }
    std::erase_if(sharpness.corners,
                  [&](const CornerTag& corner) { return renumber[at(corner.vertex)] == invalid_index; });
    for (CornerTag& corner : sharpness.corners) {
        corner.vertex = renumber[at(corner.vertex)];
    }
    Points positions(static_cast<Eigen::Index>(result.source_vertex.size()), 3);
    for (size_t v = 0; v < result.source_vertex.size(); ++v) {
        positions.row(static_cast<Eigen::Index>(v)) = soup.positions.row(result.source_vertex[v]);
    }
    Topology topology(static_cast<Index>(result.source_vertex.size()), soup.face_offsets, corners, sharpness);
    result.mesh = ControlMesh(std::move(topology), std::move(positions), soup.hints);
    result.report = std::move(report);
    result.source.file = soup.source.file;
    result.source.face_lines = soup.source.face_lines;
    result.groups = soup.groups;  // faces keep their numbers
    result.groups.current = -1;
    if (!soup.source.vertex_lines.empty()) {
        for (const Index v : result.source_vertex) {
            result.source.vertex_lines.push_back(soup.source.vertex_lines[at(v)]);
        }
    }
    return result;
}

PolygonSoup to_polygon_soup(const ControlMesh& mesh) {
    const Topology& topology = mesh.topology();
    PolygonSoup soup;
    // Copies of up to a few hundred MB before writing a refined mesh: into memory advised for huge
    // pages, whose first touch is what the copy costs (detail/huge_pages.h).
    soup.positions.resize(mesh.positions().rows(), 3);
    detail::advise_huge_pages(soup.positions.data(), sizeof(double) * static_cast<std::size_t>(soup.positions.size()));
    soup.positions = mesh.positions();
    write_faces(topology, soup);
    soup.hints = mesh.hints();
    return soup;
}

void write_faces(const Topology& topology, PolygonSoup& soup) {
    detail::reserve_huge(soup.face_offsets, topology.face_offsets().size());
    soup.face_offsets.assign(topology.face_offsets().begin(), topology.face_offsets().end());
    detail::reserve_huge(soup.face_vertices, topology.all_face_vertices().size());
    soup.face_vertices.assign(topology.all_face_vertices().begin(), topology.all_face_vertices().end());
    soup.sharpness = topology.sharpness_tags();
}

}  // namespace limsurf
