// Subdivision inner products assembled per control face from shared ring stencils
// (patch_inner_products.h).
#include "limsurf/sec/patch_inner_products.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "limsurf/core/error.h"
#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/detail/element_gather.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/refine/form_subdivision.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/polygon_element.h"

namespace limsurf::detail {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// --- rings ------------------------------------------------------------------------------------

/// Control face f and the faces sharing a vertex with it, numbered so that the numbering depends
/// only on the connectivity around f: f first, then the faces around each corner of f in turn,
/// counter-clockwise from f; each face read from the corner it was reached at; vertices numbered
/// as they first appear. On coarse meshes a ring can touch itself at an outer vertex (two fans
/// of ring faces meet there without sharing an edge); a "split" ring gives each such fan its own
/// copy of the vertex, which makes the ring a mesh and changes nothing inside f (only the outer
/// vertex's own rules see the split, and no level-L element inside f depends on them).
struct FaceRing {
    std::vector<Index> faces;      ///< global ids; faces[0] = f
    std::vector<Index> rotations;  ///< the global corner of each face's local corner 0
    std::vector<Index> vertices;   ///< global id of each local vertex
    std::vector<Index> key;        ///< per face: its degree, then its local corners
};

/// Gathers rings with scratch marks sized to the mesh (one gatherer per thread).
class RingGatherer {
  public:
    explicit RingGatherer(const Topology& t)
        : t_(t), local_id_(static_cast<std::size_t>(t.num_vertices()), invalid_index),
          taken_(static_cast<std::size_t>(t.num_faces()), 0) {}

    FaceRing gather(Index f, bool split) {
        FaceRing ring;
        take(ring, f, 0);
        for (const Index corner : t_.face_vertices(f)) {
            take_fan(ring, corner, f);
        }
        if (split) {
            number_split_vertices(ring);
        } else {
            for (std::size_t k = 0; k < ring.faces.size(); ++k) {
                number_vertices(ring, k);
            }
            for (const Index v : ring.vertices) {
                local_id_[at(v)] = invalid_index;
            }
        }
        for (const Index h : ring.faces) {
            taken_[at(h)] = 0;
        }
        return ring;
    }

  private:
    static std::size_t at(Index i) { return static_cast<std::size_t>(i); }

    void take(FaceRing& ring, Index face, Index rotation) {
        taken_[at(face)] = 1;
        ring.faces.push_back(face);
        ring.rotations.push_back(rotation);
    }

    /// The faces around @p corner not taken yet, counter-clockwise starting after @p from.
    void take_fan(FaceRing& ring, Index corner, Index from) {
        const auto faces = t_.vertex_faces(corner);
        const auto corners = t_.vertex_face_corners(corner);
        const std::size_t n = faces.size();
        const auto start = static_cast<std::size_t>(std::find(faces.begin(), faces.end(), from) - faces.begin());
        for (std::size_t i = 1; i < n; ++i) {
            const std::size_t j = (start + i) % n;
            if (taken_[at(faces[j])] == 0) {
                take(ring, faces[j], corners[j]);
            }
        }
    }

    void number_vertices(FaceRing& ring, std::size_t k) {
        const auto verts = t_.face_vertices(ring.faces[k]);
        const std::size_t n = verts.size();
        ring.key.push_back(static_cast<Index>(n));
        for (std::size_t i = 0; i < n; ++i) {
            const Index v = verts[(at(ring.rotations[k]) + i) % n];
            if (local_id_[at(v)] == invalid_index) {
                local_id_[at(v)] = static_cast<Index>(ring.vertices.size());
                ring.vertices.push_back(v);
            }
            ring.key.push_back(local_id_[at(v)]);
        }
    }

    /// Numbers the ring's corners so that two corners share a local vertex exactly when they are
    /// the same vertex and joined through ring faces that share edges at it.
    void number_split_vertices(FaceRing& ring) const {
        struct Slot {
            Index vertex, edge_in, edge_out;
        };
        std::vector<Slot> slots;
        for (std::size_t k = 0; k < ring.faces.size(); ++k) {
            const auto verts = t_.face_vertices(ring.faces[k]);
            const auto edges = t_.face_edges(ring.faces[k]);
            const std::size_t n = verts.size();
            for (std::size_t i = 0; i < n; ++i) {
                const std::size_t c = (at(ring.rotations[k]) + i) % n;
                slots.push_back({verts[c], edges[(c + n - 1) % n], edges[c]});
            }
        }
        std::vector<std::size_t> root(slots.size());
        for (std::size_t a = 0; a < slots.size(); ++a) {
            root[a] = a;
        }
        const auto find = [&](std::size_t a) {
            while (root[a] != a) {
                a = root[a] = root[root[a]];
            }
            return a;
        };
        for (std::size_t a = 0; a < slots.size(); ++a) {
            for (std::size_t b = a + 1; b < slots.size(); ++b) {
                const Slot& x = slots[a];
                const Slot& y = slots[b];
                if (x.vertex == y.vertex && (x.edge_in == y.edge_out || x.edge_out == y.edge_in)) {
                    root[find(b)] = find(a);
                }
            }
        }
        std::vector<Index> local(slots.size(), invalid_index);
        std::size_t slot = 0;
        for (std::size_t k = 0; k < ring.faces.size(); ++k) {
            const auto n = static_cast<std::size_t>(t_.face_degree(ring.faces[k]));
            ring.key.push_back(static_cast<Index>(n));
            for (std::size_t i = 0; i < n; ++i, ++slot) {
                auto& id = local[find(slot)];
                if (id == invalid_index) {
                    id = static_cast<Index>(ring.vertices.size());
                    ring.vertices.push_back(slots[slot].vertex);
                }
                ring.key.push_back(id);
            }
        }
    }

    const Topology& t_;
    std::vector<Index> local_id_;
    std::vector<std::uint8_t> taken_;
};

struct KeyHash {
    std::size_t operator()(const std::vector<Index>& key) const noexcept {
        std::size_t h = key.size();
        for (const Index x : key) {
            h ^= static_cast<std::size_t>(x) + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        }
        return h;
    }
};

// --- stencils ---------------------------------------------------------------------------------

/// Where a ring edge sits: a (local face, local corner) that runs along it, and whether that
/// traversal follows the edge's local orientation.
struct EdgeSource {
    Index face = 0;
    Index corner = 0;
    double local_sign = 1.0;
};

/// What every face with one ring connectivity shares: the rows of A_k^L for the level-L elements
/// inside the ring's first face, over the ring's elements, and the level-L faces' corners.
struct PatchStencil {
    std::vector<EdgeSource> ring_edges;  ///< one per ring edge, in the ring's local edge order
    int fine_degree = 0;                 ///< 4 (Catmull–Clark) or 3 (Loop)
    RowMatrix vertex_rows;               ///< #fine vertices × #ring vertices: A_0^L
    RowMatrix position_rows;             ///< the limit positions' rows (SecSnap), else empty
    RowMatrix edge_rows;                 ///< #fine edges × #ring edges: A_1^L
    RowMatrix face_rows;                 ///< #fine faces × #ring faces: A_2^L
    std::vector<Index> corner_vertex;    ///< fine face g, corner i → row of vertex_rows [g·degree + i]
    std::vector<Index> corner_edge;      ///< edge from corner i to i+1 → row of edge_rows
    std::vector<double> corner_sign;     ///< +1 when that edge runs along the face's orientation
};

/// Local topology of a ring from its key.
Topology ring_topology(const FaceRing& ring) {
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    for (std::size_t p = 0; p < ring.key.size();) {
        const auto n = static_cast<std::size_t>(ring.key[p]);
        corners.insert(corners.end(), ring.key.begin() + static_cast<std::ptrdiff_t>(p + 1),
                       ring.key.begin() + static_cast<std::ptrdiff_t>(p + 1 + n));
        offsets.push_back(static_cast<Index>(corners.size()));
        p += n + 1;
    }
    return Topology(static_cast<Index>(ring.vertices.size()), offsets, corners);
}

/// The rows @p rows of @p A, densely.
RowMatrix dense_rows(const SparseMatrix& A, const std::vector<Index>& rows) {
    RowMatrix out = RowMatrix::Zero(static_cast<Eigen::Index>(rows.size()), A.cols());
    for (std::size_t r = 0; r < rows.size(); ++r) {
        for (SparseMatrix::InnerIterator it(A, rows[r]); it; ++it) {
            out(static_cast<Eigen::Index>(r), it.col()) = it.value();
        }
    }
    return out;
}

/// Numbers @p id in @p rows on first sight and returns its row.
Index row_of(Index id, std::vector<Index>& slot, std::vector<Index>& rows) {
    auto& s = slot[static_cast<std::size_t>(id)];
    if (s == invalid_index) {
        s = static_cast<Index>(rows.size());
        rows.push_back(id);
    }
    return s;
}

/// Refines the ring alone, @p level times with forms, and keeps what lies inside its first face.
/// @throws TopologyError when the ring is not a mesh of its own
PatchStencil build_stencil(const FaceRing& ring, SchemeKind scheme, const SchemeOptions& options, int level,
                           bool snap) {
    PatchStencil s;
    Topology local = ring_topology(ring);
    s.ring_edges.resize(static_cast<std::size_t>(local.num_edges()));
    for (Index h = 0; h < local.num_faces(); ++h) {
        const auto edges = local.face_edges(h);
        const auto signs = local.face_edge_signs(h);
        for (std::size_t i = 0; i < edges.size(); ++i) {
            s.ring_edges[static_cast<std::size_t>(edges[i])] = {h, static_cast<Index>(i), double(signs[i])};
        }
    }
    RefineOptions refine;
    refine.scheme = scheme;
    refine.levels = level;
    refine.scheme_options = options;
    refine.forms = true;
    const Hierarchy hierarchy(std::move(local), refine);
    const Topology& fine = hierarchy.topology(level);
    std::vector<Index> vertex_slot(static_cast<std::size_t>(fine.num_vertices()), invalid_index);
    std::vector<Index> edge_slot(static_cast<std::size_t>(fine.num_edges()), invalid_index);
    std::vector<Index> vertices, edges, faces;
    for (Index g = 0; g < fine.num_faces(); ++g) {
        Index ancestor = g;
        for (int l = level; l >= 1; --l) {
            ancestor = hierarchy.step(l).provenance.face_parent[static_cast<std::size_t>(ancestor)];
        }
        if (ancestor != 0) {
            continue;
        }
        faces.push_back(g);
        s.fine_degree = static_cast<int>(fine.face_degree(g));
        const auto corners = fine.face_vertices(g);
        const auto sides = fine.face_edges(g);
        const auto signs = fine.face_edge_signs(g);
        for (std::size_t i = 0; i < corners.size(); ++i) {
            s.corner_vertex.push_back(row_of(corners[i], vertex_slot, vertices));
            s.corner_edge.push_back(row_of(sides[i], edge_slot, edges));
            s.corner_sign.push_back(double(signs[i]));
        }
    }
    const SparseMatrix& A0 = hierarchy.accumulated(level);
    s.vertex_rows = dense_rows(A0, vertices);
    if (snap) {
        const SparseMatrix limit = LimitBasis(fine, scheme, options).vertex_limit_matrix() * A0;
        s.position_rows = dense_rows(limit, vertices);
    }
    s.edge_rows = dense_rows(hierarchy.accumulated_form(1, level), edges);
    s.face_rows = dense_rows(hierarchy.accumulated_form(2, level), faces);
    return s;
}

// --- per-face elements ------------------------------------------------------------------------

/// One face's global ids: its ring's vertices, edges (with the sign from the ring's local
/// orientation to the global one) and faces, and its stencil.
struct FaceEntry {
    const PatchStencil* stencil = nullptr;
    std::vector<Index> vertices;
    std::vector<Index> edges;
    std::vector<double> edge_signs;
    std::vector<Index> faces;
};

/// The global ids of the ring edges of face entry @p e.
void map_ring_edges(const Topology& t, const FaceRing& ring, FaceEntry& e) {
    const auto& sources = e.stencil->ring_edges;
    e.edges.resize(sources.size());
    e.edge_signs.resize(sources.size());
    for (std::size_t le = 0; le < sources.size(); ++le) {
        const EdgeSource& src = sources[le];
        const Index face = ring.faces[static_cast<std::size_t>(src.face)];
        const auto n = static_cast<std::size_t>(t.face_degree(face));
        const std::size_t corner =
            (static_cast<std::size_t>(src.corner + ring.rotations[static_cast<std::size_t>(src.face)])) % n;
        e.edges[le] = t.face_edges(face)[corner];
        e.edge_signs[le] = src.local_sign * double(t.face_edge_signs(face)[corner]);
    }
}

/// The element matrices of one control face, n_k × n_k for k = 0, 1, 2, their lower triangles packed
/// (element_gather.h).
struct ElementBlocks {
    /// Left uninitialised: every entry is written by face_elements (zeroing 200 MiB at 20 k triangles
    /// first cost a fifth of the assembly).
    std::array<std::unique_ptr<double[]>, 3> values;
    std::array<std::vector<std::size_t>, 3> offsets;  ///< #F + 1 each
};

/// Scratch reused across the faces one thread handles.
struct Workspace {
    Eigen::Matrix<double, Eigen::Dynamic, 3> ring_points;
    Eigen::Matrix<double, Eigen::Dynamic, 3> fine_points;
    Eigen::VectorXd vertex_mass;
    RowMatrix edge_products;  ///< M_1^L|_f · A_1^L|_f
    Eigen::VectorXd face_mass;
    RowMatrix scaled;
    Eigen::MatrixXd square;  ///< an element matrix's lower triangle before it is packed
};

/// The corners of fine face g (N × 3) and their vector area.
/// @throws NumericalError naming the control face when the face is degenerate
template <int N>
Eigen::Vector3d fine_face_corners(const PatchStencil& s, Index g, Index control_face, int level, const Workspace& w,
                                  Eigen::Matrix<double, N, 3>& P) {
    const auto base = static_cast<std::size_t>(g) * N;
    for (int i = 0; i < N; ++i) {
        P.row(i) = w.fine_points.row(s.corner_vertex[base + static_cast<std::size_t>(i)]);
    }
    const Eigen::Vector3d vector_area = polygon_vector_area<N>(P);
    LIMSURF_CHECK(!polygon_is_degenerate<N>(P, vector_area.norm()), NumericalError, "a level-", level,
                  " face inside control face ", control_face,
                  " has zero area (or a non-finite vertex): the inner products need non-degenerate faces");
    return vector_area;
}

/// Adds fine face g's polygonal inner products to the workspace (the level-L M_k|_f).
template <int N>
void add_fine_face(const PatchStencil& s, Index g, Index control_face, int level, Workspace& w) {
    const auto base = static_cast<std::size_t>(g) * N;
    Eigen::Matrix<double, N, 3> P;
    const Eigen::Vector3d vector_area = fine_face_corners<N>(s, g, control_face, level, w, P);
    const PolygonElement<N> element = polygon_element<N>(P, vector_area);
    for (int i = 0; i < N; ++i) {
        w.vertex_mass(s.corner_vertex[base + static_cast<std::size_t>(i)]) += element.area / N;
    }
    for (int i = 0; i < N; ++i) {
        const Index ei = s.corner_edge[base + static_cast<std::size_t>(i)];
        for (int j = 0; j < N; ++j) {
            const std::size_t cj = base + static_cast<std::size_t>(j);
            const double m =
                s.corner_sign[base + static_cast<std::size_t>(i)] * s.corner_sign[cj] * element.one_form(i, j);
            w.edge_products.row(ei) += m * s.edge_rows.row(s.corner_edge[cj]);
        }
    }
    w.face_mass(g) = 1.0 / element.area;
}

/// Adds fine face g's share of the level-L vertex masses (|a_g| / N at each corner) to the workspace.
template <int N>
void add_fine_mass(const PatchStencil& s, Index g, Index control_face, int level, Workspace& w) {
    Eigen::Matrix<double, N, 3> P;
    const double area = fine_face_corners<N>(s, g, control_face, level, w, P).norm();
    const auto base = static_cast<std::size_t>(g) * N;
    for (int i = 0; i < N; ++i) {
        w.vertex_mass(s.corner_vertex[base + static_cast<std::size_t>(i)]) += area / N;
    }
}

/// The level-L positions inside a control face (w.fine_points, #fine vertices × 3) from the
/// control points of its ring: subdivided (Sec) or at their limit (SecSnap).
void fine_positions(const PatchStencil& s, const std::vector<Index>& ring_vertices, const Points& X0, Workspace& w) {
    const auto n0 = static_cast<Eigen::Index>(ring_vertices.size());
    w.ring_points.resize(n0, 3);
    for (Eigen::Index i = 0; i < n0; ++i) {
        w.ring_points.row(i) = X0.row(ring_vertices[static_cast<std::size_t>(i)]);
    }
    w.fine_points.noalias() = (s.position_rows.size() != 0 ? s.position_rows : s.vertex_rows) * w.ring_points;
}

/// Aᵀ B (n × n) for a symmetric product, computed on its lower triangle (in @p scratch) and
/// written to @p out packed (element_gather.h's pack_lower).
void symmetric_product(const RowMatrix& A, const RowMatrix& B, Eigen::MatrixXd& scratch, double* out) {
    const Eigen::Index n = A.cols();
    scratch.setZero(n, n);
    scratch.triangularView<Eigen::Lower>() += A.transpose() * B;
    pack_lower(scratch, static_cast<std::size_t>(n), out);
}

/// The three element matrices of control face @p f.
void face_elements(const FaceEntry& e, const Points& X0, Index f, int level, Workspace& w, ElementBlocks& out) {
    const PatchStencil& s = *e.stencil;
    fine_positions(s, e.vertices, X0, w);
    w.vertex_mass.setZero(s.vertex_rows.rows());
    w.edge_products.setZero(s.edge_rows.rows(), s.edge_rows.cols());
    w.face_mass.resize(s.face_rows.rows());
    for (Index g = 0; g < static_cast<Index>(s.face_rows.rows()); ++g) {
        if (s.fine_degree == 4) {
            add_fine_face<4>(s, g, f, level, w);
        } else {
            add_fine_face<3>(s, g, f, level, w);
        }
    }
    const auto at = static_cast<std::size_t>(f);
    w.scaled = w.vertex_mass.asDiagonal() * s.vertex_rows;
    symmetric_product(s.vertex_rows, w.scaled, w.square, out.values[0].get() + out.offsets[0][at]);
    w.scaled = w.face_mass.asDiagonal() * s.face_rows;
    symmetric_product(s.face_rows, w.scaled, w.square, out.values[2].get() + out.offsets[2][at]);
    // M_1: A_1ᵀ (M_1^L A_1), then D C D with D the signs from the ring's edge orientation to the
    // global one (products of ±1: exact).
    double* one_forms = out.values[1].get() + out.offsets[1][at];
    symmetric_product(s.edge_rows, w.edge_products, w.square, one_forms);
    const std::size_t n = e.edge_signs.size();
    for (std::size_t c = 0; c < n; ++c) {
        for (std::size_t r = c; r < n; ++r) {
            *one_forms++ *= e.edge_signs[r] * e.edge_signs[c];
        }
    }
}

// --- global gather ----------------------------------------------------------------------------

/// The rows × rows matrix Σ_f R_fᵀ C_f R_f over the ids @p ids of each face entry (element_gather.h).
SparseMatrix assemble(Index rows, const std::vector<FaceEntry>& entries, const std::vector<Index> FaceEntry::*ids,
                      const double* values, const std::vector<std::size_t>& offsets, int num_threads) {
    const auto ids_of = [&](Index f) -> const std::vector<Index>& { return entries[static_cast<std::size_t>(f)].*ids; };
    return gather_elements(rows, static_cast<Index>(entries.size()), ids_of, values, offsets, num_threads);
}

/// A stencil cached per ring connectivity.
struct CachedStencil {
    std::unique_ptr<PatchStencil> stencil;
    bool pinched = false;  ///< the ring touches itself: use the split ring
};

/// Every control face's ring and its stencil, shared by the faces with one ring connectivity.
struct Patches {
    std::unordered_map<std::vector<Index>, CachedStencil, KeyHash> cache;  ///< owns the stencils
    std::vector<FaceRing> rings;                                           ///< per control face
    std::vector<const PatchStencil*> stencils;                             ///< per control face
};

/// The rings and stencils of every control face of @p topology, or nullopt (UnsupportedError
/// when @p required) when some face's ring cannot be refined on its own.
std::optional<Patches> gather_patches(const Topology& topology, SchemeKind scheme, const SchemeOptions& options,
                                      int level, bool snap, int num_threads, bool required) {
    const Index num_faces = topology.num_faces();
    Patches patches;
    patches.rings.resize(static_cast<std::size_t>(num_faces));
    parallel_ranges(num_faces, num_threads, [&](Index begin, Index end) {
        RingGatherer gatherer(topology);
        for (Index f = begin; f < end; ++f) {
            patches.rings[static_cast<std::size_t>(f)] = gatherer.gather(f, false);
        }
    });
    // One stencil per distinct ring connectivity (a handful on a refined mesh).
    const auto stencil_of = [&](const FaceRing& ring) -> CachedStencil& {
        CachedStencil& cached = patches.cache[ring.key];
        if (!cached.stencil && !cached.pinched) {
            try {
                cached.stencil = std::make_unique<PatchStencil>(build_stencil(ring, scheme, options, level, snap));
            } catch (const TopologyError&) {
                cached.pinched = true;
            }
        }
        return cached;
    };
    patches.stencils.resize(patches.rings.size());
    RingGatherer gatherer(topology);
    for (std::size_t f = 0; f < patches.rings.size(); ++f) {
        const CachedStencil* cached = &stencil_of(patches.rings[f]);
        if (cached->pinched) {
            patches.rings[f] = gatherer.gather(static_cast<Index>(f), true);
            cached = &stencil_of(patches.rings[f]);
        }
        if (!cached->stencil) {
            LIMSURF_CHECK(!required, UnsupportedError, "the ring of face ", f,
                          " (the faces sharing a vertex with it) cannot be refined on its own; use "
                          "SecAssembly::Auto or Hierarchy");
            return std::nullopt;
        }
        patches.stencils[f] = cached->stencil.get();
    }
    return patches;
}

/// The level-L masses and positions of one block of control faces, each face's fine vertices
/// after the previous face's (a vertex on a control edge or corner appears once per face).
struct FineBlock {
    std::vector<Eigen::Index> offsets;  ///< per face of the block, + 1
    Points points;
    Eigen::VectorXd masses;  ///< the face's share of each fine vertex's polygonal mass
};

/// Fills @p block with control faces [begin, end) of @p patches.
void fine_block(const Patches& patches, const Points& X0, Index begin, Index end, int level, int num_threads,
                FineBlock& block) {
    block.offsets.assign(1, 0);
    for (Index f = begin; f < end; ++f) {
        block.offsets.push_back(block.offsets.back() +
                                patches.stencils[static_cast<std::size_t>(f)]->vertex_rows.rows());
    }
    block.points.resize(block.offsets.back(), 3);
    block.masses.resize(block.offsets.back());
    parallel_ranges(end - begin, num_threads, [&](Index first, Index last) {
        Workspace w;
        for (Index i = first; i < last; ++i) {
            const Index f = begin + i;
            const PatchStencil& s = *patches.stencils[static_cast<std::size_t>(f)];
            fine_positions(s, patches.rings[static_cast<std::size_t>(f)].vertices, X0, w);
            w.vertex_mass.setZero(s.vertex_rows.rows());
            const auto fine_faces = static_cast<Index>(s.corner_vertex.size()) / s.fine_degree;
            for (Index g = 0; g < fine_faces; ++g) {
                if (s.fine_degree == 4) {
                    add_fine_mass<4>(s, g, f, level, w);
                } else {
                    add_fine_mass<3>(s, g, f, level, w);
                }
            }
            const Eigen::Index at = block.offsets[static_cast<std::size_t>(i)];
            block.points.middleRows(at, w.fine_points.rows()) = w.fine_points;
            block.masses.segment(at, w.vertex_mass.size()) = w.vertex_mass;
        }
    });
}

}  // namespace

void require_ring_stencils(const Topology& topology, SchemeKind scheme, const SchemeOptions& options) {
    require_form_rules(topology, scheme, options);
    require_local_size(topology, max_limit_size, "SEC's ring stencils");
}

std::optional<InnerProducts> patch_inner_products(const Topology& topology, const Points& X0, SchemeKind scheme,
                                                  const SchemeOptions& options, int level, bool snap, int num_threads,
                                                  bool required) {
    std::optional<Patches> patches = gather_patches(topology, scheme, options, level, snap, num_threads, required);
    if (!patches) {
        return std::nullopt;
    }
    const Index num_faces = topology.num_faces();
    std::vector<FaceRing>& rings = patches->rings;
    std::vector<FaceEntry> entries(static_cast<std::size_t>(num_faces));
    for (std::size_t f = 0; f < rings.size(); ++f) {
        entries[f].stencil = patches->stencils[f];
    }
    ElementBlocks blocks;
    for (std::size_t k = 0; k < 3; ++k) {
        blocks.offsets[k].assign(rings.size() + 1, 0);
    }
    for (std::size_t f = 0; f < rings.size(); ++f) {
        const PatchStencil& s = *entries[f].stencil;
        const std::array<std::size_t, 3> sizes = {static_cast<std::size_t>(s.vertex_rows.cols()),
                                                  static_cast<std::size_t>(s.edge_rows.cols()),
                                                  static_cast<std::size_t>(s.face_rows.cols())};
        for (std::size_t k = 0; k < 3; ++k) {
            blocks.offsets[k][f + 1] = blocks.offsets[k][f] + packed_size(sizes[k]);
        }
    }
    for (std::size_t k = 0; k < 3; ++k) {
        const std::size_t n = blocks.offsets[k].back();
        blocks.values[k] = std::make_unique_for_overwrite<double[]>(n);
        advise_huge_pages(blocks.values[k].get(), n * sizeof(double));
    }
    parallel_ranges(num_faces, num_threads, [&](Index begin, Index end) {
        Workspace w;
        for (Index f = begin; f < end; ++f) {
            const auto at = static_cast<std::size_t>(f);
            FaceEntry& e = entries[at];
            map_ring_edges(topology, rings[at], e);
            e.vertices = std::move(rings[at].vertices);
            e.faces = std::move(rings[at].faces);
            face_elements(e, X0, f, level, w, blocks);
        }
    });
    return InnerProducts(
        assemble(topology.num_vertices(), entries, &FaceEntry::vertices, blocks.values[0].get(), blocks.offsets[0],
                 num_threads),
        assemble(topology.num_edges(), entries, &FaceEntry::edges, blocks.values[1].get(), blocks.offsets[1],
                 num_threads),
        assemble(num_faces, entries, &FaceEntry::faces, blocks.values[2].get(), blocks.offsets[2], num_threads));
}

std::optional<Eigen::VectorXd> patch_load_vector(const Topology& topology, const Points& X0, SchemeKind scheme,
                                                 const SchemeOptions& options, int level, bool snap, int num_threads,
                                                 bool required,
                                                 const std::function<Eigen::VectorXd(const Points&)>& f) {
    const std::optional<Patches> patches =
        gather_patches(topology, scheme, options, level, snap, num_threads, required);
    if (!patches) {
        return std::nullopt;
    }
    // Blocks of control faces keep the fine points small (about 20 MB at level 3 on quads) while
    // f sees many points per call.
    constexpr Index block_faces = 8192;
    Eigen::VectorXd load = Eigen::VectorXd::Zero(topology.num_vertices());
    FineBlock block;
    Eigen::VectorXd ring_load;
    for (Index begin = 0; begin < topology.num_faces(); begin += block_faces) {
        const Index end = std::min(topology.num_faces(), begin + block_faces);
        fine_block(*patches, X0, begin, end, level, num_threads, block);
        const Eigen::VectorXd values = f(block.points);
        LIMSURF_CHECK(values.size() == block.points.rows() && values.allFinite(), InputError,
                      "the right-hand side must give one finite value per point (", block.points.rows(), ")");
        // Face by face in order, so the sums do not depend on the thread count.
        for (Index face = begin; face < end; ++face) {
            const PatchStencil& s = *patches->stencils[static_cast<std::size_t>(face)];
            const Eigen::Index at = block.offsets[static_cast<std::size_t>(face - begin)];
            const Eigen::Index n = s.vertex_rows.rows();
            ring_load.noalias() =
                s.vertex_rows.transpose() * block.masses.segment(at, n).cwiseProduct(values.segment(at, n));
            const std::vector<Index>& ring = patches->rings[static_cast<std::size_t>(face)].vertices;
            for (std::size_t i = 0; i < ring.size(); ++i) {
                load(ring[i]) += ring_load(static_cast<Eigen::Index>(i));
            }
        }
    }
    return load;
}

}  // namespace limsurf::detail
