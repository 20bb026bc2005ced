// Hierarchy: uniform refinement to level L, keeping every level (DESIGN.md §2).
//
// Level 0 is the control mesh's topology; level l (1 <= l <= L) is
// step(l).topology, reached from level l−1 by step(l).S0. The accumulated
// operator A^l = S0^{l−1} ··· S0^0 (#V_l × #V_0) maps control-vertex data
// straight to level l; it is built on first request and cached. With
// RefineOptions::forms the same holds for 1- and 2-forms: A_k^l = S_k^{l−1} ··· S_k^0
// (SEC Eq. 5).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/refine/level.h"
#include "limsurf/refine/refine.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// Which level topologies a Hierarchy keeps (refine_finest() and refine_finest_faces() ignore it).
enum class KeptTopologies : std::uint8_t {
    /// Every level's Topology (Hierarchy::topology(l) for l = 0..L): the default.
    Every,
    /// The base's and the finest level's Topology only (topology(0) and topology(L)): each level's
    /// between goes once its child is built. Every S0, S1, S2, provenance, position and accumulated
    /// operator is Every's, bit for bit. For computations on the finest level alone (the reference
    /// solutions of the SEC applications): the levels between are a third of the finest's tables.
    Finest,
    /// The base's Topology and the finest level's face list only (Hierarchy::finest_faces()): each
    /// level's Topology is dropped once its child is built, and the last step writes only its child's
    /// face list and sharpness tags, as refine_finest_faces() does (with RefineOptions::forms the
    /// finest Topology is built, S1 and S2 are numbered by its edges, and dropped after). Every S0, S1,
    /// S2, provenance, position and accumulated operator is Every's, bit for bit. For users who want
    /// the operators and the refined mesh as arrays (Python's subdivide(operators=True,
    /// topology=False)): Catmull–Clark, 100 k → 1.6 M quads, peaks at about 0.6 of Every's
    /// (docs/BENCHMARKS.md).
    FinestFaces,
};

/// Options for uniform refinement.
struct RefineOptions {
    SchemeKind scheme = SchemeKind::CatmullClark;
    int levels = 1;                                  ///< number of refinement steps, 0 <= levels <= 16
    SchemeOptions scheme_options;                    ///< boundary, creasing, triangle rule
    TunedWeights weights;                            ///< Catmull–Clark only; default = Catmull–Clark's own
    std::int64_t max_faces = std::int64_t{1} << 27;  ///< refuse when the finest level would exceed this
    /// Refuse (before allocating) when the estimated peak exceeds this (estimated_peak_bytes() for a
    /// Hierarchy, estimated_finest_peak_bytes() for refine_finest and refine_finest_faces); empty: the
    /// default budget, 3/4 of the machine's memory (default_memory_budget(), core/memory.h).
    std::optional<std::int64_t> max_memory = std::nullopt;
    /// Memory the caller will hold next to the hierarchy (e.g. a copy of the finest level to
    /// write it), counted into the peak that max_memory limits.
    std::int64_t reserved_bytes = 0;
    /// Also build the form operators S1, S2 of every step (form_subdivision.h; Loop and
    /// Catmull–Clark): off by default, so plain subdivision pays nothing for them.
    bool forms = false;
    /// Threads for each step (0: hardware concurrency): with two or more, a step (not with forms)
    /// builds the child topology on a second thread while the first builds S0 or carries the
    /// points, once the parent has 1024 faces. The result does not depend on it.
    int num_threads = 0;
    /// Which level topologies a Hierarchy keeps (the others are dropped as soon as the next step exists).
    KeptTopologies kept_topologies = KeptTopologies::Every;
};

/// Element counts of one level, predicted before refining.
struct LevelSize {
    std::int64_t vertices = 0;
    std::int64_t edges = 0;
    std::int64_t faces = 0;
    std::int64_t corners = 0;  ///< sum of face degrees
    /// Σ (face degree)²: the non-zeros of the masks that are dense over a face (Catmull–Clark's
    /// face points inside its vertex and edge points, Doo–Sabin's corners). Exact at level 0,
    /// an upper bound after.
    std::int64_t face_degree_squares = 0;
    std::int64_t valence_squares = 0;  ///< Σ valence², likewise
    /// The non-zeros of the S0 that refines this level: counted rule by rule at level 0 (a
    /// boundary vertex's crease rule has no face point), estimated_step_nonzeros() after.
    std::int64_t step_nonzeros = 0;
};

/// @brief Counts of levels 0..levels for @p scheme, without refining: exact for
///   Catmull–Clark, Loop, bilinear and linear and for Doo–Sabin on closed meshes;
///   an upper bound for Doo–Sabin with boundary.
[[nodiscard]] std::vector<LevelSize> predict_sizes(const Topology& base, SchemeKind scheme, int levels);

/// Memory (bytes) of a Topology of this size, and of its positions.
[[nodiscard]] std::int64_t estimated_bytes(const LevelSize& size);

/// @brief An upper bound of the non-zeros of the S0 that refines a level of size @p parent,
///   from its counts alone (as if every vertex and edge were interior).
[[nodiscard]] std::int64_t estimated_step_nonzeros(const LevelSize& parent, SchemeKind scheme);

/// @brief Peak memory (bytes) of a Hierarchy over @p sizes (predict_sizes()): every level's
///   topology, S0 and positions (all are kept) and the transient tables of building the largest
///   step. Calibrated on the bundled meshes (measured peaks 0.73–0.95 of it; docs/io.md "Memory").
[[nodiscard]] std::int64_t estimated_peak_bytes(const std::vector<LevelSize>& sizes);

/// @brief Peak memory (bytes) of a Hierarchy over @p sizes keeping @p kept: Every as above; Finest and
///   FinestFaces every level's S0 and positions, the base's topology, and at the largest step its
///   parent's topology, its child's (at the last step: FinestFaces only its face list) and the
///   transient tables.
[[nodiscard]] std::int64_t estimated_peak_bytes(const std::vector<LevelSize>& sizes, KeptTopologies kept);

/// @brief Peak memory (bytes) of refine_finest() (@p face_list false) or refine_finest_faces() (true)
///   over @p sizes: the base, and the largest step's parent (topology and points), child (topology —
///   for refine_finest_faces' last step only its face list — and points) and transient tables, each
///   table rounded up to whole huge pages; the first step's S0 counts as if stored (its masks, dense
///   over a face, cost time with the square of its degree). An upper bound: measured peaks are
///   0.64–0.88 of it (docs/io.md "Memory").
[[nodiscard]] std::int64_t estimated_finest_peak_bytes(const std::vector<LevelSize>& sizes, bool face_list);

class Hierarchy {
  public:
    /// @brief Refines @p base options.levels times.
    /// @throws InputError when levels is out of range, num_threads negative, kept_topologies not one of
    ///   KeptTopologies' values, or the finest level would
    ///   exceed options.max_faces or 32-bit indices, or the estimated peak memory
    ///   options.max_memory (all checked before any work; the message names the largest face
    ///   when dense masks over it dominate)
    /// @throws UnsupportedError when the scheme cannot refine a face (e.g. Loop on a quad), or
    ///   options.forms is set and form subdivision has no rules for the mesh (require_form_rules)
    Hierarchy(Topology base, const RefineOptions& options);

    /// @brief Refines @p base as above and carries @p control_points (#V_0 × 3) to every level as
    ///   each step builds its rows: positions(level) then gives what positions(level, control_points)
    ///   would, bit for bit, without a second pass over every S0 (Catmull–Clark, 100k → 1.6M quads:
    ///   docs/BENCHMARKS.md). Holds every level's positions (24 bytes per vertex and level).
    /// @throws as the constructor above; InputError when @p control_points does not have a row per
    ///   base vertex; NumericalError as positions(level, control_points)
    Hierarchy(Topology base, const RefineOptions& options, const Points& control_points);

    Hierarchy(Hierarchy&&) noexcept = default;
    Hierarchy& operator=(Hierarchy&&) noexcept = default;

    /// Number of refinement steps L (levels 0..L exist).
    [[nodiscard]] int num_steps() const noexcept { return static_cast<int>(steps_.size()); }
    [[nodiscard]] const RefineOptions& options() const noexcept { return options_; }

    /// Topology of level @p level (0 = the base).
    /// @throws InputError when out of range, or for a level the hierarchy did not keep
    ///   (KeptTopologies::Finest: 1..L−1; FinestFaces: 1..L, finest_faces() has the finest level's faces)
    [[nodiscard]] const Topology& topology(int level) const;

    /// The finest level's face list and sharpness tags (PolygonSoup's face_offsets, face_vertices and
    /// sharpness; no positions: positions(num_steps()) has them) of a hierarchy built with
    /// KeptTopologies::FinestFaces: to_polygon_soup() of what topology(num_steps()) would be, tag for tag
    /// (Doo–Sabin: no tags, as refine_finest_faces()).
    /// @throws InputError when the hierarchy keeps every Topology (topology(num_steps()) is the finest)
    [[nodiscard]] const PolygonSoup& finest_faces() const;

    /// The step that produced level @p level (1 <= level <= L); its topology is empty where the
    /// hierarchy did not keep it (KeptTopologies). @throws InputError when out of range
    [[nodiscard]] const Level& step(int level) const;

    /// A^level = S0^{level−1} ··· S0^0, #V_level × #V_0 (identity for level 0); built once, cached.
    /// Thread-safe. @throws InputError when out of range
    [[nodiscard]] const SparseMatrix& accumulated(int level) const;

    /// A_k^level for k-forms: k = 0 is accumulated(level); k = 1 (#E_level × #E_0) and
    /// k = 2 (#F_level × #F_0) need RefineOptions::forms. Built once, cached, thread-safe.
    /// @throws InputError when out of range, k is not 0, 1, 2, or the forms were not built
    [[nodiscard]] const SparseMatrix& accumulated_form(int k, int level) const;

    /// Per-vertex data (#V_0 × k, any k) carried to level @p level by successive
    /// S0 products (cheaper than forming A). @throws InputError on a row-count mismatch
    [[nodiscard]] Eigen::MatrixXd apply(int level, const Eigen::MatrixXd& data) const;

    /// k-form data (#V_0, #E_0 or #F_0 rows for k = 0, 1, 2; any number of columns) carried to level
    /// @p level by successive S_k products: accumulated_form(k, level) · data up to rounding, without
    /// forming the product matrix (at 327 k triangles it is most of the work). k = 0 is apply().
    /// @throws InputError when out of range, k is not 0, 1, 2, the forms were not built (k > 0), or
    ///   on a row-count mismatch
    [[nodiscard]] Eigen::MatrixXd apply_form(int k, int level, const Eigen::MatrixXd& data) const;

    /// Positions at level @p level from control points (#V_0 × 3).
    /// @throws InputError as apply(); NumericalError when finite control points give non-finite
    ///   positions (an overflow, for coordinates near the range of a double)
    [[nodiscard]] Points positions(int level, const Points& control_points) const;

    /// Whether the hierarchy was built with its control points (positions(level) is available).
    [[nodiscard]] bool has_positions() const noexcept { return !positions_.empty(); }

    /// Positions at level @p level (0: the control points) of a hierarchy built with its control
    /// points. @throws InputError when out of range or built without control points
    [[nodiscard]] const Points& positions(int level) const;

  private:
    void check_level(int level, int lowest) const;
    /// Builds the levels; with @p control_points (not null) carries them to every level too.
    void build(const Points* control_points);

    RefineOptions options_;
    Topology base_;
    std::vector<Level> steps_;
    std::vector<Points> positions_;  ///< [level], when built with control points; otherwise empty
    PolygonSoup finest_faces_;       ///< KeptTopologies::FinestFaces: the finest level's faces and tags
    // Lazily built accumulated operators; the mutex lives on the heap so that
    // the hierarchy stays movable.
    mutable std::array<std::vector<std::optional<SparseMatrix>>, 3> accumulated_;  // [k][level]
    mutable std::unique_ptr<std::mutex> accumulated_mutex_ = std::make_unique<std::mutex>();
};

/// The finest level of a refinement, without the levels before it.
struct FinestLevel {
    Topology topology;  ///< level L
    Points positions;   ///< #V_L × 3
    /// {#V, #E, #F} of every level 0..L (as Hierarchy::topology(l) would report them).
    std::vector<std::array<Index, 3>> counts;
};

/// @brief Refines @p base options.levels times and keeps only the finest level (for users who
///   only want the refined mesh: `limsurf subdivide`). No step stores its S0: each step writes
///   each row's product with the points as it builds the row, summed as S0 · X sums; each parent
///   level is dropped once its child exists, so the peak holds two topologies and the points.
///   Topology and positions are those of Hierarchy(base, options).topology(L) and .positions(L,
///   control_points), bit for bit. options.forms is ignored.
/// @throws as Hierarchy's constructor and Hierarchy::positions (the same checks, before any work)
[[nodiscard]] FinestLevel refine_finest(const Topology& base, const Points& control_points,
                                        const RefineOptions& options);

/// The finest level of a refinement as a face list, without its Topology.
struct FinestFaces {
    /// Level L's positions, face list and sharpness tags: to_polygon_soup() of refine_finest()'s
    /// result, tag for tag (no hints, groups or source lines).
    PolygonSoup mesh;
    /// {#V, #E, #F} of every level 0..L, as refine_finest() reports them.
    std::vector<std::array<Index, 3>> counts;
};

/// @brief refine_finest() without the finest level's Topology (its edges, one-rings and boundary
///   loops): the last step writes only the child's face list and sharpness tags, as OpenSubdiv's
///   uniform refinement does without fullTopologyInLastLevel. For users who write the refined mesh
///   or hand it on as arrays (`limsurf subdivide`): at 1.6 M quads the Topology is ~240 MiB, the face
///   list ~30 MiB.
/// @throws as refine_finest()
[[nodiscard]] FinestFaces refine_finest_faces(const Topology& base, const Points& control_points,
                                              const RefineOptions& options);

}  // namespace limsurf
