// The two small dense products of the shape functionals' element kernels (shape_functionals.cpp):
// forwards, the samples' positions and derivatives from the element's control points; backwards,
// the samples' local gradients pulled back to those control points.
//
// Why not Eigen: at these sizes (a Loop element: 96 × 12 times 12 × 3, and 12 × 80 times 80 × 9)
// Eigen's general product packs both operands for its blocked kernel on every call, which took
// as long as the arithmetic, and the library is built for the distribution's baseline x86-64
// (SSE2, two doubles per instruction). These loops are compiled once per instruction set (SSE2,
// AVX2, AVX-512 where the compiler and the platform support function multi-versioning) and the
// widest one the CPU has is chosen when the library is loaded.
//
// Every entry is summed in an order fixed by these loops alone, with no fused multiply–add (the
// file is compiled with -ffp-contract=off): the same bits on every CPU, for every instruction set
// and every thread count.
#pragma once

#include <cstddef>

namespace limsurf::detail {

/// out = K · P, the forward pass.
/// K: rows × cols, column-major, leading dimension ld_k ≥ rows; P: cols × 3, column-major
/// (leading dimension cols); out: rows × 3, column-major, leading dimension ld_out ≥ rows.
/// out(r, c) = Σ_j K(r, j) P(j, c), summed over j = 0, 1, … from +0.
/// Preconditions: rows, cols ≥ 0; out overlaps neither K nor P.
void element_forward(const double* K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols, const double* P,
                     double* out, std::ptrdiff_t ld_out) noexcept;

/// out = Kᵀ · L, the backward pass, from K stored by rows.
/// Kt: K (rows × cols) row-major, leading dimension ld_kt ≥ cols rounded up to a multiple of 8
/// (the entries beyond cols are read but do not reach out); L: rows × width, column-major, leading
/// dimension ld_l ≥ rows; out: cols × width, row-major, leading dimension ld_out ≥ width.
/// out(j, w) = Σ_r K(r, j) L(r, w), summed over r = 0, 1, … from +0.
/// Preconditions: rows, cols, width ≥ 0; out overlaps neither Kt nor L.
void element_backward(const double* Kt, std::ptrdiff_t ld_kt, std::ptrdiff_t rows, std::ptrdiff_t cols, const double* L,
                      std::ptrdiff_t ld_l, std::ptrdiff_t width, double* out, std::ptrdiff_t ld_out) noexcept;

}  // namespace limsurf::detail
