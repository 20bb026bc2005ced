#include "limsurf/mesh/topology.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/detail/connectivity.h"
#include "limsurf/detail/huge_pages.h"
#include "limsurf/mesh/validate.h"

namespace limsurf {
namespace {

using std::size_t;

size_t at(Index i) {
    return static_cast<size_t>(i);
}

/// Throws when the connectivity check found errors; isolated vertices count
/// as errors here because a Topology has none (build_control_mesh drops them).
void throw_if_unusable(const ValidationReport& report) {
    ValidationReport fatal;
    for (const Issue& issue : report.issues) {
        if (issue.severity == Severity::Error) {
            fatal.issues.push_back(issue);
        } else if (issue.problem == Problem::IsolatedVertex) {
            fatal.issues.push_back({issue.problem, Severity::Error, issue.location,
                                    issue.message + "; a Topology cannot hold isolated vertices"});
        }
    }
    if (fatal.has_errors() && fatal.issues.front().problem == Problem::IsolatedVertex) {
        throw TopologyError(fatal.summary());
    }
    fatal.throw_if_errors();
}

/// Component roots with path halving.
Index find_root(detail::HugeTable<Index>& parent, Index x) {
    while (parent[at(x)] != x) {
        parent[at(x)] = parent[at(parent[at(x)])];
        x = parent[at(x)];
    }
    return x;
}

}  // namespace

Topology::Topology(Index num_vertices, std::span<const Index> face_offsets, std::span<const Index> face_vertices,
                   const SharpnessTags& sharpness)
    : num_vertices_(num_vertices) {
    copy_face_list(face_offsets, face_vertices);
    const detail::FaceListView faces{num_vertices, face_offsets, face_vertices};
    ValidationReport report;
    detail::HalfEdges half_edges;
    // Bow-tie vertices are found by the one-ring walk, which needs manifold, consistently oriented
    // edges (checked here); the report for them comes from the full check, as validate() writes it.
    detail::check_connectivity(faces, sharpness, SourceMap{}, report, &half_edges, detail::VertexFans::LeftToTheCaller);
    throw_if_unusable(report);
    if (!build(half_edges, sharpness)) {
        ValidationReport full;
        detail::check_connectivity(faces, sharpness, SourceMap{}, full);
        throw_if_unusable(full);
        throw std::logic_error("limsurf bug: a one-ring walk ended early but no vertex is non-manifold");
    }
}

Topology::Topology(Trusted, Index num_vertices, std::span<const Index> face_offsets,
                   std::span<const Index> face_vertices, const SharpnessTags& sharpness)
    : num_vertices_(num_vertices) {
    copy_face_list(face_offsets, face_vertices);
#ifndef NDEBUG
    // Debug and sanitizer builds still check what refinement produced.
    ValidationReport report;
    detail::check_connectivity({num_vertices, face_offsets, face_vertices}, sharpness, SourceMap{}, report);
    LIMSURF_ASSERT(!report.has_errors(), "refinement produced an invalid topology: ", report.summary());
#endif
    [[maybe_unused]] const bool manifold =
        build(detail::sorted_half_edges_unchecked({num_vertices, face_offsets, face_vertices}), sharpness);
    LIMSURF_ASSERT(manifold, "refinement produced a non-manifold vertex");
}

void Topology::copy_face_list(std::span<const Index> face_offsets, std::span<const Index> face_vertices) {
    detail::reserve_huge(face_offsets_, face_offsets.size());
    face_offsets_.assign(face_offsets.begin(), face_offsets.end());
    detail::reserve_huge(face_vertices_, face_vertices.size());
    face_vertices_.assign(face_vertices.begin(), face_vertices.end());
}

bool Topology::build(std::span<const detail::HalfEdge> half_edges, const SharpnessTags& sharpness) {
    const detail::HugeTable<Index> edge_face_corners = build_edges(half_edges);
    if (!build_one_rings(edge_face_corners)) {
        return false;
    }
    build_boundary_loops();
    build_components();
    apply_sharpness(sharpness);
    return true;
}

namespace detail {

Topology refined_topology(Index num_vertices, std::span<const Index> face_offsets, std::span<const Index> face_vertices,
                          const SharpnessTags& sharpness) {
    return Topology(Topology::Trusted{}, num_vertices, face_offsets, face_vertices, sharpness);
}

}  // namespace detail

Topology Topology::from_polygons(Index num_vertices, const std::vector<std::vector<Index>>& faces,
                                 const SharpnessTags& sharpness) {
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    for (const auto& face : faces) {
        corners.insert(corners.end(), face.begin(), face.end());
        offsets.push_back(static_cast<Index>(corners.size()));
    }
    return Topology(num_vertices, offsets, corners, sharpness);
}

detail::HugeTable<Index> Topology::build_edges(std::span<const detail::HalfEdge> half_edges) {
    // half_edges is sorted by (edge key, face): each run of equal keys is one edge (a group). Each
    // corner's group goes into face_edges_ first, and is replaced by its edge below (no table of
    // its own: a million quads have 4M corners).
    detail::assign_huge(face_edges_, face_vertices_.size());
    Index num_groups = 0;
    for (size_t i = 0; i < half_edges.size(); ++i) {
        num_groups += i == 0 || half_edges[i].key != half_edges[i - 1].key ? 1 : 0;
        face_edges_[at(half_edges[i].corner)] = num_groups - 1;
    }

    // Edges numbered in order of first appearance in the face list (locality, like Vtr), in one pass
    // over the corners; then each edge's faces (at most two: validated) in a second pass.
    detail::HugeTable<Index> edge_of_group;
    detail::assign_huge(edge_of_group, at(num_groups), invalid_index);
    detail::assign_huge(edge_vertices_, 2 * at(num_groups));
    Index num_numbered = 0;
    for (Index f = 0; f < num_faces(); ++f) {
        const Index first = face_offsets_[at(f)];
        const Index last = face_offsets_[at(f) + 1] - 1;
        for (Index c = first; c <= last; ++c) {
            const Index a = face_vertices_[at(c)];
            const Index b = face_vertices_[at(c == last ? first : c + 1)];
            Index& e = edge_of_group[at(face_edges_[at(c)])];
            if (e == invalid_index) {
                e = num_numbered++;
                edge_vertices_[2 * at(e)] = std::min(a, b);
                edge_vertices_[2 * at(e) + 1] = std::max(a, b);
            }
            face_edges_[at(c)] = e;
        }
    }
    detail::HugeTable<Index> edge_face_corners;
    fill_edge_faces(&edge_face_corners);
    return edge_face_corners;
}

void Topology::fill_edge_faces(detail::HugeTable<Index>* edge_face_corners) {
    detail::assign_huge(edge_faces_, 2 * at(num_edges()), invalid_index);
    if (edge_face_corners != nullptr) {
        // parallel to edge_faces_: where each face enters the edge
        detail::assign_huge(*edge_face_corners, edge_faces_.size(), invalid_index);
    }
    // Each edge lists the face traversing it lower -> higher first, then the other; a boundary edge
    // its only face. A face running it higher -> lower takes the first slot while it is free and
    // gives it up when the other face comes (consistent orientation: one of each, validated).
    const auto place = [&](Index slot, Index f, Index c) {
        edge_faces_[at(slot)] = f;
        if (edge_face_corners != nullptr) {
            (*edge_face_corners)[at(slot)] = c;
        }
    };
    for (Index f = 0; f < num_faces(); ++f) {
        for (Index c = face_offsets_[at(f)]; c < face_offsets_[at(f) + 1]; ++c) {
            const Index slot = 2 * face_edges_[at(c)];
            const bool first_free = edge_faces_[at(slot)] == invalid_index;
            if (corner_sign(f, c) < 0) {
                place(first_free ? slot : slot + 1, f, c);
                continue;
            }
            if (!first_free) {
                place(slot + 1, edge_faces_[at(slot)],
                      edge_face_corners != nullptr ? (*edge_face_corners)[at(slot)] : invalid_index);
            }
            place(slot, f, c);
        }
    }
}

void Topology::allocate_one_rings() {
    std::partial_sum(vertex_face_offsets_.begin(), vertex_face_offsets_.end(), vertex_face_offsets_.begin());
    detail::HugeTable<Index>().swap(vertex_edge_offsets_);  // without boundary: vertex_face_offsets_
    if (std::find(vertex_is_boundary_.begin(), vertex_is_boundary_.end(), 1) != vertex_is_boundary_.end()) {
        detail::assign_huge(vertex_edge_offsets_, at(num_vertices_) + 1, 0);
        for (Index v = 0; v < num_vertices_; ++v) {
            vertex_edge_offsets_[at(v) + 1] = vertex_edge_offsets_[at(v)] + vertex_face_offsets_[at(v) + 1] -
                                              vertex_face_offsets_[at(v)] + vertex_is_boundary_[at(v)];
        }
    }
    detail::assign_huge(vertex_faces_, at(vertex_face_offsets_.back()));
    detail::assign_huge(vertex_face_corners_, at(vertex_face_offsets_.back()));
    large_corners_.clear();
    detail::assign_huge(vertex_edges_, at(vertex_edge_offset(num_vertices_)));
}

Index Topology::find_edge(Index a, Index b) const {
    if (a < 0 || b < 0 || a >= num_vertices_ || b >= num_vertices_) {
        return invalid_index;
    }
    for (const Index e : vertex_edges(a)) {
        if (other_vertex(e, a) == b) {
            return e;
        }
    }
    return invalid_index;
}

bool Topology::build_one_rings(const detail::HugeTable<Index>& edge_face_corners) {
    // Per vertex: its number of corners, and the corner its walk starts at — the first corner in
    // face order, or for a boundary vertex the corner whose outgoing edge is its (single, the
    // vertex is manifold) outgoing boundary edge. No per-vertex corner lists are needed.
    detail::assign_huge(vertex_face_offsets_, at(num_vertices_) + 1, 0);
    detail::HugeTable<Index> start;
    detail::assign_huge(start, at(num_vertices_), invalid_index);
    for (size_t c = 0; c < face_vertices_.size(); ++c) {
        const auto v = at(face_vertices_[c]);
        ++vertex_face_offsets_[v + 1];
        start[v] = start[v] == invalid_index ? static_cast<Index>(c) : start[v];
    }
    vertex_is_boundary_.assign(at(num_vertices_), 0);
    for (Index e = 0; e < num_edges(); ++e) {
        if (edge_face_count(e) == 1) {
            const Index c = edge_face_corners[2 * at(e)];
            start[at(face_vertices_[at(c)])] = c;
            vertex_is_boundary_[at(face_vertices_[at(c)])] = 1;
        }
    }

    // Each vertex's slots are known before the walks (its corners; its edges, one more on the
    // boundary), so the vertices are walked in order of their first corner in the face list: the
    // faces and edges a walk visits were numbered near each other, and memory is read nearly in order.
    allocate_one_rings();
    const detail::HugeTable<Index>& offsets = vertex_face_offsets_;
    std::vector<std::uint8_t> walked(at(num_vertices_), 0);
    bool every_walk_complete = true;

    // The walk, for a way of finding a corner's face: arithmetic when all faces have one degree
    // (every refined level of Catmull–Clark and Loop), a table otherwise.
    const auto walk = [&](const auto& face_of) {
        for (size_t c = 0; c < face_vertices_.size(); ++c) {
            const Index v = face_vertices_[c];
            if (walked[at(v)] != 0) {
                continue;
            }
            walked[at(v)] = 1;
            const Index count = offsets[at(v) + 1] - offsets[at(v)];
            Index face_slot = offsets[at(v)];
            Index edge_slot = vertex_edge_offset(v);
            Index corner = start[at(v)];
            for (Index step = 0; step < count; ++step) {
                const Index f = face_of(corner);
                const Index first = face_offsets_[at(f)];
                vertex_faces_[at(face_slot)] = f;
                set_vertex_face_corner(at(face_slot++), corner - first);
                vertex_edges_[at(edge_slot++)] = face_edges_[at(corner)];
                // Counter-clockwise, the next face shares this face's incoming edge (from the previous corner).
                const Index previous = corner == first ? face_offsets_[at(f) + 1] - 1 : corner - 1;
                const Index in = face_edges_[at(previous)];
                const Index across = 2 * in;
                if (edge_face_count(in) == 1) {
                    vertex_edges_[at(edge_slot++)] = in;  // closing boundary edge
                    break;
                }
                // The other face runs that edge from v: its half-edge there starts at its corner at v
                // (looked up, not searched: a face of 10⁵ corners must not make the walk quadratic).
                const Index other = edge_faces_[at(across)] == f ? 1 : 0;
                corner = edge_face_corners[at(across + other)];
                if (corner == start[at(v)]) {
                    break;  // round the fan: the last step, unless another fan meets here
                }
            }
            // A walk round one fan ends at a boundary edge or back at its start: short of the vertex's
            // corners, some other fan meets this one only at the vertex (a bow-tie).
            if (face_slot != offsets[at(v) + 1] || edge_slot != vertex_edge_offset(v + 1)) {
                every_walk_complete = false;
                return;
            }
        }
    };
    if (all_faces_have_degree(4)) {
        walk([](Index corner) { return corner / 4; });
    } else if (all_faces_have_degree(3)) {
        walk([](Index corner) { return corner / 3; });
    } else {
        std::vector<Index> corner_face(face_vertices_.size());
        for (Index f = 0; f < num_faces(); ++f) {
            std::fill(corner_face.begin() + face_offsets_[at(f)], corner_face.begin() + face_offsets_[at(f) + 1], f);
        }
        walk([&](Index corner) { return corner_face[at(corner)]; });
    }
    sort_large_corners();
    return every_walk_complete;
}

Index VertexFaceCorners::large(std::size_t slot) const {
    const auto found = std::lower_bound(large_corners_.begin(), large_corners_.end(), static_cast<Index>(slot),
                                        [](const std::pair<Index, Index>& entry, Index s) { return entry.first < s; });
    LIMSURF_ASSERT(found != large_corners_.end() && found->first == static_cast<Index>(slot),
                   "no large corner at one-ring slot ", slot);
    return found->second;
}

void Topology::sort_large_corners() {
    std::sort(large_corners_.begin(), large_corners_.end());
}

std::span<const Index> Topology::vertex_faces(Index v) const {
    const auto begin = at(vertex_face_offsets_[at(v)]);
    return std::span<const Index>(vertex_faces_).subspan(begin, at(vertex_face_offsets_[at(v) + 1]) - begin);
}

std::span<const Index> Topology::vertex_edges(Index v) const {
    const auto begin = at(vertex_edge_offset(v));
    return std::span<const Index>(vertex_edges_).subspan(begin, at(vertex_edge_offset(v + 1)) - begin);
}

void Topology::build_boundary_loops() {
    // Each boundary edge runs (as its single face traverses it) from the
    // vertex where it is the first one-ring edge; the next edge of the loop is
    // the first one-ring edge of the vertex it enters.
    std::vector<std::uint8_t> visited(at(num_edges()), 0);
    boundary_loop_offsets_.assign(1, 0);
    for (Index v = 0; v < num_vertices_; ++v) {
        const Index start = is_boundary_vertex(v) ? vertex_edges(v).front() : invalid_index;
        if (start == invalid_index || visited[at(start)] != 0) {
            continue;
        }
        Index u = v;
        Index e = start;
        while (visited[at(e)] == 0) {
            visited[at(e)] = 1;
            boundary_loop_vertices_.push_back(u);
            u = other_vertex(e, u);
            e = vertex_edges(u).front();
        }
        boundary_loop_offsets_.push_back(static_cast<Index>(boundary_loop_vertices_.size()));
    }
}

std::span<const Index> Topology::boundary_loop(Index i) const {
    const auto begin = at(boundary_loop_offsets_[at(i)]);
    return std::span<const Index>(boundary_loop_vertices_)
        .subspan(begin, at(boundary_loop_offsets_[at(i) + 1]) - begin);
}

void Topology::build_components() {
    detail::HugeTable<Index> parent;
    detail::assign_huge(parent, at(num_faces()));
    std::iota(parent.begin(), parent.end(), Index{0});
    // Union by size (the smaller tree goes under the larger): the trees stay logarithmically
    // shallow whatever the edge order, where linking one way round builds long chains on a grid.
    detail::HugeTable<Index> size;
    detail::assign_huge(size, at(num_faces()), 1);
    for (Index e = 0; e < num_edges(); ++e) {
        const auto faces = edge_faces(e);
        if (faces.size() != 2) {
            continue;
        }
        Index a = find_root(parent, faces[0]);
        Index b = find_root(parent, faces[1]);
        if (a == b) {
            continue;
        }
        if (size[at(a)] < size[at(b)]) {
            std::swap(a, b);
        }
        parent[at(b)] = a;
        size[at(a)] += size[at(b)];
    }
    // Number components in order of their first face (in the sizes' table, no longer needed: a
    // table less to fault in).
    detail::HugeTable<Index>& number = size;
    std::fill(number.begin(), number.end(), invalid_index);
    detail::assign_huge(face_component_, at(num_faces()), 0);
    num_components_ = 0;
    for (Index f = 0; f < num_faces(); ++f) {
        Index& n = number[at(find_root(parent, f))];
        if (n == invalid_index) {
            n = num_components_++;
        }
        face_component_[at(f)] = n;
    }
    // chi and boundary loops per component give the genus of each.
    std::vector<Index> chi(at(num_components_), 0);
    std::vector<Index> loops(at(num_components_), 0);
    for (Index f = 0; f < num_faces(); ++f) {
        ++chi[at(face_component_[at(f)])];
    }
    for (Index v = 0; v < num_vertices_; ++v) {
        ++chi[at(vertex_component(v))];
    }
    for (Index e = 0; e < num_edges(); ++e) {
        --chi[at(face_component_[at(edge_faces(e).front())])];
    }
    for (Index i = 0; i < num_boundary_loops(); ++i) {
        ++loops[at(vertex_component(boundary_loop(i).front()))];
    }
    genus_ = 0;
    for (Index c = 0; c < num_components_; ++c) {
        LIMSURF_ASSERT((2 - chi[at(c)] - loops[at(c)]) % 2 == 0, "odd 2 - chi - b in component ", c);
        genus_ += (2 - chi[at(c)] - loops[at(c)]) / 2;
    }
    if (num_components_ == 1) {
        detail::HugeTable<Index>().swap(face_component_);  // every face's is 0
    }
}

Index Topology::vertex_component(Index v) const {
    return face_component(vertex_faces(v).front());
}

bool Topology::all_faces_have_degree(Index degree) const noexcept {
    for (Index f = 0; f < num_faces(); ++f) {
        if (face_offsets_[at(f) + 1] - face_offsets_[at(f)] != degree) {
            return false;
        }
    }
    return true;
}

void Topology::apply_sharpness(const SharpnessTags& sharpness) {
    // The last tag of an edge or vertex wins, a 0 included, as in OpenSubdiv's factory (validate()
    // warns when two tags disagree). The tables stay empty until some sharpness is positive.
    for (const CreaseTag& crease : sharpness.creases) {
        if (crease.sharpness > 0.0 || !edge_sharpness_.empty()) {
            edge_sharpness_.resize(at(num_edges()), 0.0);
            edge_sharpness_[at(find_edge(crease.v0, crease.v1))] = crease.sharpness;
        }
    }
    for (const CornerTag& corner : sharpness.corners) {
        if (corner.sharpness > 0.0 || !vertex_sharpness_.empty()) {
            vertex_sharpness_.resize(at(num_vertices_), 0.0);
            vertex_sharpness_[at(corner.vertex)] = corner.sharpness;
        }
    }
    // A later 0 may have cleared every sharpness: then the mesh is as smooth as one without tags.
    const auto all_zero = [](const auto& table) {
        return std::all_of(table.begin(), table.end(), [](double s) { return s == 0.0; });
    };
    if (all_zero(edge_sharpness_)) {
        edge_sharpness_.clear();
    }
    if (all_zero(vertex_sharpness_)) {
        vertex_sharpness_.clear();
    }
    for (const HoleTag& hole : sharpness.holes) {
        holes_.resize(at(num_faces()), 0);
        holes_[at(hole.face)] = 1;
    }
}

SharpnessTags Topology::sharpness_tags() const {
    SharpnessTags tags;
    for (size_t e = 0; e < edge_sharpness_.size(); ++e) {
        if (edge_sharpness_[e] > 0.0) {
            const auto ends = edge_vertices(static_cast<Index>(e));
            tags.creases.push_back({ends[0], ends[1], edge_sharpness_[e], 0});
        }
    }
    for (size_t v = 0; v < vertex_sharpness_.size(); ++v) {
        if (vertex_sharpness_[v] > 0.0) {
            tags.corners.push_back({static_cast<Index>(v), vertex_sharpness_[v], 0});
        }
    }
    for (size_t f = 0; f < holes_.size(); ++f) {
        if (holes_[f] != 0) {
            tags.holes.push_back({static_cast<Index>(f), 0});
        }
    }
    return tags;
}

}  // namespace limsurf
