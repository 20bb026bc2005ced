// Volume forms laid out for evaluation, from the shipped tables or generated on
// demand (private to src/limsurf/volume).
#pragma once

#include <cstdint>
#include <vector>

#include "limsurf/scheme/scheme.h"

namespace limsurf::detail {

/// An alternating trilinear form vol(f) = Σ_{i<j<k} c_ijk det(p_i, p_j, p_k), grouped by
/// the pair (j, k): vol = Σ_{(j,k)} q_jk · (p_j × p_k) with q_jk = Σ_i c_ijk p_i, so that
/// each cross product is formed once.
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
    /// The regular Catmull–Clark facet is a bicubic patch: evaluated as ⅓∫ x·(x_s × x_t) by a
    /// 5×5 Gauss rule, exact for its degree-(8,8) integrand and the same form (Ŷ is the
    /// alternation of the divergence-theorem integrals), in about half the time.
    bool bicubic = false;

    /// @brief The facet's volume from its m points @p p (m × 3, row-major); adds the gradient
    ///   to @p gradient (m × 3, row-major) unless it is null.
    double evaluate(const double* p, double* gradient) const;
    /// evaluate() by the coefficients, also for the bicubic facet (tests compare the two).
    double evaluate_by_coefficients(const double* p, double* gradient) const;
};

/// Lays out coefficients c_ijk (i < j < k, lexicographic) for evaluation.
[[nodiscard]] VolumeForm make_volume_form(SchemeKind scheme, int type, std::vector<double> coefficients);

/// True when the library ships the form of this scheme and type.
[[nodiscard]] bool is_shipped(SchemeKind scheme, int type);

/// @brief The shipped form, or the form generated now in double precision from the shipped
///   regular one (Corollary 2, form_generator.h).
[[nodiscard]] VolumeForm load_volume_form(SchemeKind scheme, int type);

}  // namespace limsurf::detail
