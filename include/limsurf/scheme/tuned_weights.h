// Catmull–Clark with tuned extraordinary-vertex weights
// (iga-tuned-catmull-clark-weights, Fig. 1 and Table 1).
//
// At a smooth interior vertex v of valence n, the Catmull–Clark vertex rule is
//     v' = (α v + β Σ_j e_j + γ Σ_j f_j) / (α + n β + n γ)
// with e_j the n edge-neighbours of v and f_j the n new face points of the
// faces around v. Catmull–Clark's own weights are α = n(n−2), β = γ = 1
// (for n = 4: 8, 1, 1, the bicubic B-spline). Tuned weights change α, β, γ at
// extraordinary vertices only; every other rule (faces, edges, creases,
// boundaries) is unchanged.
#pragma once

#include <filesystem>
#include <map>
#include <string_view>

#include "limsurf/core/types.h"

namespace limsurf {

/// Unnormalised weights of the vertex rule (see the header comment).
struct VertexRuleWeights {
    double alpha = 0.0;  ///< weight of the vertex itself, > 0
    double beta = 1.0;   ///< weight of each edge-neighbour, >= 0
    double gamma = 1.0;  ///< weight of each new face point, >= 0
};

/// Catmull–Clark's own weights for valence @p n: α = n(n−2), β = γ = 1.
[[nodiscard]] VertexRuleWeights catmull_clark_weights(int valence) noexcept;

/// Weights per valence, optionally overridden per control vertex.
class TunedWeights {
  public:
    /// No overrides: every vertex uses catmull_clark_weights().
    TunedWeights() = default;

    /// The paper's valence-5 sets (Table 1): "cup" (α 13.4575, β = γ 0.999938)
    /// or "saddle" (α 13.9851, β = γ 0.824885); "catmull-clark" for none.
    /// @throws InputError for any other name
    [[nodiscard]] static TunedWeights preset(std::string_view name);

    /// Reads lines "valence alpha beta gamma" and "vertex INDEX alpha beta gamma"
    /// ('#' comments). @throws InputError naming file and line on bad input
    [[nodiscard]] static TunedWeights from_file(const std::filesystem::path& path);

    /// Weights for every vertex of valence @p valence (>= 3).
    /// @throws InputError on a valence < 3, a non-positive α or negative β, γ
    void set_valence(int valence, VertexRuleWeights weights);

    /// Weights for control vertex @p vertex, whatever its valence (the paper picks
    /// cup or saddle per vertex). Applies to the vertex and to its descendants:
    /// refinement keeps a vertex's index for its child (docs/conventions.md), so
    /// the index is a level-0 index (Hierarchy refuses one beyond the control mesh).
    /// @throws InputError as set_valence
    void set_vertex(Index vertex, VertexRuleWeights weights);

    /// The weights for @p vertex of valence @p valence: the vertex override, else
    /// the valence entry, else Catmull–Clark's.
    [[nodiscard]] VertexRuleWeights at(Index vertex, int valence) const;

    /// The largest vertex index with its own weights, or invalid_index when none.
    [[nodiscard]] Index largest_vertex() const noexcept {
        return by_vertex_.empty() ? invalid_index : by_vertex_.rbegin()->first;
    }

    /// True when no valence or vertex has been given weights.
    [[nodiscard]] bool is_catmull_clark() const noexcept { return by_valence_.empty() && by_vertex_.empty(); }

  private:
    std::map<int, VertexRuleWeights> by_valence_;
    std::map<Index, VertexRuleWeights> by_vertex_;
};

}  // namespace limsurf
