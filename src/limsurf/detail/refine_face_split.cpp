#include "limsurf/detail/refine_face_split.h"

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <utility>

#include "limsurf/core/parallel.h"
#include "limsurf/detail/huge_pages.h"

namespace limsurf::detail {
namespace {

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

}  // namespace

EffectiveSharpness effective_sharpness(const Topology& parent, BoundaryInterpolation boundary) {
    EffectiveSharpness result;
    const Index num_edges = parent.num_edges();
    const Index num_vertices = parent.num_vertices();
    result.edge.resize(at(num_edges));
    for (Index e = 0; e < num_edges; ++e) {
        result.edge[at(e)] = parent.is_boundary_edge(e) ? infinite_sharpness : parent.edge_sharpness(e);
    }
    result.vertex.resize(at(num_vertices));
    const bool sharpen_corners = boundary == BoundaryInterpolation::EdgeAndCorner;
    for (Index v = 0; v < num_vertices; ++v) {
        const bool corner = sharpen_corners && parent.is_boundary_vertex(v) && parent.vertex_faces(v).size() == 1;
        result.vertex[at(v)] = corner ? infinite_sharpness : parent.vertex_sharpness(v);
    }
    return result;
}

namespace {

/// Child vertices numbered by the parent elements they come from, in blocks of @p counts in turn:
/// each block's parents are 0, 1, ... (the face splits' vertex order, refine/level.h). The tables
/// are advised for huge pages and written once (no zero fill before).
void number_child_vertices(std::initializer_list<std::pair<Index, ParentKind>> counts, Provenance& p) {
    std::size_t total = 0;
    for (const auto& block : counts) {
        total += at(block.first);
    }
    reserve_huge(p.vertex_parent_kind, total);
    reserve_huge(p.vertex_parent, total);
    for (const auto& [count, kind] : counts) {
        p.vertex_parent_kind.insert(p.vertex_parent_kind.end(), at(count), kind);
        for (Index i = 0; i < count; ++i) {
            p.vertex_parent.push_back(i);
        }
    }
}

}  // namespace

Provenance quad_split_provenance(Index vertices, Index edges, std::span<const Index> face_offsets) {
    const auto F = static_cast<Index>(face_offsets.size()) - 1;
    Provenance p;
    number_child_vertices({{vertices, ParentKind::Vertex}, {F, ParentKind::Face}, {edges, ParentKind::Edge}}, p);
    const auto num_child_faces = at(face_offsets.back());
    assign_huge(p.face_parent_kind, num_child_faces, ParentKind::Face);
    reserve_huge(p.face_parent, num_child_faces);
    reserve_huge(p.face_parent_corner, num_child_faces);
    for (Index f = 0; f < F; ++f) {
        const Index n = face_offsets[at(f) + 1] - face_offsets[at(f)];
        for (Index k = 0; k < n; ++k) {
            p.face_parent.push_back(f);
            p.face_parent_corner.push_back(k);
        }
    }
    return p;
}

Provenance tri_split_provenance(Index vertices, Index edges, Index F) {
    Provenance p;
    number_child_vertices({{vertices, ParentKind::Vertex}, {edges, ParentKind::Edge}}, p);
    const auto num_child_faces = 4 * at(F);
    assign_huge(p.face_parent_kind, num_child_faces, ParentKind::Face);
    reserve_huge(p.face_parent, num_child_faces);
    reserve_huge(p.face_parent_corner, num_child_faces);
    for (Index f = 0; f < F; ++f) {
        for (Index k = 0; k < 4; ++k) {
            p.face_parent.push_back(f);
            p.face_parent_corner.push_back(k < 3 ? k : invalid_index);
        }
    }
    return p;
}

SharpnessTags child_sharpness(const Topology& parent, const EffectiveSharpness& effective, CreasingMethod method,
                              Index first_edge_vertex, bool triangle_split) {
    SharpnessTags tags;
    if (!parent.has_sharpness()) {
        return tags;
    }
    std::vector<double> around;
    for (Index e = 0; e < parent.num_edges(); ++e) {
        const double own = parent.edge_sharpness(e);
        if (!is_sharp(own)) {
            continue;
        }
        const auto ends = parent.edge_vertices(e);
        const Index mid = first_edge_vertex + e;
        for (const Index end : ends) {
            double child = 0.0;
            if (parent.is_boundary_edge(e)) {
                child = decrement_sharpness(own);
            } else {
                const auto edges = parent.vertex_edges(end);
                around.resize(edges.size());
                for (std::size_t i = 0; i < edges.size(); ++i) {
                    around[i] = effective.edge[at(edges[i])];
                }
                child = subdivide_edge_sharpness_at_vertex(own, around, method);
            }
            if (is_sharp(child)) {
                tags.creases.push_back({end, mid, child, 0});
            }
        }
    }
    for (Index v = 0; v < parent.num_vertices(); ++v) {
        const double child = decrement_sharpness(parent.vertex_sharpness(v));
        if (is_sharp(child)) {
            tags.corners.push_back({v, child, 0});
        }
    }
    Index first_child_face = 0;
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index count = triangle_split ? 4 : parent.face_degree(f);
        if (parent.is_hole(f)) {
            for (Index k = 0; k < count; ++k) {
                tags.holes.push_back({first_child_face + k, 0});
            }
        }
        first_child_face += count;
    }
    return tags;
}

namespace {

/// Where the child edge of crease @p tag (a half of a parent edge: {parent end, edge point}) first
/// appears in the child face list, as slot × face size + edge: the child Topology numbers its edges in
/// that order. The half at v of edge e lies in the child at v's corner of each face of e, as its
/// first edge (e leaves that corner) or its last (e enters it).
Index first_appearance(const Topology& parent, Split split, Index first_edge_vertex, const CreaseTag& tag) {
    const Index e = tag.v1 - first_edge_vertex;
    const Index v = tag.v0;
    const Index size = split == Split::Quads ? 4 : 3;
    Index first = std::numeric_limits<Index>::max();
    for (const Index g : parent.edge_faces(e)) {
        const auto verts = parent.face_vertices(g);
        const auto k = static_cast<Index>(std::find(verts.begin(), verts.end(), v) - verts.begin());
        const Index child = split == Split::Quads ? parent.face_offset(g) + k : 4 * g + k;
        const Index edge = parent.face_edges(g)[at(k)] == e ? 0 : size - 1;
        first = std::min(first, size * child + edge);
    }
    return first;
}

}  // namespace

void write_split_faces(const Topology& parent, Split split, SharpnessTags tags, PolygonSoup& out) {
    const Index V = parent.num_vertices();
    const Index F = parent.num_faces();
    const Index first_edge_vertex = split == Split::Quads ? V + F : V;
    const std::size_t num_faces = split == Split::Quads ? at(parent.num_corners()) : 4 * at(F);
    const Index size = split == Split::Quads ? 4 : 3;
    reserve_huge(out.face_offsets, num_faces + 1);
    out.face_offsets.resize(num_faces + 1);
    for (std::size_t i = 0; i <= num_faces; ++i) {
        out.face_offsets[i] = static_cast<Index>(size * static_cast<Index>(i));
    }
    reserve_huge(out.face_vertices, num_faces * at(size));
    out.face_vertices.clear();
    for (Index f = 0; f < F; ++f) {
        const auto verts = parent.face_vertices(f);
        const auto edges = parent.face_edges(f);
        const std::size_t n = verts.size();
        for (std::size_t k = 0; k < n; ++k) {
            const Index next = first_edge_vertex + edges[k];
            const Index previous = first_edge_vertex + edges[(k + n - 1) % n];
            if (split == Split::Quads) {  // [v_k, e_k, f, e_(k-1)]
                out.face_vertices.insert(out.face_vertices.end(), {verts[k], next, V + f, previous});
            } else {  // [v_k, e_k, e_(k-1)]
                out.face_vertices.insert(out.face_vertices.end(), {verts[k], next, previous});
            }
        }
        if (split == Split::Triangles) {  // the middle [e_0, e_1, e_2]
            for (const Index e : edges) {
                out.face_vertices.push_back(first_edge_vertex + e);
            }
        }
    }

    std::vector<std::pair<Index, std::size_t>> order;
    order.reserve(tags.creases.size());
    for (std::size_t i = 0; i < tags.creases.size(); ++i) {
        order.emplace_back(first_appearance(parent, split, first_edge_vertex, tags.creases[i]), i);
    }
    std::sort(order.begin(), order.end());
    out.sharpness.creases.clear();
    for (const auto& [position, i] : order) {
        out.sharpness.creases.push_back(tags.creases[i]);
    }
    // child_sharpness() gives corners in vertex and holes in face order already.
    out.sharpness.corners = std::move(tags.corners);
    out.sharpness.holes = std::move(tags.holes);
}

Index opposite_vertex(const Topology& parent, Index f, Index e) {
    const auto edges = parent.face_edges(f);
    const auto verts = parent.face_vertices(f);
    for (std::size_t k = 0; k < 3; ++k) {
        if (edges[k] == e) {
            return verts[(k + 2) % 3];
        }
    }
    return invalid_index;
}

void require_triangles(const Topology& parent, const char* scheme) {
    for (Index f = 0; f < parent.num_faces(); ++f) {
        const Index degree = parent.face_degree(f);
        LIMSURF_CHECK_AT(degree == 3, UnsupportedError, face_element(f), "face ", f, " has ", degree,
                         " vertices: ", scheme, " needs triangles");
    }
}

SparseRowBuilder::SparseRowBuilder(Index rows, Index cols, Index nnz_hint, const StepRun& run)
    : matrix_(rows, cols), carried_(run.carried), keep_matrix_(run.keeps_matrix()) {
    if (carried_ != nullptr) {
        LIMSURF_ASSERT(carried_->parent.rows() == cols, "carried points: ", carried_->parent.rows(), " rows for ", cols,
                       " columns");
        carried_->child.resize(rows, 3);
        advise_huge_pages(carried_->child.data(), sizeof(double) * static_cast<std::size_t>(carried_->child.size()));
    }
    if (keep_matrix_) {
        matrix_.reserve(nnz_hint);
        advise_huge_pages(matrix_.valuePtr(), sizeof(double) * static_cast<std::size_t>(nnz_hint));
        advise_huge_pages(matrix_.innerIndexPtr(), sizeof(Index) * static_cast<std::size_t>(nnz_hint));
    }
    row_.reserve(64);
    slot_of_column_.assign(static_cast<std::size_t>(cols), 0);
}

void SparseRowBuilder::sort_row() {
    const auto by_column = [](const Entry& a, const Entry& b) { return a.col < b.col; };
    if (row_.size() > 32) {  // an n-gon's face point or a vertex of an n-gon
        std::sort(row_.begin(), row_.end(), by_column);
        return;
    }
    // Insertion sort: rows hold a handful of entries.
    for (std::size_t i = 1; i < row_.size(); ++i) {
        const Entry entry = row_[i];
        std::size_t j = i;
        while (j > 0 && by_column(entry, row_[j - 1])) {
            row_[j] = row_[j - 1];
            --j;
        }
        row_[j] = entry;
    }
}

void SparseRowBuilder::end_row() {
    sort_row();
    if (carried_ != nullptr) {
        // Eigen's sparse × dense product sums each coordinate from +0 in column order (no FMA on
        // this build's baseline); the same operations here give the same bits.
        double x = 0.0;
        double y = 0.0;
        double z = 0.0;
        for (const Entry& entry : row_) {
            const double* p = carried_->parent.row(entry.col).data();
            x += entry.weight * p[0];
            y += entry.weight * p[1];
            z += entry.weight * p[2];
        }
        carried_->child(current_, 0) = x;
        carried_->child(current_, 1) = y;
        carried_->child(current_, 2) = z;
    }
    if (keep_matrix_) {
        // Appended straight into the compressed arrays (Eigen's insertBack checks and grows per
        // entry); the storage doubles when the hint was short.
        auto& data = matrix_.data();
        const Index begin = data.size();
        data.resize(begin + static_cast<Index>(row_.size()), 1.0);
        for (std::size_t i = 0; i < row_.size(); ++i) {
            data.index(begin + static_cast<Index>(i)) = row_[i].col;
            data.value(begin + static_cast<Index>(i)) = row_[i].weight;
        }
        matrix_.outerIndexPtr()[current_ + 1] = data.size();
    }
    row_.clear();
    ++current_;
}

void add_identity_rows(Index num_vertices, SparseRowBuilder& rows) {
    for (Index v = 0; v < num_vertices; ++v) {
        rows.add(v, 1.0);
        rows.end_row();
    }
}

void add_edge_midpoint(const Topology& parent, Index e, SparseRowBuilder& rows) {
    const auto ends = parent.edge_vertices(e);
    rows.add(ends[0], 0.5);
    rows.add(ends[1], 0.5);
}

void add_midpoint_rows(const Topology& parent, SparseRowBuilder& rows) {
    for (Index e = 0; e < parent.num_edges(); ++e) {
        add_edge_midpoint(parent, e, rows);
        rows.end_row();
    }
}

void add_vertex_and_neighbours(const Topology& parent, Index v, const VertexMask& mask, SparseRowBuilder& rows) {
    rows.add(v, mask.vertex);
    const auto edges = parent.vertex_edges(v);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        rows.add(parent.other_vertex(edges[i], v), mask.edges[i]);
    }
}

SparseMatrix SparseRowBuilder::finish() {
    LIMSURF_ASSERT(current_ == matrix_.rows(), "rows ended: ", current_, " of ", matrix_.rows());
    if (carried_ != nullptr) {
        carried_->parent = {};  // read by the rows only: freed before the rest of the step
    }
    slot_of_column_ = {};
    SparseMatrix out;  // swap, not move: Eigen 3.4's SparseMatrix has no move constructor
    out.swap(matrix_);
    return out;
}

bool edge_child_is_crease(const Topology& parent, const EffectiveSharpness& effective, CreasingMethod method, Index e,
                          std::vector<double>& scratch) {
    const double s = effective.edge[at(e)];
    if (method == CreasingMethod::Uniform || is_infinitely_sharp(s)) {
        return is_sharp(decrement_sharpness(s));
    }
    for (const Index end : parent.edge_vertices(e)) {
        const auto edges = parent.vertex_edges(end);
        scratch.resize(edges.size());
        for (std::size_t i = 0; i < edges.size(); ++i) {
            scratch[i] = effective.edge[at(edges[i])];
        }
        if (!is_sharp(subdivide_edge_sharpness_at_vertex(s, scratch, method))) {
            return false;
        }
    }
    return true;
}

int step_threads(int requested, const Topology& parent) {
    // A thread starts in tens of microseconds; a step of 1024 faces takes about a millisecond.
    constexpr Index smallest_parallel_step = 1024;
    if (parent.num_faces() < smallest_parallel_step) {
        return 1;
    }
    return std::min(2, thread_count(requested, parent.num_faces()));
}

Level finish_step(const Topology& parent, std::future<Topology>& child, SparseRowBuilder& rows, const StepRun& run,
                  Split split, EffectiveSharpness* effective) {
    SparseMatrix S0 = rows.finish();
    // The child (its sharpness reads the effective sharpness) before the provenance, the step's last
    // table: what the child no longer needs, and with run.release_parent the parent, goes first, and
    // the step peaks lower.
    Topology topology = child.get();
    if (effective != nullptr) {
        *effective = {};
    }
    const Index vertices = parent.num_vertices();
    const Index edges = parent.num_edges();
    const Index parent_faces = parent.num_faces();
    std::span<const Index> face_offsets = parent.face_offsets();
    std::vector<Index> kept_offsets;  // the quad split's face sizes, when the parent goes first
    if (run.release_parent) {
        if (split == Split::Quads && run.keeps_matrix()) {
            kept_offsets.assign(face_offsets.begin(), face_offsets.end());
        }
        face_offsets = kept_offsets;
        run.release_parent();  // `parent` is not read from here on
    }
    Provenance provenance;
    if (run.keeps_matrix()) {
        provenance = split == Split::Quads ? quad_split_provenance(vertices, edges, face_offsets)
                                           : tri_split_provenance(vertices, edges, parent_faces);
    }
    return Level{std::move(topology), std::move(S0), std::move(provenance)};
}

}  // namespace limsurf::detail
