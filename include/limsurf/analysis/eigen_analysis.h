// Eigen-analysis of a subdivision scheme around one extraordinary vertex (or, for Doo–Sabin, one
// extraordinary face): the local subdivision matrix S of its R-ring neighbourhood, its spectrum
// block by block through the discrete Fourier transform of its rotational symmetry, Jordan
// structure, eigenvectors, the characteristic map, and the classical smoothness tests
// (iga-tuned-catmull-clark-weights §2.2–2.4; c2g0-sphere-scheme-biomembranes §2.1–2.2;
// docs/eigen.md).
//
// S is read off the scheme's own refinement (refine.h) of a local complex, not from formulas:
// the analysis checks the rules the library actually applies.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "limsurf/core/types.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/scheme/tuned_weights.h"

namespace limsurf {

/// What to analyse.
struct EigenRequest {
    SchemeKind scheme = SchemeKind::CatmullClark;  ///< CatmullClark, Loop, DooSabin or C2g0
    /// Valence of the extraordinary vertex (edges at it); Doo–Sabin: the degree of the
    /// extraordinary face. With `boundary`, the vertex has valence − 1 faces.
    int valence = 5;
    /// The vertex on a boundary (Catmull–Clark and Loop, SchemeOptions' boundary rule): no
    /// rotational symmetry, S is decomposed as a whole.
    bool boundary = false;
    /// Rings of the neighbourhood (face rings around the vertex; Doo–Sabin: around the face's
    /// corners); 0 = what the characteristic map needs: Catmull–Clark 2 (6n+1 vertices), Loop 2
    /// (3n+1), C2g0 3 (the paper's 19 at valence 3), Doo–Sabin 1 (4n).
    int rings = 0;
    SchemeOptions options;  ///< boundary rule and the like
    /// Tuned Catmull–Clark weights at the vertex (the paper's α, β, γ; tuned_weights.h).
    std::optional<VertexRuleWeights> weights;
};

/// One eigenvalue (a cluster of numerically equal ones) of one Fourier block.
struct EigenvalueEntry {
    std::complex<double> value;
    /// Fourier frequency k of its block (0..n−1), or −1 when S has no rotational symmetry.
    int frequency = 0;
    int algebraic = 1;               ///< algebraic multiplicity within the block
    int geometric = 1;               ///< geometric multiplicity within the block
    std::vector<int> jordan_blocks;  ///< sizes, largest first (all 1 when not defective)
    /// Right eigenvectors over the neighbourhood (#neighbourhood × geometric, in neighbourhood() order).
    Eigen::MatrixXcd eigenvectors;
};

/// The verdict of one classical test, with what it rests on.
struct SmoothnessTest {
    bool checked = false;  ///< false when the test does not apply or could not be run (see `detail`)
    bool passed = false;
    std::string detail;
};

/// The characteristic map sampled on the ring segment (the faces at the vertex minus their
/// half-size sub-faces at it).
struct CharacteristicMap {
    bool evaluated = false;
    std::string reason;         ///< why not, when not evaluated
    double min_jacobian = 0.0;  ///< min over the samples of det DΦ, with Φ oriented so that the largest is > 0
    double max_jacobian = 0.0;
    double winding_number = 0.0;  ///< of the image of the segment's outer boundary about Φ(vertex) = 0
    int samples = 0;
    /// Samples per face edge: face f's samples are (u, v) = (i, j)/resolution, i = 0..resolution,
    /// j = 0..resolution (0..resolution − i on triangles), in that order, face after face around the vertex.
    int resolution = 16;
    /// The sampled map as a mesh (quads or triangles): positions (x, y, 0) and faces, for writing out.
    Points positions;
    std::vector<std::vector<Index>> faces;
};

/// The result of analyse_scheme().
struct SchemeSpectrum {
    EigenRequest request;
    int rings = 0;
    /// Local subdivision matrix over the neighbourhood (sector-major order: the fixed centre, then
    /// sector 0's vertices, sector 1's in the same order, ...).
    Eigen::MatrixXd S;
    /// Per neighbourhood vertex: its sector (−1 for the centre; 0 for every vertex without symmetry).
    std::vector<int> sector;
    /// All eigenvalues, by decreasing modulus, then frequency.
    std::vector<EigenvalueEntry> eigenvalues;
    double dominant = 0.0;             ///< λ₀ (1 for an affine-invariant scheme)
    double subdominant = 0.0;          ///< λ = λ₁ = λ₂ (largest modulus after λ₀)
    int subdominant_multiplicity = 0;  ///< how many eigenvalues have λ's modulus (algebraic)
    double subsubdominant = 0.0;       ///< the next modulus after λ
    int subsubdominant_multiplicity = 0;
    /// ‖S P − P S‖ / ‖S‖ for the rotation P of the neighbourhood (0 when there is none).
    double symmetry_residual = 0.0;
    CharacteristicMap characteristic_map;
    SmoothnessTest
        c1_spectrum;  ///< λ₀ = 1 simple, λ₁ = λ₂ real, from frequencies 1 and n−1, non-defective, > all others
    SmoothnessTest c1;                 ///< c1_spectrum and a regular, injective characteristic map (Reif)
    SmoothnessTest bounded_curvature;  ///< every other eigenvalue |μ| ≤ λ²
    SmoothnessTest c2_necessary;  ///< (17): λ₃ = λ₄ = λ₅ = λ² from frequencies 0, 2, n−2, > all others
};

/// @brief Analyses @p request (docs/eigen.md).
/// @throws InputError for a valence below 3 (2 with a boundary), above max_limit_size, rings < 1
///   or > 8, weights for a scheme other than Catmull–Clark, a boundary with Doo–Sabin or C2g0, C2g0
///   at a valence other than 3 and 6; NumericalError when the neighbourhood is not invariant
///   under the rules (too few rings: it names the ring count needed)
[[nodiscard]] SchemeSpectrum analyse_scheme(const EigenRequest& request);

/// Closed forms from the literature, for checking: the subdominant eigenvalue of Catmull–Clark
/// at an interior vertex of valence n, (5 + cos(2π/n) + cos(π/n) √(2(9 + cos(2π/n)))) / 16
/// (Doo and Sabin 1978; Ball and Storry 1988), and of Loop, 3/8 + cos(2π/n)/4 (Loop 1987).
[[nodiscard]] double catmull_clark_subdominant(int valence);
[[nodiscard]] double loop_subdominant(int valence);

}  // namespace limsurf
