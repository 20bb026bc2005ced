// Exact enclosed volume by trilinear forms (enclosed_volume.h).
//
// Construction sorts the control mesh's elements (faces; vertices for Doo–Sabin) into
// facets, used with their control points directly, and the rest, which are refined
// locally: the faces within a few rings of them are copied into a small Topology,
// refined once or twice with the scheme's own step, and the descendants' facets take
// their control points as rows of those steps ("derived points": level-1 points are
// rows of the first step applied to the control points, level-2 points rows of the
// second applied to level-1 points; both kept sparse and restricted to the rows that
// facets need). A child vertex is trusted only when its parent element is interior to
// the copy and everything its stencil reads is trusted; when a facet needs an untrusted
// point the copy is grown and built again.
#include "limsurf/volume/enclosed_volume.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <span>
#include <thread>

#include <Eigen/Geometry>

#include "limsurf/core/error.h"
#include "limsurf/core/magnitude.h"
#include "limsurf/core/memory.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"
#include "limsurf/volume/facet_ring.h"
#include "limsurf/volume/facet_seed.h"
#include "limsurf/volume/volume_forms.h"

namespace limsurf {
namespace {

using detail::VolumeForm;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

void check_input(const Topology& topology, SchemeKind scheme, const SchemeOptions& options, Index max_type) {
    LIMSURF_CHECK(scheme == SchemeKind::CatmullClark || scheme == SchemeKind::Loop || scheme == SchemeKind::DooSabin,
                  UnsupportedError, "exact volume: no volume forms for the ", to_string(scheme),
                  " scheme (catmull-clark, loop and doo-sabin have them)");
    LIMSURF_CHECK(topology.num_faces() > 0, InputError, "exact volume: the mesh has no faces");
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK_AT(!topology.is_boundary_vertex(v), InputError, vertex_element(v),
                         "exact volume: the surface is open (vertex ", v,
                         " lies on a boundary); only a closed mesh encloses a volume");
    }
    LIMSURF_CHECK(!topology.has_sharpness(), UnsupportedError,
                  "exact volume: the mesh has creases, corners or holes; the volume forms cover the smooth rules only");
    LIMSURF_CHECK(scheme != SchemeKind::CatmullClark || options.triangles == TriangleSubdivision::CatmullClark,
                  UnsupportedError, "exact volume: the smooth-triangle Catmull–Clark rule has no volume forms");
    if (scheme == SchemeKind::Loop) {
        for (Index f = 0; f < topology.num_faces(); ++f) {
            LIMSURF_CHECK_AT(topology.face_degree(f) == 3, UnsupportedError, face_element(f),
                             "exact volume: Loop needs triangles, face ", f, " has ", topology.face_degree(f),
                             " corners");
        }
    }
    // Facet types are the valences and face degrees: forms exist from 3 on (a valence-2 vertex,
    // as in a two-face "pillow", has none), and are generated up to the limit (each costs
    // O(type⁴) operations per squaring of its series).
    for (Index v = 0; v < topology.num_vertices(); ++v) {
        LIMSURF_CHECK_AT(topology.valence(v) >= 3, UnsupportedError, vertex_element(v), "exact volume: vertex ", v,
                         " has valence ", topology.valence(v), "; the volume forms need valences of at least 3");
    }
    require_local_size(topology, max_type, "exact volume");
}

/// A copy of the faces around some elements, as its own Topology.
struct Region {
    Topology topology;
    std::vector<Index> global_vertex;  ///< per local vertex
    std::vector<Index> local_element;  ///< per requested element: its local face (vertex, Doo–Sabin)
};

/// Number of separate fans of marked faces around v (0: none; 1 with all marked: the full ring).
int fan_runs(const Topology& t, Index v, const std::vector<char>& in) {
    const auto faces = t.vertex_faces(v);
    const std::size_t n = faces.size();
    int runs = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (in[at(faces[i])] && !in[at(faces[(i + n - 1) % n])]) {
            ++runs;
        }
    }
    return runs;
}

Region make_region(const Topology& t, SchemeKind scheme, const std::vector<Index>& elements, int radius) {
    std::vector<char> face_in(at(t.num_faces()), 0);
    std::vector<char> seen(at(t.num_vertices()), 0);
    std::vector<Index> frontier;
    for (const Index e : elements) {
        if (scheme == SchemeKind::DooSabin) {
            frontier.push_back(e);
        } else {
            frontier.insert(frontier.end(), t.face_vertices(e).begin(), t.face_vertices(e).end());
        }
    }
    for (const Index v : frontier) {
        seen[at(v)] = 1;
    }
    for (int r = 0; r < radius; ++r) {
        std::vector<Index> next;
        for (const Index v : frontier) {
            for (const Index f : t.vertex_faces(v)) {
                if (face_in[at(f)]) {
                    continue;
                }
                face_in[at(f)] = 1;
                for (const Index u : t.face_vertices(f)) {
                    if (!seen[at(u)]) {
                        seen[at(u)] = 1;
                        next.push_back(u);
                    }
                }
            }
        }
        frontier = std::move(next);
    }
    // A union of fans can pinch at a rim vertex (two fans meeting at one vertex): close such
    // vertices' rings so that the copy is a manifold.
    for (bool changed = true; changed;) {
        changed = false;
        for (Index f = 0; f < t.num_faces(); ++f) {
            if (!face_in[at(f)]) {
                continue;
            }
            for (const Index v : t.face_vertices(f)) {
                if (fan_runs(t, v, face_in) > 1) {
                    for (const Index g : t.vertex_faces(v)) {
                        changed = changed || !face_in[at(g)];
                        face_in[at(g)] = 1;
                    }
                }
            }
        }
    }
    Region region;
    std::vector<Index> local(at(t.num_vertices()), invalid_index);
    std::vector<Index> local_face(at(t.num_faces()), invalid_index);
    std::vector<std::vector<Index>> faces;
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (!face_in[at(f)]) {
            continue;
        }
        local_face[at(f)] = static_cast<Index>(faces.size());
        std::vector<Index> corners;
        for (const Index v : t.face_vertices(f)) {
            if (local[at(v)] == invalid_index) {
                local[at(v)] = static_cast<Index>(region.global_vertex.size());
                region.global_vertex.push_back(v);
            }
            corners.push_back(local[at(v)]);
        }
        faces.push_back(std::move(corners));
    }
    region.topology = Topology::from_polygons(static_cast<Index>(region.global_vertex.size()), faces);
    for (const Index e : elements) {
        region.local_element.push_back(scheme == SchemeKind::DooSabin ? local[at(e)] : local_face[at(e)]);
    }
    return region;
}

/// Which child vertices of @p level have the rule and the inputs they have in the whole mesh.
std::vector<char> trusted_children(const Topology& parent, const Level& level, SchemeKind scheme,
                                   const std::vector<char>& trusted_parent) {
    const Index n = level.topology.num_vertices();
    std::vector<char> out(at(n), 0);
    for (Index c = 0; c < n; ++c) {
        bool ok = true;
        for (SparseMatrix::InnerIterator it(level.S0, c); it && ok; ++it) {
            ok = trusted_parent[at(static_cast<Index>(it.col()))] != 0;
        }
        if (ok && scheme == SchemeKind::DooSabin) {
            const auto pc = detail::doo_sabin_parent_corner(parent, c);
            for (const Index v : parent.face_vertices(pc.face)) {
                ok = ok && !parent.is_boundary_vertex(v);
            }
        } else if (ok) {
            const Index p = level.provenance.vertex_parent[at(c)];
            switch (level.provenance.vertex_parent_kind[at(c)]) {
            case ParentKind::Vertex:
                ok = !parent.is_boundary_vertex(p);
                break;
            case ParentKind::Edge:
                ok = !parent.is_boundary_edge(p);
                break;
            case ParentKind::Face:
                break;
            }
        }
        out[at(c)] = ok ? 1 : 0;
    }
    return out;
}

/// Facets, each with its form and its points, while they are collected: a block per classifying
/// worker, one for the facets of subdivided elements.
struct FacetBlock {
    std::vector<std::uint32_t> form;  ///< per facet: index into Impl::forms (its type while classifying)
    std::vector<Index> offset{0};     ///< per facet + 1: offsets into points
    std::vector<Index> points;        ///< < V: control vertex; >= V: derived point V + d
    [[nodiscard]] Index size() const { return static_cast<Index>(form.size()); }
    void add(std::uint32_t f, std::span<const Index> facet_points) {
        form.push_back(f);
        points.insert(points.end(), facet_points.begin(), facet_points.end());
        offset.push_back(static_cast<Index>(points.size()));
    }
};

/// The facets as evaluated, in fixed chunks of facets_per_chunk: a chunk reads its points into a
/// table of its own (each point once) and adds its facets' gradients there, so that its scatter
/// stays in cache and no two chunks write the same memory; a point's gradient is then the sum of
/// its entries in the chunks' tables, in chunk order. The chunks do not depend on the number of
/// threads, so neither do the bits of the volume or of its gradient.
struct FacetTable {
    static constexpr Index facets_per_chunk = 1024;
    std::vector<std::uint32_t> form;     ///< per facet: index into Impl::forms
    std::vector<Index> offset{0};        ///< per facet + 1: into local
    std::vector<std::uint32_t> local;    ///< per facet point: its row in the chunk's table
    std::vector<Index> chunk_offset{0};  ///< per chunk + 1: into chunk_points
    std::vector<Index> chunk_points;     ///< rows of the point table (control, then derived points)
    std::vector<Index> row_offset;       ///< per point-table row + 1: into row_entries
    std::vector<Index> row_entries;      ///< the row's entries in chunk_points, in chunk order

    [[nodiscard]] Index num_facets() const { return static_cast<Index>(form.size()); }
    [[nodiscard]] Index num_chunks() const { return static_cast<Index>(chunk_offset.size()) - 1; }
    /// Lays out @p blocks' facets in order; their points are rows < @p num_rows.
    void lay_out(const std::vector<FacetBlock>& blocks, Index num_rows);
};

void FacetTable::lay_out(const std::vector<FacetBlock>& blocks, Index num_rows) {
    std::vector<Index> slot_of(at(num_rows), invalid_index);
    const auto close_chunk = [&] {
        for (std::size_t k = at(chunk_offset.back()); k < chunk_points.size(); ++k) {
            slot_of[at(chunk_points[k])] = invalid_index;
        }
        chunk_offset.push_back(static_cast<Index>(chunk_points.size()));
    };
    for (const FacetBlock& block : blocks) {
        for (Index f = 0; f < block.size(); ++f) {
            if (num_facets() > 0 && num_facets() % facets_per_chunk == 0) {
                close_chunk();
            }
            form.push_back(block.form[at(f)]);
            const Index first = chunk_offset.back();
            for (Index k = block.offset[at(f)]; k < block.offset[at(f) + 1]; ++k) {
                Index& slot = slot_of[at(block.points[at(k)])];
                if (slot == invalid_index) {
                    slot = static_cast<Index>(chunk_points.size()) - first;
                    chunk_points.push_back(block.points[at(k)]);
                }
                local.push_back(static_cast<std::uint32_t>(slot));
            }
            offset.push_back(static_cast<Index>(local.size()));
        }
    }
    if (num_facets() > 0) {
        close_chunk();
    }
    // The transpose: entries of each row, in chunk order.
    row_offset.assign(at(num_rows) + 1, 0);
    for (const Index r : chunk_points) {
        ++row_offset[at(r) + 1];
    }
    for (std::size_t r = 0; r < at(num_rows); ++r) {
        row_offset[r + 1] += row_offset[r];
    }
    row_entries.resize(chunk_points.size());
    std::vector<Index> fill(row_offset.begin(), row_offset.end() - 1);
    for (std::size_t k = 0; k < chunk_points.size(); ++k) {
        row_entries[at(fill[at(chunk_points[k])]++)] = static_cast<Index>(k);
    }
}

/// Workers for @p items items: the requested number (0: hardware concurrency), at most one per 1024
/// items (a facet with its gradient takes 0.1–1 µs; starting a thread, some 50 µs).
unsigned worker_count(int requested, Index items) {
    const unsigned wanted =
        requested > 0 ? static_cast<unsigned>(requested) : std::max(1U, std::thread::hardware_concurrency());
    return std::max(1U, std::min<unsigned>(wanted, static_cast<unsigned>(items / 1024)));
}

/// Runs work(0..threads-1), on threads when there is more than one.
template <class Work>
void run_parallel(unsigned threads, Work&& work) {
    if (threads == 1) {
        work(0U);
        return;
    }
    std::vector<std::thread> pool;
    for (unsigned w = 0; w < threads; ++w) {
        pool.emplace_back(work, w);
    }
    for (auto& t : pool) {
        t.join();
    }
}

/// Points in row-major order (x, y, z of a point adjacent in memory).
using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

}  // namespace

struct EnclosedVolume::Impl {
    SchemeKind scheme = SchemeKind::CatmullClark;
    Index num_vertices = 0;
    VolumeOptions options;
    VolumeStatistics statistics;
    std::vector<VolumeForm> forms;
    std::map<int, std::size_t> form_of_type;
    FacetTable facets;
    /// The refined points facets need, as rows of the refinement steps of the local copy:
    /// level-1 points = first_level · X (n1 × V), level-2 points = second_level · level-1 points.
    SparseMatrix first_level;
    SparseMatrix second_level;
    int last_type = -1;  ///< cached_form_index's cache
    std::uint32_t last_form = 0;

    std::uint32_t form_index(int type) {
        const auto it = form_of_type.find(type);
        if (it != form_of_type.end()) {
            return static_cast<std::uint32_t>(it->second);
        }
        LIMSURF_CHECK(detail::is_shipped(scheme, type) || type <= options.max_generated_type, UnsupportedError,
                      "exact volume: facet type ", type, " (a valence or face degree) is above the limit ",
                      options.max_generated_type, " for generating its volume form");
        if (!detail::is_shipped(scheme, type)) {
            statistics.generated_types.push_back(type);
        }
        forms.push_back(detail::load_volume_form(scheme, type));
        form_of_type.emplace(type, forms.size() - 1);
        statistics.max_type = std::max(statistics.max_type, type);
        return static_cast<std::uint32_t>(forms.size() - 1);
    }

    std::uint32_t cached_form_index(int type) {
        if (type != last_type) {
            last_type = type;
            last_form = form_index(type);
        }
        return last_form;
    }

    /// Refines the region around @p elements into @p block (and first_level, second_level); false
    /// when the region was too small.
    bool subdivide(const Topology& t, const std::vector<Index>& elements, int radius, FacetBlock& block);

    double evaluate(const Points& X, Points* gradient) const;
};

bool EnclosedVolume::Impl::subdivide(const Topology& t, const std::vector<Index>& elements, int radius,
                                     FacetBlock& block) {
    const Region region = make_region(t, scheme, elements, radius);
    const Topology& t0 = region.topology;
    const Level level1 = refine(t0, scheme);
    const std::vector<char> trusted0(at(t0.num_vertices()), 1);
    const std::vector<char> trusted1 = trusted_children(t0, level1, scheme, trusted0);
    Level level2;
    std::vector<char> trusted2;
    struct Pending {
        int type;
        int level;
        std::vector<Index> ring;  ///< vertices of level `level` of the copy
    };
    std::vector<Pending> pending;
    for (const Index e : region.local_element) {
        for (const Index child : detail::child_elements(t0, scheme, e)) {
            if (auto ring = detail::typed_facet(level1.topology, scheme, child)) {
                for (const Index p : ring->points) {
                    if (!trusted1[at(p)]) {
                        return false;
                    }
                }
                pending.push_back({ring->type, 1, std::move(ring->points)});
                continue;
            }
            if (level2.topology.num_vertices() == 0) {
                level2 = refine(level1.topology, scheme);
                trusted2 = trusted_children(level1.topology, level2, scheme, trusted1);
            }
            for (const Index grandchild : detail::child_elements(level1.topology, scheme, child)) {
                auto ring = detail::typed_facet(level2.topology, scheme, grandchild);
                LIMSURF_CHECK(ring.has_value(), UnsupportedError,
                              "exact volume: an element is not a facet after two subdivisions (internal error)");
                for (const Index p : ring->points) {
                    if (!trusted2[at(p)]) {
                        return false;
                    }
                }
                pending.push_back({ring->type, 2, std::move(ring->points)});
            }
        }
    }
    // The points the facets need, level by level: level-2 points read level-1 points.
    std::vector<Index> id1(at(level1.topology.num_vertices()), invalid_index);
    std::vector<Index> id2(at(level2.topology.num_vertices()), invalid_index);
    Index n1 = 0;
    Index n2 = 0;
    for (const Pending& p : pending) {
        for (const Index v : p.ring) {
            Index& id = p.level == 1 ? id1[at(v)] : id2[at(v)];
            if (id == invalid_index) {
                id = p.level == 1 ? n1++ : n2++;
            }
        }
    }
    std::vector<Index> rows2(at(n2));
    for (Index v = 0; v < static_cast<Index>(id2.size()); ++v) {
        if (id2[at(v)] != invalid_index) {
            rows2[at(id2[at(v)])] = v;
            for (SparseMatrix::InnerIterator it(level2.S0, v); it; ++it) {
                Index& id = id1[at(static_cast<Index>(it.col()))];
                if (id == invalid_index) {
                    id = n1++;
                }
            }
        }
    }
    std::vector<Eigen::Triplet<double>> triplets1;
    for (Index v = 0; v < static_cast<Index>(id1.size()); ++v) {
        if (id1[at(v)] != invalid_index) {
            for (SparseMatrix::InnerIterator it(level1.S0, v); it; ++it) {
                triplets1.emplace_back(id1[at(v)], region.global_vertex[at(static_cast<Index>(it.col()))], it.value());
            }
        }
    }
    std::vector<Eigen::Triplet<double>> triplets2;
    for (Index r = 0; r < n2; ++r) {
        for (SparseMatrix::InnerIterator it(level2.S0, rows2[at(r)]); it; ++it) {
            triplets2.emplace_back(r, id1[at(static_cast<Index>(it.col()))], it.value());
        }
    }
    first_level.resize(n1, num_vertices);
    first_level.setFromTriplets(triplets1.begin(), triplets1.end());
    second_level.resize(n2, n1);
    second_level.setFromTriplets(triplets2.begin(), triplets2.end());
    // Facet points: control vertices 0..V-1, then the level-1 points, then the level-2 points.
    std::vector<Index> facet_points;
    for (const Pending& p : pending) {
        facet_points.clear();
        for (const Index v : p.ring) {
            facet_points.push_back(num_vertices + (p.level == 1 ? id1[at(v)] : n1 + id2[at(v)]));
        }
        block.add(cached_form_index(p.type), std::span<const Index>(facet_points));
        ++statistics.subdivided_facets;
    }
    return true;
}

EnclosedVolume::EnclosedVolume(const Topology& topology, SchemeKind scheme, const SchemeOptions& options,
                               const VolumeOptions& volume_options)
    : impl_(std::make_unique<Impl>()) {
    check_input(topology, scheme, options, volume_options.max_generated_type);
    Impl& d = *impl_;
    d.scheme = scheme;
    d.num_vertices = topology.num_vertices();
    d.options = volume_options;
    // Classify the elements in parallel (read-only walks), then append their facets in order.
    const Index count = detail::num_facet_elements(topology, scheme);
    const unsigned threads = worker_count(volume_options.num_threads, count);
    std::vector<FacetBlock> blocks(threads);
    std::vector<std::vector<Index>> untyped_parts(threads);
    run_parallel(threads, [&](unsigned w) {
        FacetBlock& block = blocks[w];
        const Index begin = count * static_cast<Index>(w) / static_cast<Index>(threads);
        const Index end = count * static_cast<Index>(w + 1) / static_cast<Index>(threads);
        for (Index e = begin; e < end; ++e) {
            if (const auto ring = detail::typed_facet(topology, scheme, e)) {
                block.add(static_cast<std::uint32_t>(ring->type), ring->points);
            } else {
                untyped_parts[w].push_back(e);
            }
        }
    });
    // Types to forms (loading or generating each form once).
    std::vector<Index> untyped;
    for (unsigned w = 0; w < threads; ++w) {
        for (std::uint32_t& form : blocks[w].form) {
            form = d.cached_form_index(static_cast<int>(form));
        }
        d.statistics.direct_facets += blocks[w].size();
        untyped.insert(untyped.end(), untyped_parts[w].begin(), untyped_parts[w].end());
    }
    d.statistics.subdivided_elements = static_cast<Index>(untyped.size());
    if (!untyped.empty()) {
        bool done = false;
        for (int radius = 3; radius <= 8 && !done; ++radius) {
            // Start over at each radius (a failed attempt may have added some facets).
            FacetBlock block;
            d.statistics.subdivided_facets = 0;
            done = d.subdivide(topology, untyped, radius, block);
            if (done) {
                blocks.push_back(std::move(block));
            }
        }
        LIMSURF_CHECK(done, UnsupportedError,
                      "exact volume: could not isolate the irregular elements (internal error)");
    }
    d.facets.lay_out(blocks, d.num_vertices + static_cast<Index>(d.first_level.rows() + d.second_level.rows()));
}

EnclosedVolume::~EnclosedVolume() = default;
EnclosedVolume::EnclosedVolume(EnclosedVolume&&) noexcept = default;
EnclosedVolume& EnclosedVolume::operator=(EnclosedVolume&&) noexcept = default;

double EnclosedVolume::Impl::evaluate(const Points& X, Points* gradient) const {
    LIMSURF_CHECK(X.rows() == num_vertices, InputError, "exact volume: ", X.rows(), " points for ", num_vertices,
                  " vertices");
    LIMSURF_CHECK(X.allFinite(), InputError, "exact volume: the control points have a non-finite coordinate");
    // About the mean control point: the sum is translation invariant for a closed surface, and
    // small coordinates keep the facets' contributions from cancelling. In units of 2^e (exact):
    // the products of three coordinates neither overflow nor underflow for a mesh of any size; the
    // volume is scaled back by 2^3e, the gradient by 2^2e. Control and derived points go into one
    // row-major table, so that a facet reads 3 adjacent doubles per point.
    const int e = magnitude_exponent(X);
    const Points Y = times_power_of_two(X, -e);
    const Eigen::RowVector3d o = Y.colwise().mean();
    const Index V = num_vertices;
    const auto n1 = static_cast<Index>(first_level.rows());
    const auto n2 = static_cast<Index>(second_level.rows());
    const Index D = n1 + n2;
    RowPoints all(V + D, 3);
    all.topRows(V) = Y.rowwise() - o;
    if (n1 > 0) {
        // Refinement rows sum to 1: they commute with the shift by o.
        all.middleRows(V, n1) = first_level * all.topRows(V);
    }
    if (n2 > 0) {
        all.bottomRows(n2) = second_level * all.middleRows(V, n1);
    }
    const double* table = all.data();
    // Per chunk: its points' rows of `all`, its facets' volumes summed in facet order, and its
    // points' gradients summed in facet order into its own rows of chunk_gradient.
    const Index num_chunks = facets.num_chunks();
    std::vector<double> chunk_sums(at(num_chunks), 0.0);
    std::vector<double> chunk_gradient(gradient != nullptr ? 3 * facets.chunk_points.size() : 0, 0.0);
    const unsigned workers = std::min(worker_count(options.num_threads, facets.num_facets()),
                                      static_cast<unsigned>(std::max<Index>(num_chunks, 1)));
    run_parallel(workers, [&](unsigned w) {
        const Index first_chunk = num_chunks * static_cast<Index>(w) / static_cast<Index>(workers);
        const Index last_chunk = num_chunks * static_cast<Index>(w + 1) / static_cast<Index>(workers);
        std::vector<double> points;  // the chunk's rows of `all`
        std::vector<double> p;
        std::vector<double> g;
        for (Index c = first_chunk; c < last_chunk; ++c) {
            const Index first_point = facets.chunk_offset[at(c)];
            const Index num_points = facets.chunk_offset[at(c) + 1] - first_point;
            points.resize(3 * at(num_points));
            for (Index k = 0; k < num_points; ++k) {
                const double* q = table + 3 * at(facets.chunk_points[at(first_point + k)]);
                std::copy(q, q + 3, points.begin() + 3 * k);
            }
            double* chunk_g = gradient != nullptr ? chunk_gradient.data() + 3 * at(first_point) : nullptr;
            double sum = 0.0;
            const Index last_facet = std::min(facets.num_facets(), (c + 1) * FacetTable::facets_per_chunk);
            for (Index f = c * FacetTable::facets_per_chunk; f < last_facet; ++f) {
                const VolumeForm& form = forms[facets.form[at(f)]];
                const std::uint32_t* local = facets.local.data() + facets.offset[at(f)];
                const auto m = at(form.size);
                p.resize(3 * m);
                for (std::size_t a = 0; a < m; ++a) {
                    std::copy_n(points.begin() + 3 * local[a], 3, p.begin() + 3 * a);
                }
                if (chunk_g == nullptr) {
                    sum += form.evaluate(p.data(), nullptr);
                    continue;
                }
                g.assign(p.size(), 0.0);
                sum += form.evaluate(p.data(), g.data());
                for (std::size_t a = 0; a < m; ++a) {
                    double* row = chunk_g + 3 * local[a];
                    row[0] += g[3 * a];
                    row[1] += g[3 * a + 1];
                    row[2] += g[3 * a + 2];
                }
            }
            chunk_sums[at(c)] = sum;
        }
    });
    double volume = 0.0;
    for (const double s : chunk_sums) {
        volume += s;
    }
    if (gradient != nullptr) {
        // Each row from +0, its chunks in order.
        RowPoints g(V + D, 3);
        const unsigned row_workers = worker_count(options.num_threads, V + D);
        run_parallel(row_workers, [&](unsigned w) {
            const Index begin = (V + D) * static_cast<Index>(w) / static_cast<Index>(row_workers);
            const Index end = (V + D) * static_cast<Index>(w + 1) / static_cast<Index>(row_workers);
            for (Index r = begin; r < end; ++r) {
                double sum[3] = {0.0, 0.0, 0.0};
                for (Index k = facets.row_offset[at(r)]; k < facets.row_offset[at(r) + 1]; ++k) {
                    const double* entry = chunk_gradient.data() + 3 * at(facets.row_entries[at(k)]);
                    sum[0] += entry[0];
                    sum[1] += entry[1];
                    sum[2] += entry[2];
                }
                g(r, 0) = sum[0];
                g(r, 1) = sum[1];
                g(r, 2) = sum[2];
            }
        });
        if (n2 > 0) {
            g.middleRows(V, n1) += second_level.transpose() * g.bottomRows(n2);
        }
        if (n1 > 0) {
            g.topRows(V) += first_level.transpose() * g.middleRows(V, n1);
        }
        *gradient = times_power_of_two(g.topRows(V), 2 * e);
        LIMSURF_CHECK(gradient->allFinite(), NumericalError,
                      "exact volume: the gradient overflows a double: the mesh is too large; rescale its coordinates");
    }
    return scale_back(volume, 3 * e, "enclosed volume");
}

double EnclosedVolume::volume(const Points& X) const {
    return impl_->evaluate(X, nullptr);
}

Points EnclosedVolume::gradient(const Points& X) const {
    Points g;
    impl_->evaluate(X, &g);
    return g;
}

double EnclosedVolume::volume_and_gradient(const Points& X, Points& gradient) const {
    return impl_->evaluate(X, &gradient);
}

Index EnclosedVolume::num_vertices() const noexcept {
    return impl_->num_vertices;
}

SchemeKind EnclosedVolume::scheme() const noexcept {
    return impl_->scheme;
}

const VolumeStatistics& EnclosedVolume::statistics() const noexcept {
    return impl_->statistics;
}

std::vector<double> volume_form_coefficients(SchemeKind scheme, int type) {
    LIMSURF_CHECK(scheme == SchemeKind::CatmullClark || scheme == SchemeKind::Loop || scheme == SchemeKind::DooSabin,
                  UnsupportedError, "no volume forms for the ", to_string(scheme), " scheme");
    LIMSURF_CHECK(type >= 3, UnsupportedError, "facet type ", type, " (valences and face degrees start at 3)");
    return detail::load_volume_form(scheme, type).coefficients;
}

double exact_volume(const ControlMesh& mesh, SchemeKind scheme) {
    return EnclosedVolume(mesh.topology(), scheme).volume(mesh.positions());
}

double polyhedral_volume(const Topology& topology, const Points& X) {
    LIMSURF_CHECK(X.rows() == topology.num_vertices(), InputError, "polyhedral volume: ", X.rows(), " points for ",
                  topology.num_vertices(), " vertices");
    // In units of 2^e about the mean point, as EnclosedVolume::volume.
    const int e = magnitude_exponent(X);
    const Points Y = times_power_of_two(X, -e);
    const Eigen::RowVector3d o = Y.rows() > 0 ? Eigen::RowVector3d(Y.colwise().mean()) : Eigen::RowVector3d::Zero();
    double sum = 0.0;
    for (Index f = 0; f < topology.num_faces(); ++f) {
        const auto v = topology.face_vertices(f);
        const Eigen::Vector3d a = (Y.row(v[0]) - o).transpose();
        for (std::size_t k = 1; k + 1 < v.size(); ++k) {
            const Eigen::Vector3d b = (Y.row(v[k]) - o).transpose();
            const Eigen::Vector3d c = (Y.row(v[k + 1]) - o).transpose();
            sum += a.dot(b.cross(c));
        }
    }
    return scale_back(sum / 6.0, 3 * e, "polyhedral volume");
}

std::vector<PolyhedralVolume> polyhedral_volumes(const Topology& topology, const Points& X, SchemeKind scheme,
                                                 int levels, Index max_faces, const SchemeOptions& options) {
    LIMSURF_CHECK(levels >= 0 && levels <= 16, InputError, "polyhedral volumes: levels must be 0..16 (got ", levels,
                  ")");
    std::vector<PolyhedralVolume> out{{0, topology.num_faces(), polyhedral_volume(topology, X)}};
    RefineOptions step;
    step.scheme = scheme;
    step.levels = 1;
    step.scheme_options = options;
    FinestLevel level;  // the last level refined; the first step reads the caller's mesh, not a copy
    const Topology* t = &topology;
    const Points* P = &X;
    for (int l = 1; l <= levels; ++l) {
        const std::vector<LevelSize> next = predict_sizes(*t, scheme, 1);
        if (next.back().faces > max_faces || estimated_finest_peak_bytes(next, false) > default_memory_budget()) {
            break;
        }
        level = refine_finest(*t, *P, step);
        t = &level.topology;
        P = &level.positions;
        out.push_back({l, t->num_faces(), polyhedral_volume(*t, *P)});
    }
    return out;
}

}  // namespace limsurf
