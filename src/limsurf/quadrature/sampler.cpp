#include "limsurf/quadrature/sampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>

#include "limsurf/core/error.h"
#include "limsurf/core/huge_page_allocator.h"
#include "limsurf/core/parallel.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/quadrature/rules.h"

namespace limsurf {
namespace {

using Vec2 = Eigen::Vector2d;

/// A tile of a ptex domain: a square or a triangle given by its corners (3 or 4).
struct Tile {
    std::array<Vec2, 4> corner;
    int num_corners = 4;
    int level = 0;
};

/// True where the limit surface is not a plain polynomial patch around control vertex v.
/// A boundary vertex with half the regular number of faces (2 quads, 3 triangles) is a
/// regular boundary: its patches are B-spline/box-spline patches with phantom points.
/// An interior vertex of the regular valence crossed by one infinitely sharp crease (two sharp edges
/// opposite each other) is regular too: each side is a B-spline patch with phantom points beyond
/// the crease, as beyond a boundary (iga-with-catmull-clark §4).
bool is_irregular_vertex(const Topology& t, Index v, int regular_valence) {
    const auto faces = static_cast<int>(t.vertex_faces(v).size());
    const bool regular = t.is_boundary_vertex(v) ? 2 * faces == regular_valence : faces == regular_valence;
    if (!regular || t.vertex_sharpness(v) > 0.0) {
        return true;
    }
    const auto edges = t.vertex_edges(v);
    std::vector<std::size_t> sharp;
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const double s = t.edge_sharpness(edges[i]);
        if (s > 0.0 && (s < infinite_sharpness || t.is_boundary_vertex(v))) {
            return true;  // semi-sharp creases decay over levels: not a stationary patch
        }
        if (s > 0.0) {
            sharp.push_back(i);
        }
    }
    return !(sharp.empty() ||
             (sharp.size() == 2 && 2 * (sharp[1] - sharp[0]) == edges.size()));  // a straight-through crease
}

/// Parameter points of the irregular corners of ptex face p.
std::vector<Vec2> irregular_corners(const LimitBasis& basis, Index p) {
    const Topology& t = basis.topology();
    const PtexFace ptex = basis.ptex_face(p);
    const auto fv = t.face_vertices(ptex.control_face);
    const Index n = static_cast<Index>(fv.size());
    std::vector<Vec2> corners;
    if (basis.domain() == ParameterDomain::Triangle) {
        const std::array<Vec2, 3> at{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
        for (int i = 0; i < 3; ++i) {
            if (is_irregular_vertex(t, fv[static_cast<std::size_t>(i)], 6)) {
                corners.push_back(at[static_cast<std::size_t>(i)]);
            }
        }
        return corners;
    }
    const std::array<Vec2, 4> at{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
    if (ptex.corner < 0) {
        for (int i = 0; i < 4; ++i) {
            if (is_irregular_vertex(t, fv[static_cast<std::size_t>(i)], 4)) {
                corners.push_back(at[static_cast<std::size_t>(i)]);
            }
        }
        return corners;
    }
    // Sub-face k of an n-gon: (0,0) = v_k, (1,1) = the face point (valence n != 4),
    // (1,0) and (0,1) = points of the edges (v_k, v_k+1) and (v_k-1, v_k), irregular on a boundary or crease.
    const Index k = ptex.corner;
    const Index vk = fv[static_cast<std::size_t>(k)];
    if (is_irregular_vertex(t, vk, 4)) {
        corners.push_back(at[0]);
    }
    corners.push_back(at[2]);
    const auto edge_irregular = [&](Index a, Index b) {
        const Index e = t.find_edge(a, b);
        return e == invalid_index || t.is_boundary_edge(e) || t.edge_sharpness(e) > 0.0;
    };
    if (edge_irregular(vk, fv[static_cast<std::size_t>((k + 1) % n)])) {
        corners.push_back(at[1]);
    }
    if (edge_irregular(fv[static_cast<std::size_t>((k + n - 1) % n)], vk)) {
        corners.push_back(at[3]);
    }
    return corners;
}

bool touches(const Tile& tile, const std::vector<Vec2>& points) {
    for (int i = 0; i < tile.num_corners; ++i) {
        for (const Vec2& p : points) {
            if (tile.corner[static_cast<std::size_t>(i)] == p) {  // dyadic coordinates: exact
                return true;
            }
        }
    }
    return false;
}

/// The 4 children of a tile: quadtree split of a square, 1-to-4 split of a triangle.
std::array<Tile, 4> split(const Tile& t) {
    std::array<Tile, 4> out;
    const auto& c = t.corner;
    if (t.num_corners == 4) {
        const Vec2 o = c[0];
        const double h = (c[1] - c[0]).x() / 2.0;
        for (int j = 0; j < 2; ++j) {
            for (int i = 0; i < 2; ++i) {
                Tile& s = out[static_cast<std::size_t>(2 * j + i)];
                const Vec2 a = o + Vec2(i * h, j * h);
                s.corner = {a, a + Vec2(h, 0), a + Vec2(h, h), a + Vec2(0, h)};
                s.num_corners = 4;
                s.level = t.level + 1;
            }
        }
        return out;
    }
    const Vec2 ab = (c[0] + c[1]) / 2.0;
    const Vec2 bc = (c[1] + c[2]) / 2.0;
    const Vec2 ca = (c[2] + c[0]) / 2.0;
    const std::array<std::array<Vec2, 3>, 4> tris{{{c[0], ab, ca}, {ab, c[1], bc}, {ca, bc, c[2]}, {bc, ca, ab}}};
    for (std::size_t i = 0; i < 4; ++i) {
        out[i].corner = {tris[i][0], tris[i][1], tris[i][2], Vec2::Zero()};
        out[i].num_corners = 3;
        out[i].level = t.level + 1;
    }
    return out;
}

/// Maps the rule onto @p tile (affine map from the reference square / triangle).
void place_rule(const QuadratureRule& rule, const Tile& tile, Index face, QuadratureSamples& out) {
    const Vec2 o = tile.corner[0];
    const Vec2 e1 = tile.corner[1] - o;
    const Vec2 e2 = (tile.num_corners == 4 ? tile.corner[3] : tile.corner[2]) - o;
    const double jacobian = std::abs(e1.x() * e2.y() - e1.y() * e2.x());
    for (int q = 0; q < rule.num_points(); ++q) {
        const auto i = static_cast<std::size_t>(q);
        const Vec2 x = o + rule.u[i] * e1 + rule.v[i] * e2;
        out.points.push_back({face, x.x(), x.y()});
        out.weights.push_back(rule.weight[i] * jacobian);
    }
}

void place_tiles(const QuadratureRule& rule, const Tile& tile, Index face, const std::vector<Vec2>& irregular,
                 int max_level, QuadratureSamples& out) {
    if (tile.level < max_level && touches(tile, irregular)) {
        for (const Tile& child : split(tile)) {
            place_tiles(rule, child, face, irregular, max_level, out);
        }
        return;
    }
    place_rule(rule, tile, face, out);
}

}  // namespace

LimitSampler::LimitSampler(const LimitBasis& basis, int degree, int subdivide_near_extraordinary)
    : LimitSampler(basis, SamplerOptions{degree, subdivide_near_extraordinary, 0}) {}

LimitSampler::LimitSampler(const LimitBasis& basis, const SamplerOptions& options)
    : LimitSampler(basis, options, 0, basis.num_ptex_faces()) {}

QuadratureSamples quadrature_samples(const LimitBasis& basis, const SamplerOptions& options, Index first_ptex_face,
                                     Index last_ptex_face) {
    LIMSURF_CHECK(0 <= first_ptex_face && first_ptex_face <= last_ptex_face && last_ptex_face <= basis.num_ptex_faces(),
                  InputError, "ptex faces [", first_ptex_face, ", ", last_ptex_face, ") are not within the ",
                  basis.num_ptex_faces(), " ptex faces of the surface");
    LIMSURF_CHECK(options.subdivide_near_extraordinary >= 0 && options.subdivide_near_extraordinary <= 30, InputError,
                  "tile levels near extraordinary vertices must be in 0..30, not ",
                  options.subdivide_near_extraordinary);
    const bool quads = basis.domain() == ParameterDomain::Quad;
    const int max_degree = quads ? max_square_rule_degree : max_triangle_rule_degree;
    LIMSURF_CHECK(options.degree >= 1 && options.degree <= max_degree, InputError,
                  "the quadrature degree per tile must be in 1..", max_degree, " on ", quads ? "quad" : "triangle",
                  " ptex faces, not ", options.degree);
    const QuadratureRule rule = quads ? square_rule(options.degree) : triangle_rule(options.degree);

    // Room for one rule per face (four on Doo–Sabin's quads) at once: tiles add a few more. The
    // samples of a large mesh run to millions; growing by doubling cost a fifth of `limsurf measure`,
    // and their first-touch page faults (4 KiB pages) another tenth.
    QuadratureSamples samples;
    const auto per_face =
        static_cast<std::size_t>(rule.num_points()) * (basis.scheme() == SchemeKind::DooSabin ? 4 : 1);
    samples.points.reserve(static_cast<std::size_t>(last_ptex_face - first_ptex_face) * per_face);
    samples.weights.reserve(samples.points.capacity());
    detail::advise_huge_pages(samples.points.data(), samples.points.capacity() * sizeof(SurfacePoint));
    detail::advise_huge_pages(samples.weights.data(), samples.weights.capacity() * sizeof(double));
    for (Index p = first_ptex_face; p < last_ptex_face; ++p) {
        if (!basis.has_limit_surface(p)) {
            continue;
        }
        Tile root;
        if (quads) {
            root.corner = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
            root.num_corners = 4;
        } else {
            root.corner = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2::Zero()};
            root.num_corners = 3;
        }
        const std::vector<Vec2> irregular =
            options.subdivide_near_extraordinary > 0 ? irregular_corners(basis, p) : std::vector<Vec2>{};
        if (basis.scheme() == SchemeKind::DooSabin && basis.ptex_face(p).corner < 0) {
            // A Doo–Sabin quad carries four polynomial patches, one per quadrant
            // (docs/doo_sabin_limit.md): integrate each on its own.
            for (Tile quarter : split(root)) {
                quarter.level = 0;
                place_tiles(rule, quarter, p, irregular, options.subdivide_near_extraordinary, samples);
            }
            continue;
        }
        place_tiles(rule, root, p, irregular, options.subdivide_near_extraordinary, samples);
    }
    return samples;
}

LimitSampler::LimitSampler(const LimitBasis& basis, const SamplerOptions& options, Index first_ptex_face,
                           Index last_ptex_face)
    : options_(options), domain_(basis.domain()), num_vertices_(basis.topology().num_vertices()) {
    QuadratureSamples samples = quadrature_samples(basis, options, first_ptex_face, last_ptex_face);
    points_ = std::move(samples.points);
    weights_ = std::move(samples.weights);
    const Index n = num_samples();

    // Evaluate in parallel chunks of samples. Each thread writes its samples' entries into blocks
    // of a fixed capacity, opened as they fill, and the blocks are the storage: nothing is copied
    // after it is written. Growing one vector per thread copied everything it held at every
    // reallocation into fresh pages, and concatenating the threads' vectors copied it all once more
    // on one thread (80 % of `limsurf measure` went to those copies and their page faults).
    const int threads = thread_count(options.num_threads, n);
    const auto chunk_begin = [&](Index c) { return static_cast<Index>(std::int64_t{n} * c / threads); };
    std::vector<std::vector<Block>> per_thread(static_cast<std::size_t>(threads));
    block_of_.resize(points_.size());
    offsets_.assign(points_.size() + 1, 0);  // each sample's entry count at s + 1 first
    run_ranges(threads, threads, [&](Index first_chunk, Index last_chunk) {
        LimitWeights w;
        for (Index c = first_chunk; c < last_chunk; ++c) {
            std::vector<Block>& blocks = per_thread[static_cast<std::size_t>(c)];
            for (Index s = chunk_begin(c); s < chunk_begin(c + 1); ++s) {
                const auto i = static_cast<std::size_t>(s);
                basis.evaluate(points_[i], w, DerivativeOrder::Second);
                const std::size_t k = w.vertices.size();
                if (blocks.empty() || blocks.back().vertices.size() + k > blocks.back().vertices.capacity()) {
                    const std::size_t capacity = std::max(block_entries, k);
                    blocks.emplace_back();
                    blocks.back().vertices.reserve(capacity);
                    blocks.back().limit.reserve(6 * capacity);
                }
                offsets_[i + 1] = k;
                block_of_[i] = static_cast<std::uint32_t>(blocks.size() - 1);  // within the thread's, for now
                blocks.back().vertices.insert(blocks.back().vertices.end(), w.vertices.begin(), w.vertices.end());
                blocks.back().limit.insert(blocks.back().limit.end(), w.w.data(), w.w.data() + w.w.size());
            }
        }
    });
    // The threads' blocks in order (moved, not copied), each sample's block numbered among all, and
    // the entry counts summed into offsets.
    for (Index c = 0; c < threads; ++c) {
        const auto base = static_cast<std::uint32_t>(blocks_.size());
        std::vector<Block>& blocks = per_thread[static_cast<std::size_t>(c)];
        std::move(blocks.begin(), blocks.end(), std::back_inserter(blocks_));
        for (Index s = chunk_begin(c); s < chunk_begin(c + 1); ++s) {
            const auto i = static_cast<std::size_t>(s);
            block_of_[i] += base;
            if (i == 0 || block_of_[i] != block_of_[i - 1]) {
                blocks_[block_of_[i]].first_offset = offsets_[i];
            }
            offsets_[i + 1] += offsets_[i];
        }
    }
}

std::span<const Index> LimitSampler::vertices(Index s) const {
    const auto i = static_cast<std::size_t>(s);
    const Block& block = blocks_[block_of_[i]];
    return {block.vertices.data() + (offsets_[i] - block.first_offset), offsets_[i + 1] - offsets_[i]};
}

Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> LimitSampler::limit_weights(Index s) const {
    const auto i = static_cast<std::size_t>(s);
    const Block& block = blocks_[block_of_[i]];
    return {block.limit.data() + 6 * (offsets_[i] - block.first_offset), 6,
            static_cast<Eigen::Index>(offsets_[i + 1] - offsets_[i])};
}

Eigen::Matrix<double, 6, 3> LimitSampler::evaluate(const Points& X, Index s) const {
    LIMSURF_CHECK(X.rows() == num_vertices_, InputError, "control points have ", X.rows(), " rows, the sampler ",
                  num_vertices_, " vertices");
    const auto ids = vertices(s);
    const auto w = limit_weights(s);
    Eigen::Matrix<double, 6, 3> out = Eigen::Matrix<double, 6, 3>::Zero();
    for (std::size_t k = 0; k < ids.size(); ++k) {
        out.noalias() += w.col(static_cast<Eigen::Index>(k)) * X.row(ids[k]);
    }
    return out;
}

std::vector<Eigen::Matrix<double, 6, 3>> LimitSampler::evaluate(const Points& X) const {
    LIMSURF_CHECK(X.rows() == num_vertices_, InputError, "control points have ", X.rows(), " rows, the sampler ",
                  num_vertices_, " vertices");
    std::vector<Eigen::Matrix<double, 6, 3>> out(points_.size());
    parallel_ranges(num_samples(), options_.num_threads, [&](Index begin, Index end) {
        for (Index s = begin; s < end; ++s) {
            out[static_cast<std::size_t>(s)] = evaluate(X, s);
        }
    });
    return out;
}

}  // namespace limsurf
