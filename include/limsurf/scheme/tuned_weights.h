// Catmull–Clark with tuned extraordinary-vertex weights
// (iga-tuned-catmull-clark-weights, Fig. 1 and Table 1).
//
// α, β, γ are an extraordinary vertex v's *own* unnormalised weights in the three rules of
// Fig. 1 (each rule then normalised to sum to one), every other point weighing 1:
//     vertex rule  v' = (α v + Σ_j e_j + Σ_j F_j) / (α + 2n)       (e_j: the n edge-neighbours,
//                                                                  F_j: the n new face points)
//     edge rule    E  = (β v + w + F_0 + F_1) / (β + 3)           (edge (v, w), its two new face points)
//     face rule    F  = (γ v + Σ other corners) / (γ + m − 1)     (an m-gon at v)
// Catmull–Clark's own weights are α = n(n−2), β = γ = 1 (for n = 4: 8, 1, 1, the bicubic
// B-spline). When both ends of an edge (or several corners of a face) have own weights, each
// end (corner) brings its own. The weights act where the smooth vertex rule acts (Smooth and
// Dart vertices, the smooth part of a semi-sharp blend); boundary, crease and corner vertices
// keep β = γ = 1. Read this way, Table 1's weights give the subdominant eigenvalues 0.5500 (cup)
// and 0.5850 (saddle) (`limsurf eigen`, docs/eigen.md). Until issue 13 β and γ were read as the
// neighbours' weights in the vertex rule, which is a different scheme.
#pragma once

#include <filesystem>
#include <map>
#include <string_view>

#include "limsurf/core/types.h"

namespace limsurf {

/// An extraordinary vertex's own unnormalised weights in its three rules (see the header comment).
struct VertexRuleWeights {
    double alpha = 0.0;  ///< its weight in its vertex rule (neighbours and face points weigh 1), > 0
    double beta = 1.0;   ///< its weight in the edge rule of each incident edge, >= 0
    double gamma = 1.0;  ///< its weight in the face rule of each incident face, >= 0
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
