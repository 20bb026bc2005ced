#include "limsurf/refine/hierarchy.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/core/memory.h"
#include "limsurf/detail/huge_pages.h"
#include "limsurf/detail/refine_face_split.h"
#include "limsurf/detail/row_assembly.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/mesh/local_size.h"
#include "limsurf/refine/form_subdivision.h"

namespace limsurf {
namespace {

constexpr int max_levels = 16;

LevelSize size_of(const Topology& t) {
    LevelSize s{t.num_vertices(), t.num_edges(), t.num_faces(), t.num_corners(), 0, 0, 0};
    for (Index f = 0; f < t.num_faces(); ++f) {
        s.face_degree_squares += std::int64_t{t.face_degree(f)} * t.face_degree(f);
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        s.valence_squares += std::int64_t{t.valence(v)} * t.valence(v);
    }
    return s;
}

/// One step of the counting recurrences; for Doo–Sabin on a mesh with boundary
/// an upper bound (the boundary rule adds at most two vertices per edge). The sums of
/// squares are upper bounds after level 0.
LevelSize next_size(const LevelSize& s, SchemeKind scheme, bool closed) {
    switch (scheme) {
    case SchemeKind::CatmullClark:
    case SchemeKind::Bilinear:
        // every corner becomes a quad; a face point has the valence of its face's degree
        return {s.vertices + s.edges + s.faces,
                2 * s.edges + s.corners,
                s.corners,
                4 * s.corners,
                16 * s.corners,
                s.valence_squares + 16 * s.edges + s.face_degree_squares,
                0};
    case SchemeKind::Loop:
    case SchemeKind::Linear:
    case SchemeKind::C2g0:
        return {s.vertices + s.edges,
                2 * s.edges + 3 * s.faces,
                4 * s.faces,
                12 * s.faces,
                36 * s.faces,
                s.valence_squares + 36 * s.edges,
                0};
    case SchemeKind::DooSabin: {
        // closed: a vertex per corner, F + E + V faces, every child vertex of valence 4; the
        // face of a face keeps its degree, the face of a vertex has its valence
        const std::int64_t v = s.corners + (closed ? 0 : 2 * s.edges);
        const std::int64_t f = s.faces + s.edges + s.vertices;
        return {v,
                closed ? 2 * s.corners : 2 * v + s.edges,
                f,
                closed ? 4 * s.corners : 2 * (2 * v + s.edges),
                s.face_degree_squares + 16 * s.edges + s.valence_squares,
                16 * v,
                0};
    }
    }
    return s;
}

/// The non-zeros of the first step's S0, rule by rule where masks span whole faces: a Catmull–Clark
/// vertex or edge point holds its faces' points only in the interior, a Doo–Sabin corner holds its
/// whole face only away from the boundary (2 entries there).
std::int64_t first_step_nonzeros(const Topology& t, SchemeKind scheme) {
    const LevelSize s = {t.num_vertices(), t.num_edges(), t.num_faces(), t.num_corners(), 0, 0, 0};
    if (scheme == SchemeKind::CatmullClark) {
        std::int64_t extra = 0;  // face-point corners beyond the vertex's and edge's own neighbours
        for (Index v = 0; v < t.num_vertices(); ++v) {
            for (const Index f : t.vertex_faces(v)) {
                extra += t.is_boundary_vertex(v) ? 0 : t.face_degree(f) - 3;
            }
        }
        for (Index e = 0; e < t.num_edges(); ++e) {
            for (const Index f : t.edge_faces(e)) {
                extra += t.is_boundary_edge(e) ? 0 : t.face_degree(f) - 2;
            }
        }
        return s.vertices + 4 * s.edges + s.corners + extra;
    }
    if (scheme == SchemeKind::DooSabin) {
        std::int64_t nonzeros = 0;
        for (Index f = 0; f < t.num_faces(); ++f) {
            const auto edges = t.face_edges(f);
            const std::size_t n = edges.size();
            for (std::size_t i = 0; i < n; ++i) {
                const bool interior = !t.is_boundary_edge(edges[i]) && !t.is_boundary_edge(edges[(i + n - 1) % n]);
                nonzeros += interior ? static_cast<std::int64_t>(n) : 2;
            }
        }
        return nonzeros;
    }
    return estimated_step_nonzeros(s, scheme);
}

/// Bytes of the transient tables of building a level of size @p child with an S0 of @p nonzeros:
/// the numbering and one-ring scratch of the child Topology (32 bytes per child corner: an upper
/// bound calibrated when it still sorted half-edges; docs/io.md "Memory"), and the growth slack of S0.
std::int64_t transient_bytes(const LevelSize& child, std::int64_t nonzeros) {
    return 32 * child.corners + 12 * nonzeros;
}

/// Refuses a hierarchy whose estimated peak exceeds the memory budget, naming the cause.
void check_memory(const Topology& base, const std::vector<LevelSize>& sizes, std::int64_t peak,
                  const RefineOptions& options) {
    constexpr std::int64_t always_fine = std::int64_t{64} << 20;  // local patches: no look-up of the machine
    LIMSURF_CHECK(!options.max_memory || *options.max_memory > 0, InputError,
                  "the memory budget (max_memory) must be positive, got ", options.max_memory.value_or(0));
    if (!options.max_memory && peak <= always_fine) {
        return;
    }
    const std::int64_t budget = options.max_memory.value_or(default_memory_budget());
    if (peak <= budget) {
        return;
    }
    const bool dense_masks = options.scheme == SchemeKind::CatmullClark || options.scheme == SchemeKind::DooSabin;
    if (const LocalSize local = local_size(base); dense_masks && local.max_face_degree > 64) {
        throw InputError(detail::concat(to_string(options.scheme), " refinement needs about ", format_bytes(peak),
                                        ", more than the memory budget of ", format_bytes(budget),
                                        options.max_memory ? " (max_memory)" : " (3/4 of this machine's memory)",
                                        ": most of it are the masks over face ", local.face, "'s ",
                                        local.max_face_degree,
                                        " corners, which grow with the square of a face's degree (split the face)"),
                         face_element(local.face));
    }
    throw InputError(
        detail::concat(to_string(options.scheme), " with ", options.levels, options.levels == 1 ? " level" : " levels",
                       " needs about ", format_bytes(peak), " at its peak (", sizes.back().faces, " faces at level ",
                       options.levels, "), more than the memory budget of ", format_bytes(budget),
                       options.max_memory ? " (max_memory)" : " (3/4 of this machine's memory)",
                       ": use fewer levels, or a larger budget (limsurf --max-memory) if the machine has the memory"));
}

/// What a refinement keeps, which decides its peak.
enum class Keeping {
    EveryLevel,   ///< Hierarchy: estimated_peak_bytes(…, options.kept_topologies)
    FinestLevel,  ///< refine_finest(): estimated_finest_peak_bytes(…, false)
    FinestFaces,  ///< refine_finest_faces(): estimated_finest_peak_bytes(…, true)
};

/// Everything Hierarchy and refine_finest refuse before any work: levels, sizes, memory, weights.
void check_refinement(const Topology& base, const RefineOptions& options, Keeping keeping) {
    LIMSURF_CHECK(options.levels >= 0 && options.levels <= max_levels, InputError, "levels must be in [0, ", max_levels,
                  "], got ", options.levels);
    LIMSURF_CHECK(options.max_faces > 0, InputError, "max_faces must be > 0");
    LIMSURF_CHECK(options.num_threads >= 0, InputError, "num_threads must be >= 0 (0: all cores), got ",
                  options.num_threads);
    const auto kept = static_cast<int>(options.kept_topologies);
    LIMSURF_CHECK(kept >= 0 && kept <= static_cast<int>(KeptTopologies::FinestFaces), InputError,
                  "kept_topologies must be Every, Finest or FinestFaces, got ", kept);
    const std::vector<LevelSize> sizes = predict_sizes(base, options.scheme, options.levels);
    const LevelSize& finest = sizes.back();
    const std::int64_t peak =
        (keeping == Keeping::EveryLevel ? estimated_peak_bytes(sizes, options.kept_topologies)
                                        : estimated_finest_peak_bytes(sizes, keeping == Keeping::FinestFaces)) +
        options.reserved_bytes;
    LIMSURF_CHECK(finest.faces <= options.max_faces, InputError, to_string(options.scheme), " with ", options.levels,
                  " levels would make ", finest.faces, " faces at level ", options.levels, " (about ",
                  format_bytes(peak), "); the limit is ", options.max_faces, " faces (max_faces): use fewer levels");
    check_memory(base, sizes, peak, options);
    const auto index_max = static_cast<std::int64_t>(std::numeric_limits<Index>::max());
    LIMSURF_CHECK(finest.corners < index_max && finest.vertices < index_max && finest.edges < index_max, InputError,
                  to_string(options.scheme), " with ", options.levels, " levels would exceed 32-bit indices at level ",
                  options.levels);

    LIMSURF_CHECK(options.weights.largest_vertex() < base.num_vertices(), InputError, "tuned weights name vertex ",
                  options.weights.largest_vertex(), " but the control mesh has ", base.num_vertices(), " vertices");
}

/// Masks with negative weights (tuned, semi-sharp blends) can leave the range of a double for
/// control points near it.
void check_finite(const Points& control_points, const Points& out, int level) {
    LIMSURF_CHECK(!control_points.allFinite() || out.allFinite(), NumericalError, "the level-", level,
                  " positions overflow a double (the control points reach ", control_points.cwiseAbs().maxCoeff(),
                  "): rescale the mesh");
}

/// Per-vertex data must have a row per base vertex (apply, positions, refine_finest).
void check_rows(const Topology& base, Eigen::Index rows) {
    LIMSURF_CHECK(rows == base.num_vertices(), InputError, "data has ", rows, " rows but level 0 has ",
                  base.num_vertices(), " vertices");
}

}  // namespace

std::vector<LevelSize> predict_sizes(const Topology& base, SchemeKind scheme, int levels) {
    std::vector<LevelSize> sizes{size_of(base)};
    sizes[0].step_nonzeros = first_step_nonzeros(base, scheme);
    const bool closed = base.is_closed();
    for (int l = 0; l < levels; ++l) {
        sizes.push_back(next_size(sizes.back(), scheme, closed));
        sizes.back().step_nonzeros = estimated_step_nonzeros(sizes.back(), scheme);
    }
    return sizes;
}

std::int64_t estimated_bytes(const LevelSize& size) {
    // The Topology's tables (17 bytes per corner: corners, edges, one-ring faces, corners (a byte)
    // and edges; edge ends and two face slots; vertex offsets, face offsets and components, which
    // a closed or connected mesh goes without, counted anyway) and positions.
    return 17 * size.corners + 16 * size.edges + 9 * size.vertices + 8 * size.faces + 24 * size.vertices;
}

std::int64_t estimated_step_nonzeros(const LevelSize& parent, SchemeKind scheme) {
    const LevelSize& s = parent;
    switch (scheme) {
    case SchemeKind::CatmullClark:
        // vertex rows 1 + valence + the other corners of its faces, edge rows 2 + the other corners of
        // both faces, face rows every corner: V + 4E + 2 Σn² − 4C (25 per face of a quad mesh)
        return s.vertices + 4 * s.edges + 2 * s.face_degree_squares - 4 * s.corners;
    case SchemeKind::Bilinear:
        return s.vertices + 2 * s.edges + s.corners;
    case SchemeKind::Loop:
        return s.vertices + 6 * s.edges;
    case SchemeKind::Linear:
        return s.vertices + 2 * s.edges;
    case SchemeKind::C2g0:
        return 10 * s.vertices + 10 * s.edges;  // 7 (10 at valence 3) per vertex row, 10 (8) per edge row
    case SchemeKind::DooSabin:
        return s.face_degree_squares;  // each corner's point mixes all corners of its face
    }
    return 0;
}

std::int64_t estimated_peak_bytes(const std::vector<LevelSize>& sizes) {
    std::int64_t kept = 0;
    std::int64_t transient = 0;
    for (std::size_t l = 0; l < sizes.size(); ++l) {
        kept += estimated_bytes(sizes[l]);
        if (l > 0) {
            const std::int64_t nonzeros = sizes[l - 1].step_nonzeros;
            kept += 12 * nonzeros + 4 * sizes[l].vertices;
            transient = std::max(transient, transient_bytes(sizes[l], nonzeros));
        }
    }
    return kept + transient;
}

std::int64_t estimated_peak_bytes(const std::vector<LevelSize>& sizes, KeptTopologies kept) {
    if (kept == KeptTopologies::Every) {
        return estimated_peak_bytes(sizes);
    }
    const auto topology_bytes = [](const LevelSize& size) { return estimated_bytes(size) - 24 * size.vertices; };
    std::int64_t held = estimated_bytes(sizes[0]);  // the base, kept
    std::int64_t largest_step = 0;
    const auto last = sizes.size() - 1;
    for (std::size_t l = 1; l <= last; ++l) {
        const LevelSize& parent = sizes[l - 1];
        const LevelSize& child = sizes[l];
        const std::int64_t nonzeros = parent.step_nonzeros;
        held += 12 * nonzeros + 4 * child.vertices + 24 * child.vertices;  // S0 and positions, kept
        // The parent's topology (the base's is counted above) and the child's, only its face list at
        // the last step, live while the step runs.
        const std::int64_t parent_topology = l == 1 ? 0 : topology_bytes(parent);
        const bool faces_only = l == last && kept == KeptTopologies::FinestFaces;
        const std::int64_t child_topology = faces_only ? 4 * (child.corners + child.faces) : topology_bytes(child);
        largest_step = std::max(largest_step, parent_topology + child_topology + transient_bytes(child, nonzeros));
    }
    return held + largest_step;
}

std::int64_t estimated_finest_peak_bytes(const std::vector<LevelSize>& sizes, bool face_list) {
    // Tables of 4 MiB and more take whole 2 MiB huge pages (core/huge_page_allocator.h): each of a
    // level's tables and the step's temporaries (fewer than 17) rounds up by less than 2 MiB, and
    // by less than half itself.
    const auto rounded = [](std::int64_t bytes) { return bytes + std::min(bytes / 2, std::int64_t{34} << 20); };
    const auto last = sizes.size() - 1;
    std::int64_t largest_step = 0;
    for (std::size_t l = 1; l <= last; ++l) {
        const LevelSize& parent = sizes[l - 1];
        const LevelSize& child = sizes[l];
        // The parent's points again, row-major, as the rows read them; the base's topology and
        // points are the caller's, counted once below.
        const std::int64_t parent_bytes = 24 * parent.vertices + (l == 1 ? 0 : rounded(estimated_bytes(parent)));
        const bool faces_only = face_list && l == last;
        const std::int64_t child_bytes = faces_only ? rounded(24 * child.vertices + 4 * (child.corners + child.faces))
                                                    : rounded(estimated_bytes(child));
        // Building the child (its Topology from the parent's tables, or only its face list) numbers
        // the child's edges (4 bytes each), pairs the parent's edges with their corners (8) and
        // sharpness or faces (8 per edge and vertex), and keeps a slot per parent column in the row
        // builder and one per child vertex. The first step's S0 counts as if it were stored (12 bytes
        // per non-zero, exact at level 0): its rows are built whole, so masks dense over a large face
        // cost time with the square of its degree, and such a mesh is refused naming the face, as by
        // the Hierarchy (check_memory).
        const std::int64_t nonzeros = parent.step_nonzeros;
        const std::int64_t transient = 4 * child.edges + 16 * parent.edges + 12 * parent.vertices + 4 * child.vertices +
                                       (l == 1 ? 12 * nonzeros : 0);
        largest_step = std::max(largest_step, parent_bytes + child_bytes + transient);
    }
    return estimated_bytes(sizes[0]) + largest_step;
}

Hierarchy::Hierarchy(Topology base, const RefineOptions& options) : options_(options), base_(std::move(base)) {
    check_refinement(base_, options, Keeping::EveryLevel);
    build(nullptr);
}

Hierarchy::Hierarchy(Topology base, const RefineOptions& options, const Points& control_points)
    : options_(options), base_(std::move(base)) {
    check_refinement(base_, options, Keeping::EveryLevel);
    check_rows(base_, control_points.rows());
    build(&control_points);
}

void Hierarchy::build(const Points* control_points) {
    steps_.reserve(static_cast<std::size_t>(options_.levels));
    // With control points every face-split and Doo–Sabin step carries them as it builds its rows
    // (detail::SparseRowBuilder: S0 · points, bit for bit, while each row is in cache); steps with
    // forms build theirs first and multiply after, as positions(level, X) does.
    detail::CarriedPoints carried;
    if (control_points != nullptr) {
        positions_.reserve(static_cast<std::size_t>(options_.levels) + 1);
        positions_.push_back(*control_points);
        if (!options_.forms && options_.levels > 0) {
            carried.parent = *control_points;
        }
    }
    // KeptTopologies::Finest and FinestFaces: a level's topology goes once its child is built; with
    // FinestFaces the last step writes only its child's faces (with forms, S1 and S2 need the child's
    // edges: its whole Topology, dropped after).
    const bool drop_levels = options_.kept_topologies != KeptTopologies::Every;
    const bool faces_only = options_.kept_topologies == KeptTopologies::FinestFaces;
    for (int l = 0; l < options_.levels; ++l) {
        const Topology& parent = l == 0 ? base_ : steps_.back().topology;
        const bool carry = control_points != nullptr && !options_.forms;
        PolygonSoup* faces = faces_only && !options_.forms && l + 1 == options_.levels ? &finest_faces_ : nullptr;
        // The parent goes as soon as the step has no more use for it (the face splits: before their
        // provenance), else after the step.
        std::function<void()> release_parent;
        if (drop_levels && l > 0) {
            release_parent = [this] { steps_.back().topology = Topology{}; };
        }
        Level child = options_.forms
                          ? refine_with_forms(parent, options_.scheme, options_.scheme_options, options_.weights)
                          : detail::refine_step(parent, options_.scheme, options_.scheme_options, options_.weights,
                                                detail::step_threads(options_.num_threads, parent),
                                                carry ? &carried : nullptr, faces, release_parent);
        if (release_parent) {
            release_parent();  // (again, for steps that do not call it)
        }
        steps_.push_back(std::move(child));
        if (control_points == nullptr) {
            continue;
        }
        if (carry) {
            if (l + 1 < options_.levels) {
                carried.parent = carried.child;  // row-major again, for the next step's rows
            }
            positions_.push_back(std::move(carried.child));
        } else {
            Points next(steps_.back().S0.rows(), 3);
            next.noalias() = steps_.back().S0 * positions_.back();  // Eigen's sums, as apply() makes them
            positions_.push_back(std::move(next));
        }
        check_finite(*control_points, positions_.back(), l + 1);
    }
    if (faces_only && (options_.levels == 0 || options_.forms)) {
        write_faces(options_.levels == 0 ? base_ : steps_.back().topology, finest_faces_);
        if (options_.levels > 0) {
            steps_.back().topology = Topology{};
        }
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
    const KeptTopologies kept = options_.kept_topologies;
    LIMSURF_CHECK(
        level == 0 || kept == KeptTopologies::Every || (kept == KeptTopologies::Finest && level == num_steps()),
        InputError, "level ", level, "'s topology was not kept (RefineOptions::kept_topologies is ",
        kept == KeptTopologies::Finest ? "Finest: only levels 0 and " + std::to_string(num_steps())
                                       : std::string("FinestFaces: finest_faces() has the finest level's face list"),
        ")");
    return level == 0 ? base_ : steps_[static_cast<std::size_t>(level) - 1].topology;
}

const PolygonSoup& Hierarchy::finest_faces() const {
    LIMSURF_CHECK(options_.kept_topologies == KeptTopologies::FinestFaces, InputError,
                  "finest_faces() needs a hierarchy built with KeptTopologies::FinestFaces: topology(", num_steps(),
                  ") is the finest level");
    return finest_faces_;
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
            slot.emplace(base_size, base_size);
            slot->setIdentity();
        } else {
            const Level& s = step(l);
            const SparseMatrix& S = k == 0 ? s.S0 : k == 1 ? s.S1 : s.S2;
            // Row by row (the same bits as Eigen's product), swapped into place: Eigen 3.4's
            // SparseMatrix would copy on the optional's assignment.
            SparseMatrix product =
                detail::sparse_product(S, *cache[static_cast<std::size_t>(l) - 1], options_.num_threads);
            slot.emplace();
            slot->swap(product);
        }
    }
    return *cache[static_cast<std::size_t>(level)];
}

Eigen::MatrixXd Hierarchy::apply(int level, const Eigen::MatrixXd& data) const {
    return apply_form(0, level, data);
}

Eigen::MatrixXd Hierarchy::apply_form(int k, int level, const Eigen::MatrixXd& data) const {
    check_level(level, 0);
    LIMSURF_CHECK(k >= 0 && k <= 2, InputError, "form degree must be 0, 1 or 2, got ", k);
    LIMSURF_CHECK(k == 0 || options_.forms || level == 0, InputError, "the ", k,
                  "-form operators need a hierarchy built with RefineOptions::forms");
    if (k == 0) {
        check_rows(base_, data.rows());
    } else {
        const Index size = k == 1 ? base_.num_edges() : base_.num_faces();
        LIMSURF_CHECK(data.rows() == size, InputError, "data has ", data.rows(), " rows but level 0 has ", size,
                      k == 1 ? " edges" : " faces");
    }
    Eigen::MatrixXd values = data;
    for (int l = 1; l <= level; ++l) {
        const Level& s = step(l);
        const SparseMatrix& S = k == 0 ? s.S0 : k == 1 ? s.S1 : s.S2;
        Eigen::MatrixXd next(S.rows(), values.cols());
        detail::advise_huge_pages(next.data(), sizeof(double) * static_cast<std::size_t>(next.size()));
        next.noalias() = S * values;  // Eigen's sums, as values = S * values would make them
        values.swap(next);
    }
    return values;
}

const Points& Hierarchy::positions(int level) const {
    check_level(level, 0);
    LIMSURF_CHECK(has_positions(), InputError,
                  "this hierarchy was built without control points: use positions(level, control_points)");
    return positions_[static_cast<std::size_t>(level)];
}

Points Hierarchy::positions(int level, const Points& control_points) const {
    Points out = apply(level, control_points);
    check_finite(control_points, out, level);
    return out;
}

namespace {

/// refine_finest(), and with @p faces the last step writes only the child's face list and tags there
/// (the FinestLevel's topology is then empty; its counts are complete).
FinestLevel refine_to_finest(const Topology& base, const Points& control_points, const RefineOptions& options,
                             PolygonSoup* faces) {
    check_refinement(base, options, faces != nullptr ? Keeping::FinestFaces : Keeping::FinestLevel);
    check_rows(base, control_points.rows());
    const auto counts = [](const Topology& t) {
        return std::array<Index, 3>{t.num_vertices(), t.num_edges(), t.num_faces()};
    };
    FinestLevel out;
    out.counts.push_back(counts(base));
    // Each step carries the points as it builds its rows (detail::SparseRowBuilder): S0 is never
    // stored, and the sums are those of S0 · points, bit for bit.
    detail::CarriedPoints carried;
    if (options.levels > 0) {
        carried.parent = control_points;
    }
    Topology level;  // the current finest, once refined
    for (int l = 0; l < options.levels; ++l) {
        const Topology& parent = l == 0 ? base : level;
        const bool last = l + 1 == options.levels;
        PolygonSoup* last_faces = last ? faces : nullptr;
        Topology child =
            detail::refine_carrying(parent, options.scheme, options.scheme_options, options.weights, carried,
                                    detail::step_threads(options.num_threads, parent), last_faces);
        if (last_faces != nullptr && options.scheme == SchemeKind::DooSabin) {
            out.counts.push_back(detail::doo_sabin_child_counts(parent, options.scheme_options));
        } else if (last_faces != nullptr) {
            // The face splits' counts follow from the parent's (next_size is exact for them).
            const LevelSize size = next_size(
                {parent.num_vertices(), parent.num_edges(), parent.num_faces(), parent.num_corners(), 0, 0, 0},
                options.scheme, parent.is_closed());
            out.counts.push_back(
                {static_cast<Index>(size.vertices), static_cast<Index>(size.edges), static_cast<Index>(size.faces)});
        } else {
            out.counts.push_back(counts(child));
        }
        level = std::move(child);  // the parent goes here
        if (!last) {
            carried.parent = carried.child;
        }
    }
    // Not through ?: with the const base and control points, which would copy the child's.
    if (options.levels == 0) {
        if (faces != nullptr) {
            write_faces(base, *faces);
        } else {
            out.topology = base;
        }
        out.positions = control_points;
    } else {
        out.topology = std::move(level);
        out.positions = std::move(carried.child);
    }
    check_finite(control_points, out.positions, options.levels);
    return out;
}

}  // namespace

FinestLevel refine_finest(const Topology& base, const Points& control_points, const RefineOptions& options) {
    return refine_to_finest(base, control_points, options, nullptr);
}

FinestFaces refine_finest_faces(const Topology& base, const Points& control_points, const RefineOptions& options) {
    FinestFaces out;
    FinestLevel finest = refine_to_finest(base, control_points, options, &out.mesh);
    out.mesh.positions = std::move(finest.positions);
    out.counts = std::move(finest.counts);
    return out;
}

}  // namespace limsurf
