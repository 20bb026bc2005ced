// Quadrature samples of the limit surface, with their limit weights computed once.
//
// A LimitSampler places a quadrature rule (square_rule on Catmull–Clark ptex
// faces, triangle_rule on Loop ptex faces; quadrature/rules.h) on every ptex face
// that has a limit surface and stores, for each sample s, its point (face, u, v),
// its parameter-domain weight weight(s) and the sparse limit weights (value, ∂u,
// ∂v, ∂uu, ∂uv, ∂vv) over the control vertices the surface depends on there.
// Storage is CSR-like: offsets into arrays of vertex indices and of
// 6 weights per entry (column-major, 6 × k per sample), in blocks of consecutive samples (a
// sample's entries are contiguous; two samples' need not be). After construction,
// integrating anything over the limit surface of control points X (#V × 3) is a
// sequence of sparse products: evaluate(X) gives every sample's 6 × 3 derivatives.
//
// Accuracy near extraordinary vertices. The limit surface is C2 (a polynomial per
// tile) away from extraordinary vertices, but at an extraordinary vertex (valence
// != 4 for Catmull–Clark, != 6 for Loop, a boundary vertex of another valence than
// half that, a corner, a vertex with a semi-sharp crease, or a crease vertex other
// than a regular vertex crossed straight by one infinitely sharp crease — each side
// of that one is a B-spline patch with phantom points) it is only C1 and its
// parameterisation is piecewise polynomial on infinitely many rings
// of Stam's tiles shrinking towards the vertex. A Gauss rule on the whole ptex face
// then integrates a non-smooth function and converges slowly (algebraically, at a
// rate set by the subdominant eigenvalue) instead of exactly. With
// `subdivide_near_extraordinary = k`, each ptex face whose corner is such a vertex
// is split into quadtree tiles towards that corner, k levels deep (the corner cell
// is refined again, the three others are integrated at their level; triangles are
// split 1-to-4 likewise, the corner triangle refined again): each ring of Stam's
// tiles down to 2^-k gets its own rule, on which the integrand is polynomial, and
// only the innermost cell (area 4^-k of the face) is integrated inexactly.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/limit/limit_basis.h"

namespace limsurf {

/// Options of a LimitSampler.
struct SamplerOptions {
    int degree = 8;                        ///< degree of the rule per tile (square_rule / triangle_rule)
    int subdivide_near_extraordinary = 0;  ///< tile levels towards irregular corners, 0..30
    int num_threads = 0;                   ///< threads for construction and evaluate(); 0: hardware concurrency
};

/// The points and parameter-domain weights of quadrature samples.
struct QuadratureSamples {
    std::vector<SurfacePoint> points;
    std::vector<double> weights;
};

/// @brief The samples a LimitSampler with @p options places on ptex faces [first_ptex_face,
///   last_ptex_face), in its order, without their limit weights: for one pass over the samples
///   that needs no stored weights (measure_with_error evaluates each sample once and keeps nothing).
/// @throws InputError as LimitSampler's constructor
[[nodiscard]] QuadratureSamples quadrature_samples(const LimitBasis& basis, const SamplerOptions& options,
                                                   Index first_ptex_face, Index last_ptex_face);

/// @brief Quadrature samples of a limit surface with precomputed sparse limit weights.
/// @details Immutable after construction; evaluate() is thread-safe. Does not keep a
///   reference to the basis.
class LimitSampler {
  public:
    /// @brief Places the rules and evaluates the limit weights (with second derivatives) once.
    /// @throws InputError when the degree is out of the rules' range or the tile level is outside 0..30
    LimitSampler(const LimitBasis& basis, const SamplerOptions& options);
    /// @brief The samples of ptex faces [first_ptex_face, last_ptex_face) only: a large mesh in
    ///   pieces, so that the weights of all its samples need not be held at once.
    /// @throws InputError as above, or when the range is not within 0..basis.num_ptex_faces()
    LimitSampler(const LimitBasis& basis, const SamplerOptions& options, Index first_ptex_face, Index last_ptex_face);
    /// Shorthand for LimitSampler(basis, {degree, subdivide_near_extraordinary}).
    LimitSampler(const LimitBasis& basis, int degree, int subdivide_near_extraordinary = 0);

    [[nodiscard]] Index num_samples() const noexcept { return static_cast<Index>(points_.size()); }
    /// Number of control vertices (rows of the X the sampler expects).
    [[nodiscard]] Index num_vertices() const noexcept { return num_vertices_; }
    [[nodiscard]] const SamplerOptions& options() const noexcept { return options_; }
    [[nodiscard]] ParameterDomain domain() const noexcept { return domain_; }

    /// Ptex point of sample @p s.
    [[nodiscard]] const SurfacePoint& point(Index s) const { return points_[static_cast<std::size_t>(s)]; }
    /// Parameter-domain weight of sample @p s (weights of a face sum to 1 on the square, 1/2 on the triangle).
    [[nodiscard]] double weight(Index s) const { return weights_[static_cast<std::size_t>(s)]; }
    /// Control vertices sample @p s depends on.
    [[nodiscard]] std::span<const Index> vertices(Index s) const;
    /// Its limit weights, 6 × vertices(s).size(): rows value, ∂u, ∂v, ∂uu, ∂uv, ∂vv.
    [[nodiscard]] Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> limit_weights(Index s) const;

    /// @brief Position and derivatives (6 × 3, rows as LimitWeights) at sample @p s.
    /// @throws InputError when X does not have num_vertices() rows
    [[nodiscard]] Eigen::Matrix<double, 6, 3> evaluate(const Points& X, Index s) const;
    /// @brief evaluate(X, s) for every sample, in parallel.
    /// @throws InputError when X does not have num_vertices() rows
    [[nodiscard]] std::vector<Eigen::Matrix<double, 6, 3>> evaluate(const Points& X) const;

  private:
    SamplerOptions options_;
    ParameterDomain domain_ = ParameterDomain::Quad;
    Index num_vertices_ = 0;
    std::vector<SurfacePoint> points_;
    std::vector<double> weights_;
    /// Consecutive samples' vertices and limit weights (6 per entry, column-major per sample), filled
    /// by one construction thread up to a fixed capacity and never moved after (sampler.cpp says why).
    struct Block {
        std::size_t first_offset = 0;  ///< offsets_ of its first sample
        std::vector<Index> vertices;
        std::vector<double> limit;
    };
    /// Entries per block (a sample with more gets a block of its own): 3.5 MiB of storage.
    static constexpr std::size_t block_entries = std::size_t{1} << 16;
    std::vector<Block> blocks_;
    std::vector<std::uint32_t> block_of_;  // per sample: its block
    std::vector<std::size_t> offsets_;     // num_samples + 1 entry offsets, counted across the blocks
};

}  // namespace limsurf
