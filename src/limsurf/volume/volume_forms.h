// Volume forms laid out for evaluation, from the shipped tables or generated on
// demand (private to src/limsurf/volume).
#pragma once

#include <cstdint>
#include <vector>

#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// Facets of at most this many points are evaluated through their pair weights (below); larger
/// ones, which only generated forms of valence > 12 (Catmull–Clark) or > 26 (Loop) have, through
/// their nonzero coefficients, whose number grows as m³/6 rather than m³/2.
constexpr int max_pair_form_points = 32;

/// An alternating trilinear form vol(f) = Σ_{i<j<k} c_ijk det(p_i, p_j, p_k), laid out two ways:
/// - grouped by the pair (j, k): vol = Σ_{(j,k)} q_jk · (p_j × p_k) with q_jk = Σ_i c_ijk p_i, so
///   that each cross product is formed once (`pairs`, `term_i`, `term_c`);
/// - as the gradient's linear map from the pairs' cross products (`pair_weights`):
///   ∂vol/∂p_i = Σ_t W[t][i] (p_j × p_k) over the pairs t = (j, k), j < k, in lexicographic order,
///   where W[t][i] is c_ijk, −c_jik or c_jki as i is below, between or above j and k (0 when it is
///   one of them), and vol = ⅓ Σ_i p_i · ∂vol/∂p_i (Euler: the form is homogeneous of degree 3).
///   Dense, m × m(m−1)/2, but a product whose every sum runs in a fixed order across vector lanes,
///   2–4× faster than the coefficients (and 4× faster than a 5×5 Gauss rule on the regular
///   Catmull–Clark facet's bicubic patch, which the tests keep as a witness of that form).
struct VolumeForm {
    SchemeKind scheme = SchemeKind::CatmullClark;
    int type = 0;
    int size = 0;  ///< m: the facet's number of control points
    struct Pair {
        std::uint16_t j = 0;
        std::uint16_t k = 0;
        std::uint32_t begin = 0;  ///< terms [begin, end)
        std::uint32_t end = 0;
    };
    std::vector<Pair> pairs;
    std::vector<std::uint16_t> term_i;
    std::vector<double> term_c;
    std::vector<double> coefficients;  ///< all C(m,3), lexicographic
    /// W, row t (pair t) padded with zeros to `lanes` (m rounded up to 8) entries; empty when
    /// m > max_pair_form_points.
    int lanes = 0;
    std::vector<double> pair_weights;

    /// @brief The facet's volume from its m points @p p (m × 3, row-major); adds the gradient
    ///   to @p gradient (m × 3, row-major) unless it is null. By the pair weights where there are
    ///   some, else by the coefficients.
    double evaluate(const double* p, double* gradient) const;
    /// evaluate() by the coefficients, also where there are pair weights (tests compare the two).
    double evaluate_by_coefficients(const double* p, double* gradient) const;
    /// evaluate() by the pair weights; precondition: `lanes` > 0. The same bits with and without
    /// a gradient, and in every instruction-set copy of its kernel.
    double evaluate_by_pairs(const double* p, double* gradient) const;
};

/// Lays out coefficients c_ijk (i < j < k, lexicographic) for evaluation.
[[nodiscard]] VolumeForm make_volume_form(SchemeKind scheme, int type, std::vector<double> coefficients);

/// True when the library ships the form of this scheme and type.
[[nodiscard]] bool is_shipped(SchemeKind scheme, int type);

/// @brief The shipped form, or the form generated now in double precision from the shipped
///   regular one (Corollary 2, form_generator.h).
[[nodiscard]] VolumeForm load_volume_form(SchemeKind scheme, int type);

}  // namespace limsurf::detail
