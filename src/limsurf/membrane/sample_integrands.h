// The integrands of the shape functionals at every sample of one element, and their local
// gradients (c2g0-sphere-scheme-biomembranes §3, (3.10)–(3.11); shape_functionals.h gives the
// definitions), computed for all samples of the element in one loop that the compiler vectorises
// across samples. Like element_products.h: one copy per instruction set, chosen at load time, no
// fused multiply–add, so the same bits on every CPU.
//
// Notation: x the position less the centroid, a = ∂u, b = ∂v, N = a × b, S = N·N = EG − F²,
// J = √S, L = N·∂uu, Mn = N·∂uv, Nn = N·∂vv, Q = G ∂uu − 2F ∂uv + E ∂vv, P = N·Q,
// T = L Nn − Mn², so that H = −P / (2 J³) (limit/surface_frame.h's sign: H = 1 on the unit
// sphere) and K = T / S². Then, per unit quadrature weight: A = J, V = x·N / 3, M = H J = −P / (2S),
// W = H² J = P² / (4 S² J), K J = T / (S J), and the harmonic energy s (E + m F + G) with s = 2/√3,
// m = −1 on triangles (the equilateral triangle, τ of (3.9)) and s = 1, m = 0 on squares.
#pragma once

#include <cstddef>

namespace limsurf::detail {

/// The rows of a sample's derivatives, in the order of the forward product's rows.
enum SampleRow : int { RowValue = 0, RowDu, RowDv, RowDuu, RowDuv, RowDvv };

/// Which rows of its local gradient each functional (in ShapeFunctional's order: area, volume,
/// mean curvature, Willmore, Gaussian, harmonic) depends on: [first, last). Only those rows are
/// written; the others are zero and the backward product skips them.
inline constexpr int local_rows_first[6] = {RowDu, RowValue, RowDu, RowDu, RowDu, RowDu};
inline constexpr int local_rows_last[6] = {RowDv + 1, RowDv + 1, RowDvv + 1, RowDvv + 1, RowDvv + 1, RowDv + 1};

/// One element's samples.
struct SampleBatch {
    std::ptrdiff_t n = 0;             ///< samples
    const double* rows = nullptr;     ///< (6 n) × 3, column-major: row r n + i is row r of sample i
    const double* weights = nullptr;  ///< n quadrature weights
    /// Subtracted from the positions: the volume 1/3 ∫ (x − c)·n dA about the control points'
    /// centroid c equals 1/3 ∫ x·n dA on a closed surface, and it stays translation invariant where
    /// the quadrature of ∫ n dA = 0 is not exact (near extraordinary vertices).
    double centroid[3] = {};
    bool triangle = true;  ///< the harmonic energy's metric
};

/// Computes, for every sample i of @p batch:
/// - values[f n + i]: functional f's integrand times the weight (f in ShapeFunctional's order);
/// - normal_area[c n + i]: coordinate c of w N;
/// - local (18 columns × 6 n rows, column-major, leading dimension 6 n): column 3 f + c, row
///   r n + i: the derivative of values[f n + i] with respect to coordinate c of row r, for the rows
///   [local_rows_first[f], local_rows_last[f]) only (the rest is left as it is).
/// - degenerate[i]: 1 where the tangents are (nearly) parallel (S ≤ 1e-28 E G) or a value is not
///   finite, else 0; the other outputs of such a sample are meaningless.
/// Returns the first degenerate sample, or -1.
std::ptrdiff_t sample_integrands(const SampleBatch& batch, double* values, double* normal_area, double* local,
                                 double* degenerate) noexcept;

}  // namespace limsurf::detail
