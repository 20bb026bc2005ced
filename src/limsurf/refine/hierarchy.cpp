#include "limsurf/refine/hierarchy.h"

#include <limits>
#include <string>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/refine/form_subdivision.h"

namespace limsurf {
namespace {

constexpr int max_levels = 16;

LevelSize size_of(const Topology& t) {
    return {t.num_vertices(), t.num_edges(), t.num_faces(), t.num_corners()};
}

/// One step of the counting recurrences; for Doo–Sabin on a mesh with boundary
/// an upper bound (the boundary rule adds at most two vertices per edge).
LevelSize next_size(const LevelSize& s, SchemeKind scheme, bool closed) {
    switch (scheme) {
    case SchemeKind::CatmullClark:
    case SchemeKind::Bilinear:
        // every corner becomes a quad
        return {s.vertices + s.edges + s.faces, 2 * s.edges + s.corners, s.corners, 4 * s.corners};
    case SchemeKind::Loop:
    case SchemeKind::Linear:
        return {s.vertices + s.edges, 2 * s.edges + 3 * s.faces, 4 * s.faces, 12 * s.faces};
    case SchemeKind::DooSabin: {
        // closed: a vertex per corner, F + E + V faces, every child vertex of valence 4
        const std::int64_t v = s.corners + (closed ? 0 : 2 * s.edges);
        const std::int64_t f = s.faces + s.edges + s.vertices;
        return {v, closed ? 2 * s.corners : 2 * v + s.edges, f, closed ? 4 * s.corners : 2 * (2 * v + s.edges)};
    }
    }
    return s;
}

}  // namespace

std::vector<LevelSize> predict_sizes(const Topology& base, SchemeKind scheme, int levels) {
    std::vector<LevelSize> sizes{size_of(base)};
    const bool closed = base.is_closed();
    for (int l = 0; l < levels; ++l) {
        sizes.push_back(next_size(sizes.back(), scheme, closed));
    }
    return sizes;
}

std::int64_t estimated_bytes(const LevelSize& size) {
    // Topology: ~6 Index tables per corner plus edge and vertex tables; S0: ~8
    // non-zeros per vertex row at 12 bytes each (value + column index).
    return 26 * size.corners + 20 * size.edges + 24 * size.vertices + 8 * 12 * size.vertices;
}

Hierarchy::Hierarchy(Topology base, const RefineOptions& options) : options_(options), base_(std::move(base)) {
    LIMSURF_CHECK(options.levels >= 0 && options.levels <= max_levels, InputError, "levels must be in [0, ", max_levels,
                  "], got ", options.levels);
    LIMSURF_CHECK(options.max_faces > 0, InputError, "max_faces must be > 0");
    const std::vector<LevelSize> sizes = predict_sizes(base_, options.scheme, options.levels);
    const LevelSize& finest = sizes.back();
    LIMSURF_CHECK(finest.faces <= options.max_faces, InputError, to_string(options.scheme), " with ", options.levels,
                  " levels would make ", finest.faces, " faces at level ", options.levels, " (about ",
                  estimated_bytes(finest) / (std::int64_t{1} << 20), " MiB); the limit is ", options.max_faces,
                  " faces (max_faces): use fewer levels");
    const auto index_max = static_cast<std::int64_t>(std::numeric_limits<Index>::max());
    LIMSURF_CHECK(finest.corners < index_max && finest.vertices < index_max && finest.edges < index_max, InputError,
                  to_string(options.scheme), " with ", options.levels, " levels would exceed 32-bit indices at level ",
                  options.levels);

    LIMSURF_CHECK(options.weights.largest_vertex() < base_.num_vertices(), InputError, "tuned weights name vertex ",
                  options.weights.largest_vertex(), " but the control mesh has ", base_.num_vertices(), " vertices");

    steps_.reserve(static_cast<std::size_t>(options.levels));
    for (int l = 0; l < options.levels; ++l) {
        const Topology& parent = l == 0 ? base_ : steps_.back().topology;
        steps_.push_back(options.forms
                             ? refine_with_forms(parent, options.scheme, options.scheme_options, options.weights)
                             : refine(parent, options.scheme, options.scheme_options, options.weights));
    }
    for (auto& cache : accumulated_) {
        cache.resize(steps_.size() + 1);
    }
}

void Hierarchy::check_level(int level, int lowest) const {
    LIMSURF_CHECK(level >= lowest && level <= num_steps(), InputError, "level ", level, " is out of range [", lowest,
                  ", ", num_steps(), "]");
}

const Topology& Hierarchy::topology(int level) const {
    check_level(level, 0);
    return level == 0 ? base_ : steps_[static_cast<std::size_t>(level) - 1].topology;
}

const Level& Hierarchy::step(int level) const {
    check_level(level, 1);
    return steps_[static_cast<std::size_t>(level) - 1];
}

const SparseMatrix& Hierarchy::accumulated(int level) const {
    return accumulated_form(0, level);
}

const SparseMatrix& Hierarchy::accumulated_form(int k, int level) const {
    check_level(level, 0);
    LIMSURF_CHECK(k >= 0 && k <= 2, InputError, "form degree must be 0, 1 or 2, got ", k);
    LIMSURF_CHECK(k == 0 || options_.forms || level == 0, InputError, "the ", k,
                  "-form operators need a hierarchy built with RefineOptions::forms");
    const std::lock_guard<std::mutex> lock(*accumulated_mutex_);
    auto& cache = accumulated_[static_cast<std::size_t>(k)];
    const Index base_size = k == 0 ? base_.num_vertices() : k == 1 ? base_.num_edges() : base_.num_faces();
    // Build every missing level up to the requested one, each from the previous.
    for (int l = 0; l <= level; ++l) {
        auto& slot = cache[static_cast<std::size_t>(l)];
        if (slot) {
            continue;
        }
        if (l == 0) {
            SparseMatrix identity(base_size, base_size);
            identity.setIdentity();
            slot = std::move(identity);
        } else {
            const Level& s = step(l);
            const SparseMatrix& S = k == 0 ? s.S0 : k == 1 ? s.S1 : s.S2;
            slot = SparseMatrix(S * *cache[static_cast<std::size_t>(l) - 1]);
        }
    }
    return *cache[static_cast<std::size_t>(level)];
}

Eigen::MatrixXd Hierarchy::apply(int level, const Eigen::MatrixXd& data) const {
    check_level(level, 0);
    LIMSURF_CHECK(data.rows() == base_.num_vertices(), InputError, "data has ", data.rows(), " rows but level 0 has ",
                  base_.num_vertices(), " vertices");
    Eigen::MatrixXd values = data;
    for (int l = 1; l <= level; ++l) {
        values = step(l).S0 * values;
    }
    return values;
}

Points Hierarchy::positions(int level, const Points& control_points) const {
    return apply(level, control_points);
}

}  // namespace limsurf
