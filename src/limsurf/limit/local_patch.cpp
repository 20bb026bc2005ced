#include "local_patch.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/scheme/crease.h"

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Position of @p face in @p list (the one-ring of a vertex of it).
Index position_in(std::span<const Index> list, Index face) {
    const auto it = std::find(list.begin(), list.end(), face);
    LIMSURF_ASSERT(it != list.end(), "face ", face, " is not in the one-ring");
    return static_cast<Index>(it - list.begin());
}

/// Identifies the fan of one-ring faces around rim vertex x that contains face g:
/// the smallest face index of the run of consecutive included faces through g.
Index fan_of(const Topology& source, Index x, Index g, const std::vector<Index>& included) {
    const auto faces = source.vertex_faces(x);
    const auto m = static_cast<Index>(faces.size());
    const bool cyclic = !source.is_boundary_vertex(x);
    const auto in = [&](Index i) {
        return std::find(included.begin(), included.end(), faces[at(i)]) != included.end();
    };
    const Index start = position_in(faces, g);
    Index smallest = g;
    for (int direction : {+1, -1}) {
        Index i = start;
        for (Index step = 1; step < m; ++step) {
            Index next = i + direction;
            if (cyclic) {
                next = (next + m) % m;
            } else if (next < 0 || next >= m) {
                break;
            }
            if (!in(next)) {
                break;
            }
            i = next;
            smallest = std::min(smallest, faces[at(i)]);
        }
    }
    return smallest;
}

}  // namespace

PatchArrays extract_patch_arrays(const Topology& source, Index face, int start_corner) {
    const auto corners = source.face_vertices(face);
    const auto n = static_cast<int>(corners.size());
    // 1. The one-ring faces, canonically: the face, then around each of its
    //    corners counter-clockwise from the face; each starts at that corner.
    std::vector<Index> faces{face};
    std::vector<int> starts{start_corner};
    for (int k = 0; k < n; ++k) {
        const Index v = corners[at((start_corner + k) % n)];
        const auto ring = source.vertex_faces(v);
        const auto ring_corners = source.vertex_face_corners(v);
        const auto m = static_cast<Index>(ring.size());
        const Index i = position_in(ring, face);
        for (Index d = 1; d < m; ++d) {
            const Index j = (i + d) % m;
            if (std::find(faces.begin(), faces.end(), ring[at(j)]) == faces.end()) {
                faces.push_back(ring[at(j)]);
                starts.push_back(ring_corners[at(j)]);
            }
        }
    }
    // 2. Local vertices in order of first appearance; a rim vertex gets one local
    //    vertex per fan of one-ring faces around it.
    PatchArrays patch;
    struct Key {
        Index vertex;
        Index fan;
    };
    std::vector<Key> keys;
    const auto local_of = [&](Index x, Index g) {
        const bool own = std::find(corners.begin(), corners.end(), x) != corners.end();
        const Index fan = own ? invalid_index : fan_of(source, x, g, faces);
        for (std::size_t i = 0; i < keys.size(); ++i) {
            if (keys[i].vertex == x && keys[i].fan == fan) {
                return static_cast<Index>(i);
            }
        }
        keys.push_back({x, fan});
        patch.source.push_back(x);
        return static_cast<Index>(keys.size() - 1);
    };
    std::vector<Index>& offsets = patch.offsets;
    std::vector<Index>& local_corners = patch.corners;
    SharpnessTags& tags = patch.tags;
    offsets.push_back(0);
    for (std::size_t i = 0; i < faces.size(); ++i) {
        const Index g = faces[i];
        const auto g_corners = source.face_vertices(g);
        const auto g_edges = source.face_edges(g);
        const auto degree = static_cast<int>(g_corners.size());
        const Index first = static_cast<Index>(local_corners.size());
        for (int c = 0; c < degree; ++c) {
            local_corners.push_back(local_of(g_corners[at((starts[i] + c) % degree)], g));
        }
        for (int c = 0; c < degree; ++c) {
            const double sharpness = source.edge_sharpness(g_edges[at((starts[i] + c) % degree)]);
            if (sharpness <= 0.0) {
                continue;
            }
            const Index a = local_corners[at(first + c)];
            const Index b = local_corners[at(first + (c + 1) % degree)];
            const bool seen = std::any_of(tags.creases.begin(), tags.creases.end(), [&](const CreaseTag& t) {
                return (t.v0 == a && t.v1 == b) || (t.v0 == b && t.v1 == a);
            });
            if (!seen) {
                tags.creases.push_back({a, b, sharpness, 0});
            }
        }
        if (source.is_hole(g)) {
            tags.holes.push_back({static_cast<Index>(i), 0});
        }
        offsets.push_back(static_cast<Index>(local_corners.size()));
    }
    for (std::size_t v = 0; v < patch.source.size(); ++v) {
        const double sharpness = source.vertex_sharpness(patch.source[v]);
        if (sharpness > 0.0) {
            tags.corners.push_back({static_cast<Index>(v), sharpness, 0});
        }
    }
    return patch;
}

PatchMesh make_patch_mesh(PatchArrays arrays) {
    PatchMesh mesh;
    mesh.topology =
        refined_topology(static_cast<Index>(arrays.source.size()), arrays.offsets, arrays.corners, arrays.tags);
    mesh.source = std::move(arrays.source);
    return mesh;
}

PatchMesh extract_patch_mesh(const Topology& source, Index face, int start_corner) {
    return make_patch_mesh(extract_patch_arrays(source, face, start_corner));
}

std::string patch_signature(const PatchArrays& arrays) {
    std::string bytes;
    const auto append = [&bytes](const void* data, std::size_t size) {
        bytes.append(static_cast<const char*>(data), size);
    };
    const std::size_t counts[5] = {arrays.source.size(), arrays.offsets.size(), arrays.tags.creases.size(),
                                   arrays.tags.corners.size(), arrays.tags.holes.size()};
    append(counts, sizeof counts);
    append(arrays.offsets.data(), arrays.offsets.size() * sizeof(Index));
    append(arrays.corners.data(), arrays.corners.size() * sizeof(Index));
    for (const CreaseTag& t : arrays.tags.creases) {
        append(&t.v0, sizeof t.v0);
        append(&t.v1, sizeof t.v1);
        append(&t.sharpness, sizeof t.sharpness);
    }
    for (const CornerTag& t : arrays.tags.corners) {
        append(&t.vertex, sizeof t.vertex);
        append(&t.sharpness, sizeof t.sharpness);
    }
    for (const HoleTag& t : arrays.tags.holes) {
        append(&t.face, sizeof t.face);
    }
    return bytes;
}

std::string topology_signature(const Topology& topology) {
    std::string bytes;
    const auto append = [&bytes](const void* data, std::size_t size) {
        bytes.append(static_cast<const char*>(data), size);
    };
    const Index counts[3] = {topology.num_vertices(), topology.num_faces(), topology.num_corners()};
    append(counts, sizeof counts);
    append(topology.face_offsets().data(), topology.face_offsets().size_bytes());
    append(topology.all_face_vertices().data(), topology.all_face_vertices().size_bytes());
    if (topology.has_sharpness()) {
        for (Index e = 0; e < topology.num_edges(); ++e) {
            const double s = topology.edge_sharpness(e);
            append(&s, sizeof s);
        }
        for (Index v = 0; v < topology.num_vertices(); ++v) {
            const double s = topology.vertex_sharpness(v);
            append(&s, sizeof s);
        }
        for (Index f = 0; f < topology.num_faces(); ++f) {
            const char hole = topology.is_hole(f) ? 1 : 0;
            append(&hole, 1);
        }
    }
    return bytes;
}

void PatchPointStencil::add(Index v, double w) {
    for (int i = 0; i < size; ++i) {
        if (vertex[at(i)] == v) {
            weight[at(i)] += w;
            return;
        }
    }
    LIMSURF_ASSERT(size < 4, "a phantom point combines at most four vertices");
    vertex[at(size)] = v;
    weight[at(size)] = w;
    ++size;
}

void PatchPointStencil::add(const PatchPointStencil& other, double w) {
    for (int i = 0; i < other.size; ++i) {
        add(other.vertex[at(i)], w * other.weight[at(i)]);
    }
}

namespace {

/// How a corner of a face sits in a regular patch.
enum class CornerKind { Irregular, Smooth, Crease, Corner };

/// The sharpness the rules see (boundary edges are infinitely sharp, and so is a
/// boundary vertex in one face under EdgeAndCorner; see refine_face_split.h).
struct Sharpness {
    const Topology& t;
    BoundaryInterpolation boundary;
    [[nodiscard]] double edge(Index e) const {
        return t.is_boundary_edge(e) ? infinite_sharpness : t.edge_sharpness(e);
    }
    [[nodiscard]] double vertex(Index v) const {
        const bool corner = boundary == BoundaryInterpolation::EdgeAndCorner && t.is_boundary_vertex(v) &&
                            t.vertex_faces(v).size() == 1;
        return corner ? infinite_sharpness : t.vertex_sharpness(v);
    }
};

/// The one-ring of vertex v seen from face f: where f sits and how to step around.
struct RingView {
    std::span<const Index> faces;
    VertexFaceCorners corners;
    std::span<const Index> edges;
    Index position = 0;  ///< of f in faces
    bool cyclic = true;

    RingView(const Topology& t, Index v, Index f)
        : faces(t.vertex_faces(v)), corners(t.vertex_face_corners(v)), edges(t.vertex_edges(v)),
          position(position_in(t.vertex_faces(v), f)), cyclic(!t.is_boundary_vertex(v)) {}
    /// Index of the face @p d steps counter-clockwise (negative: clockwise) from f, or -1.
    [[nodiscard]] Index face_index(Index d) const {
        const auto m = static_cast<Index>(faces.size());
        const Index i = position + d;
        if (cyclic) {
            return ((i % m) + m) % m;
        }
        return i >= 0 && i < m ? i : -1;
    }
    /// Edge i (between faces i-1 and i), or invalid_index.
    [[nodiscard]] Index edge(Index i) const {
        const auto m = static_cast<Index>(edges.size());
        if (cyclic) {
            return edges[at(((i % m) + m) % m)];
        }
        return i >= 0 && i < m ? edges[at(i)] : invalid_index;
    }
};

/// Classifies corner vertex v of face f for a regular patch whose faces have
/// @p degree corners and whose regular valence (faces around an interior vertex) is
/// @p regular_faces; @p side_faces is the number of faces on f's side of a regular crease.
CornerKind classify_corner(const Sharpness& sharp, Index v, Index f, int degree, Index regular_faces,
                           Index side_faces) {
    const Topology& t = sharp.t;
    const RingView ring(t, v, f);
    const double vs = sharp.vertex(v);
    if (is_semi_sharp(vs)) {
        return CornerKind::Irregular;
    }
    int num_sharp = 0;
    for (Index e : ring.edges) {
        const double s = sharp.edge(e);
        if (is_semi_sharp(s)) {
            return CornerKind::Irregular;
        }
        num_sharp += is_infinitely_sharp(s) ? 1 : 0;
    }
    const bool out_sharp = is_infinitely_sharp(sharp.edge(ring.edge(ring.position)));
    const bool in_sharp = is_infinitely_sharp(sharp.edge(ring.edge(ring.position + 1)));
    const auto all_of_degree = [&](Index from, Index to) {
        for (Index d = from; d <= to; ++d) {
            const Index i = ring.face_index(d);
            if (i < 0 || t.face_degree(ring.faces[at(i)]) != degree) {
                return false;
            }
        }
        return true;
    };
    if (num_sharp == 0 && vs == 0.0) {
        const bool regular = ring.cyclic && static_cast<Index>(ring.faces.size()) == regular_faces;
        return regular && all_of_degree(0, regular_faces - 1) ? CornerKind::Smooth : CornerKind::Irregular;
    }
    if (num_sharp == 2 && vs == 0.0 && out_sharp != in_sharp) {
        // The other sharp edge closes f's side after side_faces faces.
        const Index last = out_sharp ? side_faces - 1 : -(side_faces - 1);
        const Index closing = out_sharp ? ring.position + side_faces : ring.position - (side_faces - 1);
        const bool faces_ok = out_sharp ? all_of_degree(0, last) : all_of_degree(last, 0);
        const Index e = ring.edge(closing);
        return faces_ok && e != invalid_index && is_infinitely_sharp(sharp.edge(e)) ? CornerKind::Crease
                                                                                    : CornerKind::Irregular;
    }
    if (out_sharp && in_sharp && (is_infinitely_sharp(vs) || num_sharp >= 3)) {
        return CornerKind::Corner;
    }
    return CornerKind::Irregular;
}

/// The face on the other side of edge k of face f, rotated so that entry 0 is corner
/// k+1 of f and entry 1 is corner k (quads): entries 2 and 3 are the far points.
std::array<Index, 4> across_edge(const Topology& t, Index f, int k) {
    const Index e = t.face_edges(f)[at(k)];
    const auto faces = t.edge_faces(e);
    const Index g = faces[0] == f ? faces[1] : faces[0];
    const auto gv = t.face_vertices(g);
    const Index a = t.face_vertices(f)[at((k + 1) % 4)];
    const Index j = position_in(gv, a);
    std::array<Index, 4> r{};
    for (int i = 0; i < 4; ++i) {
        r[at(i)] = gv[at((j + i) % 4)];
    }
    return r;
}

/// The quad on the other side of edge (from -> to) oriented so that entry 0 is `to`, 1 is `from`.
std::array<Index, 4> quad_across(const Topology& t, Index from, Index to) {
    const Index e = t.find_edge(from, to);
    for (Index g : t.edge_faces(e)) {
        const auto gv = t.face_vertices(g);
        const Index j = position_in(gv, to);
        if (gv[at((j + 1) % 4)] == from) {
            return {gv[at(j)], gv[at((j + 1) % 4)], gv[at((j + 2) % 4)], gv[at((j + 3) % 4)]};
        }
    }
    LIMSURF_ASSERT(false, "no quad across edge ", from, "-", to);
    return {};
}

}  // namespace

bool catmull_clark_regular_patch(const Topology& t, Index face, BoundaryInterpolation boundary, RegularPatch& out) {
    if (t.face_degree(face) != 4) {
        return false;
    }
    const Sharpness sharp{t, boundary};
    const auto v = t.face_vertices(face);
    std::array<CornerKind, 4> kind{};
    for (int k = 0; k < 4; ++k) {
        kind[at(k)] = classify_corner(sharp, v[at(k)], face, 4, 4, 2);
        if (kind[at(k)] == CornerKind::Irregular) {
            return false;
        }
    }
    std::array<bool, 4> edge_sharp{};
    for (int k = 0; k < 4; ++k) {
        edge_sharp[at(k)] = is_infinitely_sharp(sharp.edge(t.face_edges(face)[at(k)]));
    }
    // Grid (i, j) -> 4j + i; the face's corners sit at 5, 6, 10, 9.
    constexpr std::array<int, 4> own = {5, 6, 10, 9};
    constexpr std::array<std::array<int, 2>, 4> beyond = {{{1, 2}, {7, 11}, {14, 13}, {8, 4}}};
    constexpr std::array<int, 4> diagonal = {0, 3, 15, 12};
    out = RegularPatch{};
    out.size = 16;
    std::array<bool, 16> known{};
    for (int k = 0; k < 4; ++k) {
        out.points[at(own[at(k)])].add(v[at(k)], 1.0);
        known[at(own[at(k)])] = true;
    }
    for (int k = 0; k < 4; ++k) {
        if (edge_sharp[at(k)]) {
            continue;
        }
        const auto g = across_edge(t, face, k);
        out.points[at(beyond[at(k)][0])].add(g[2], 1.0);
        out.points[at(beyond[at(k)][1])].add(g[3], 1.0);
        known[at(beyond[at(k)][0])] = known[at(beyond[at(k)][1])] = true;
        // The diagonal quad at corner k (smooth corners only).
        if (kind[at(k)] == CornerKind::Smooth) {
            const auto d = quad_across(t, g[1], g[2]);
            out.points[at(diagonal[at(k)])].add(d[3], 1.0);
            known[at(diagonal[at(k)])] = true;
        }
    }
    // Phantom rows (bottom j=0, top j=3), then columns (left i=0, right i=3).
    const auto extrapolate = [&](int target, int near, int far) {
        if (!known[at(target)] && known[at(near)] && known[at(far)]) {
            out.points[at(target)].add(out.points[at(near)], 2.0);
            out.points[at(target)].add(out.points[at(far)], -1.0);
            known[at(target)] = true;
        }
    };
    for (int i = 0; i < 4; ++i) {
        if (edge_sharp[0]) {
            extrapolate(i, 4 + i, 8 + i);
        }
        if (edge_sharp[2]) {
            extrapolate(12 + i, 8 + i, 4 + i);
        }
    }
    for (int j = 0; j < 4; ++j) {
        if (edge_sharp[3]) {
            extrapolate(4 * j, 4 * j + 1, 4 * j + 2);
        }
        if (edge_sharp[1]) {
            extrapolate(4 * j + 3, 4 * j + 2, 4 * j + 1);
        }
    }
    return std::all_of(known.begin(), known.end(), [](bool b) { return b; });
}

bool loop_regular_patch(const Topology& t, Index face, BoundaryInterpolation boundary, RegularPatch& out) {
    if (t.face_degree(face) != 3) {
        return false;
    }
    const Sharpness sharp{t, boundary};
    const auto v = t.face_vertices(face);
    std::array<CornerKind, 3> kind{};
    for (int k = 0; k < 3; ++k) {
        kind[at(k)] = classify_corner(sharp, v[at(k)], face, 3, 6, 3);
    }
    int rotation = -1;
    if (std::all_of(kind.begin(), kind.end(), [](CornerKind c) { return c == CornerKind::Smooth; })) {
        rotation = 0;
    } else {
        for (int k = 0; k < 3; ++k) {
            const bool edge_k = is_infinitely_sharp(sharp.edge(t.face_edges(face)[at(k)]));
            if (edge_k && kind[at(k)] == CornerKind::Crease && kind[at((k + 1) % 3)] == CornerKind::Crease &&
                kind[at((k + 2) % 3)] == CornerKind::Smooth) {
                rotation = k;
            }
        }
    }
    if (rotation < 0) {
        return false;
    }
    out = RegularPatch{};
    out.size = 12;
    out.rotation = rotation;
    // Points met walking around each corner from the face: counter-clockwise (third
    // corner of each face) or clockwise (second corner), d = 1..4 faces away.
    constexpr std::array<std::array<int, 4>, 3> ccw = {{{7, 3, 0, 1}, {1, 2, 6, 9}, {9, 11, 10, 7}}};
    constexpr std::array<std::array<int, 4>, 3> cw = {{{1, 0, 3, 7}, {9, 6, 2, 1}, {7, 10, 11, 9}}};
    constexpr std::array<int, 3> own = {4, 5, 8};
    std::array<bool, 12> known{};
    for (int j = 0; j < 3; ++j) {
        const Index vertex = v[at((rotation + j) % 3)];
        out.points[at(own[at(j)])].add(vertex, 1.0);
        known[at(own[at(j)])] = true;
        const RingView ring(t, vertex, face);
        // Smooth: all four; crease at rotated corner 0: counter-clockwise two; corner 1: clockwise two.
        const int count = kind[at((rotation + j) % 3)] == CornerKind::Smooth ? 4 : 2;
        const bool go_cw = kind[at((rotation + j) % 3)] == CornerKind::Crease && j == 1;
        for (int d = 1; d <= count; ++d) {
            const Index i = ring.face_index(go_cw ? -d : d);
            LIMSURF_ASSERT(i >= 0, "regular Loop patch walks off the one-ring");
            const Index g = ring.faces[at(i)];
            const Index c = ring.corners[at(i)];
            const Index point = t.face_vertices(g)[at((c + (go_cw ? 1 : 2)) % 3)];
            const int slot = go_cw ? cw[at(j)][at(d - 1)] : ccw[at(j)][at(d - 1)];
            if (!known[at(slot)]) {
                out.points[at(slot)].add(point, 1.0);
                known[at(slot)] = true;
            }
        }
    }
    if (kind[at(rotation)] == CornerKind::Crease) {
        // Phantom points beyond the sharp edge 4-5 (OpenSubdiv's parallelograms).
        const auto phantom = [&](int target, int a, int b, int c) {
            out.points[at(target)].add(out.points[at(a)], 1.0);
            out.points[at(target)].add(out.points[at(b)], 1.0);
            out.points[at(target)].add(out.points[at(c)], -1.0);
            known[at(target)] = true;
        };
        phantom(0, 4, 3, 7);
        phantom(1, 4, 5, 8);
        phantom(2, 5, 6, 9);
    }
    return std::all_of(known.begin(), known.end(), [](bool b) { return b; });
}

}  // namespace limsurf::detail
