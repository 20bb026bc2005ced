// The second derivatives of the shape functionals' integrands at every sample of one element, with
// respect to the sample's position and derivatives (sample_integrands.h's rows), for the Hessians
// of ShapeFunctionals::hessian (shape_functionals.h).
//
// Each 18 × 18 Hessian is taken by central differences of the exact local gradients of
// sample_integrands — the same code that gives the values and gradients, so no second copy of
// the formulas — with one step h = 2^-17 ℓ for all 18 inputs, ℓ the sample's tangent size
// max(|∂u|∞, |∂v|∞) rounded down to a power of two. The integrands are rational in the derivatives
// with no scale of their own beyond ℓ, so the truncation error is O((h/ℓ)²) ≈ 4e-11 and the
// rounding error O(ε ℓ/h) ≈ 3e-11, relative; the area, volume and harmonic integrands are at most
// quadratic in each input, where central differences are exact up to rounding.
#pragma once

#include <cstddef>
#include <vector>

#include "limsurf/membrane/sample_integrands.h"

namespace limsurf::detail {

/// The inputs of one sample: row r (SampleRow), coordinate c at index 3 r + c.
inline constexpr int sample_inputs = 18;

/// Computes, for every sample i of @p batch, hessians[i · 324 + 18 p + q]: the second derivative of
/// Σ_f coefficients[f] values[f n + i] (sample_integrands' weighted integrands, f in
/// ShapeFunctional's order) with respect to inputs p and q, symmetrised.
/// The volume's centroid is held fixed (batch.centroid).
/// @p scratch is resized as needed (reuse it across calls).
/// Returns the first sample that is degenerate (sample_integrands) at or next to its inputs, or -1.
std::ptrdiff_t sample_hessians(const SampleBatch& batch, const double* coefficients, double* hessians,
                               std::vector<double>& scratch);

}  // namespace limsurf::detail
