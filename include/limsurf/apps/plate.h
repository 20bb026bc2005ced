// Kirchhoff–Love plates on a planar control mesh and its refinements, with the numbers that check
// them (docs/guide/plate.md): the deflection at the centre and at the quarter point of the bounding
// box, the largest deflection over the quadrature points and, for a simply supported rectangle
// under the uniform or sine loads, the relative errors against the Navier solution (centre,
// quarter point, L2, energy). The driver behind `limsurf plate` and limsurf.plate in Python, so both
// give the same numbers.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/analysis/weight_tuning.h"
#include "limsurf/core/types.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/fem/plate.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/quadrature/sampler.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf {

/// The shape of a plate's load.
enum class PlateLoadShape {
    Uniform,     ///< p
    Sinusoidal,  ///< p sin(2π(x − x0)/a) sin(2π(y − y0)/b) over the bounding box (the seed's Table 2)
    SingleWave,  ///< p sin(π(x − x0)/a) sin(π(y − y0)/b)
    Function,    ///< PlateLoad::function, evaluated at the quadrature points
    /// PlateLoad::values: control values of the load on the control mesh (p_h = Σ p_i φ_i, b = M p),
    /// carried to each refined level by its S0 (p_l = S0 p_{l−1}) like the positions.
    Values
};

/// "uniform", "sinusoidal", "single-wave" (the loads known by name); empty for any other name.
[[nodiscard]] std::optional<PlateLoadShape> plate_load_shape(const std::string& name);
/// "uniform", "sinusoidal", "single-wave", "function", "values".
[[nodiscard]] const char* to_string(PlateLoadShape shape) noexcept;

/// "simply" (PlateSupport::SimplySupported) or "clamped" (PlateSupport::Clamped), as `limsurf plate --support`.
/// @throws InputError naming the accepted names
[[nodiscard]] PlateSupport parse_plate_support(const std::string& name);

struct PlateLoad {
    PlateLoadShape shape = PlateLoadShape::Uniform;
    double pressure = 1e4;     ///< p of Uniform, Sinusoidal and SingleWave
    SurfaceFunction function;  ///< Function: the load at rows of positions
    Eigen::VectorXd values;    ///< Values: one per control vertex of the control mesh
};

/// Tuned Catmull–Clark weights in the analysis (iga-tuned-catmull-clark-weights §3.4, §4) at every
/// interior extraordinary vertex of valence ≥ 5 (valence 3 keeps Catmull–Clark's: the paper does not
/// tune it, its rings shrink faster than the others' and the gain is negligible).
enum class PlateTuning {
    None,    ///< Catmull–Clark's own weights
    Cup,     ///< tuned_vertex_weights(valence, Cup) at every such vertex
    Saddle,  ///< tuned_vertex_weights(valence, Saddle)
    /// Two passes per level: cup weights; the decomposition (38) of that solution at each vertex; then
    /// cup weights where R ≥ 1 and saddle weights where R < 1 (§3.4). With
    /// PlateStudyOptions::decide_level, the paper's §4 procedure instead: the cup pass and the choice
    /// on that level only, the choice then kept on every level.
    Auto
};
/// "none", "cup", "saddle", "auto".
[[nodiscard]] const char* to_string(PlateTuning tuning) noexcept;
/// @throws InputError naming the accepted names
[[nodiscard]] PlateTuning parse_plate_tuning(const std::string& name);

struct PlateStudyOptions {
    PlateMaterial material;
    /// SimplySupported or Clamped (ClampedNitsche is refused: the per-vertex load has no penalty).
    PlateSupport support = PlateSupport::SimplySupported;
    SchemeKind scheme = SchemeKind::CatmullClark;  ///< of the basis and the refinement (default rules)
    int levels = 0;                                ///< also solve on the control mesh refined 1..levels times (0..6)
    SamplerOptions quadrature{6, 6, 0};            ///< degree per tile, tile levels
    PlateTuning tuning = PlateTuning::None;        ///< Catmull–Clark only
    TuningOptions tuning_options;                  ///< how tuned_vertex_weights() integrates
    /// PlateTuning::Auto: decide cup or saddle once, from the cup pass on the control mesh refined this
    /// many times (0..6, also beyond `levels`), and keep the choice on every level, as §4 does (levels
    /// 2 and 3); empty: every level decides from its own cup pass.
    std::optional<int> decide_level;
};

/// The bounding rectangle [x0, x0 + a] × [y0, y0 + b] of the control points.
struct PlateRectangle {
    double x0 = 0, y0 = 0, a = 0, b = 0;
};

/// A level's deflection against the Navier solution of the simply supported rectangle.
struct PlateNavierComparison {
    double centre_deflection = 0.0;   ///< exact, at the centre of the rectangle
    double quarter_deflection = 0.0;  ///< exact, at (a/4, b/4)
    /// w_h / w − 1 at the centre; empty at a node of the exact deflection (the centre under the
    /// sinusoidal load) or where the point is off the plate.
    std::optional<double> centre_relative_error;
    std::optional<double> quarter_relative_error;  ///< the same at (a/4, b/4)
    double l2_relative_error = 0.0;                ///< ‖w_h − w‖_L2 / ‖w‖_L2 by the quadrature
    /// √((∫ p w dA − a(w_h, w_h)) / ∫ p w dA): the energy norm of the error (Galerkin orthogonality).
    double energy_relative_error = 0.0;
};

/// One solve on one level: the deflection and its checks.
struct PlatePass {
    PlateSolution solution;
    std::optional<double> centre_deflection;
    std::optional<double> quarter_deflection;
    double max_deflection = 0.0;
    std::optional<PlateNavierComparison> navier;
};

/// The weights of one tuned vertex at one level.
struct PlateTunedVertex {
    Index vertex = invalid_index;  ///< control-mesh index (refinement keeps it)
    int valence = 0;
    QuadraticShape shape = QuadraticShape::Cup;
    TunedVertex weights;
    /// PlateTuning::Auto: the decomposition of the first (cup) pass at this level, or at
    /// PlateStudyOptions::decide_level when one is given (the same vertex there). At level 0 it is
    /// read one level finer and scaled back, k_j / λ_j (⟨l_j, S p⟩ = λ_j ⟨l_j, p⟩): the control mesh's
    /// one-rings may hold two tuned vertices, which the closed form does not cover.
    std::optional<ShapeDecomposition> decomposition;
};

/// One level of solve_plate_levels.
struct PlateLevel {
    int level = 0;
    Topology topology;
    Points X;                                  ///< control points (S0 applied `level` times)
    Eigen::VectorXd load_values;               ///< PlateLoadShape::Values: the load's control values here; else empty
    PlateSolution solution;                    ///< w: #V control values of the deflection
    std::optional<double> centre_deflection;   ///< at the centre of the rectangle; empty off the plate
    std::optional<double> quarter_deflection;  ///< at (x0 + a/4, y0 + b/4); empty off the plate
    double max_deflection = 0.0;               ///< max |w_h| over the quadrature points
    std::optional<PlateNavierComparison> navier;
    /// The tuned vertices and their weights (empty for PlateTuning::None).
    std::vector<PlateTunedVertex> tuned_vertices;
    /// PlateTuning::Auto: the first pass, with cup weights at every tuned vertex (the fields above
    /// are the second pass's); with a decide_level only on that level.
    std::optional<PlatePass> first_pass;
};

struct PlateStudy {
    PlateRectangle rectangle;
    double bending_rigidity = 0.0;  ///< D = E t³ / (12 (1 − ν²))
    /// The support and load have a Navier solution (simply supported, uniform or sine load): the
    /// levels carry the comparison when the plate is its bounding rectangle.
    bool navier_load = false;
    /// The plate is its bounding rectangle: the limit surface's area (by the quadrature of level 0)
    /// is a b within 1e-6 relative.
    bool rectangle_plate = false;
    std::vector<PlateLevel> levels;
    /// What the caller should tell the user (a tuning with no vertex to tune, ...).
    std::vector<std::string> warnings;
};

/// @brief Solves the plate on the planar control mesh (@p topology, @p X, z = 0) refined
///   0..options.levels times (solve_plate on each) and measures each level's deflection.
///   With a tuning, each tuned vertex's weights act on every level (tuned_weights.h); a mesh with no
///   interior extraordinary vertex of valence ≥ 5 is solved with Catmull–Clark's weights and a warning.
/// @throws InputError for levels or a decide_level outside 0..6, a decide_level without
///   PlateTuning::Auto, a ClampedNitsche support, load values of the wrong
///   size, a Function load without a function, a tuning with a scheme other than Catmull–Clark; otherwise as
///   solve_plate (closed or non-planar mesh, material out of range, a load that fails or is not finite)
[[nodiscard]] PlateStudy solve_plate_levels(const Topology& topology, const Points& X, const PlateLoad& load,
                                            const PlateStudyOptions& options);

}  // namespace limsurf
