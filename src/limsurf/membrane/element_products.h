// The two small products of the shape functionals' element kernels (shape_functionals.cpp):
// forwards, the samples' positions and derivatives from the element's control points; backwards,
// the samples' local gradients pulled back to those control points. Dense for every element, and
// sum-factorised for a regular Catmull–Clark one (TensorElement below).
//
// Why not Eigen: at these sizes (a Loop element: 96 × 12 times 12 × 3, and 12 × 80 times 80 × 9)
// Eigen's general product packs both operands for its blocked kernel on every call, which took
// as long as the arithmetic, and the library is built for the distribution's baseline x86-64
// (SSE2, two doubles per instruction). These loops are compiled once per instruction set (SSE2,
// AVX2, AVX-512 where the compiler and the platform support it; detail/target_clones.h), each in
// vectors as wide as its registers, and the widest copy the CPU runs is called.
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

/// A regular Catmull–Clark element: a bicubic B-spline patch sampled on an n × n tensor grid (the
/// square Gauss rule, sample n j + i at (t_i, t_j)). Its kernel is a sum of products of
/// one-dimensional tables, K(r n² + n j + i, slot(a, b)) = N_a^(ku)(t_i) N_b^(kv)(t_j) with (ku, kv)
/// the orders of row r's derivatives in u and v, so both products go one direction at a time (sum
/// factorisation): at n = 5, 7 740 multiply–adds per element for the forward product and the
/// backward ones of W, A and M against 20 400 through the dense kernel.
inline constexpr std::ptrdiff_t max_tensor_samples = 16;  ///< per direction

/// The orders (ku, kv) of each row's derivatives in u and in v, in the rows' order (value, ∂u, ∂v,
/// ∂uu, ∂uv, ∂vv; sample_integrands.h's SampleRow).
inline constexpr int tensor_row_u[6] = {0, 1, 0, 2, 1, 0};
inline constexpr int tensor_row_v[6] = {0, 0, 1, 0, 1, 2};

struct TensorElement {
    std::ptrdiff_t n = 0;  ///< samples per direction, 1 ≤ n ≤ max_tensor_samples
    /// basis[(4 k + a) n + i] = the k-th derivative (k = 0, 1, 2) of the uniform cubic B-spline N_a
    /// (a = 0…3; N_0 = (1 − t)³/6 … N_3 = t³/6) at t_i; basis_by_node[(n k + i) 4 + a] the same.
    const double* basis = nullptr;
    const double* basis_by_node = nullptr;
    const int* slot = nullptr;  ///< slot[a + 4 b]: the element's slot (0…15) of control point (a, b)
};

/// The forward product of a tensor element: rows [first_row, 6) of out (value, ∂u, ∂v, ∂uu, ∂uv,
/// ∂vv; row r n² + n j + i, column-major, three columns, leading dimension ld_out ≥ 6 n²; the other
/// rows are left as they are) from P (16 slots × 3, column-major, leading dimension 16). With
/// (ku, kv) row r's orders, N the tables and p(a, b) = P(slot[a + 4 b], c):
///   h(kv, j, a) = Σ_b N_b^(kv)(t_j) p(a, b), summed over b = 0…3 from +0;
///   out(r n² + n j + i, c) = Σ_a N_a^(ku)(t_i) h(kv, j, a), summed over a = 0…3 from +0.
/// Preconditions: first_row in [0, 6); out overlaps neither P nor the tables.
void tensor_forward(const TensorElement& element, const double* P, int first_row, double* out,
                    std::ptrdiff_t ld_out) noexcept;

/// The backward product of a tensor element over rows [first_row, last_row) of L (layout of
/// tensor_forward's out, leading dimension ld_l, three columns): out(slot, c) = Σ_r K(r, slot) L(r, c)
/// for the 16 slots, row-major with leading dimension ld_out ≥ 3 (columns 0–2 written). Summed as
///   g(kv, j, a) = Σ_r Σ_i N_a^(ku)(t_i) L(r n² + n j + i, c) over the rows of v-order kv in
///   increasing r, then i = 0…n−1, from +0;
///   out(slot[a + 4 b], c) = Σ_kv Σ_j N_b^(kv)(t_j) g(kv, j, a) over the v-orders present in
///   increasing kv, then j = 0…n−1, from +0.
/// Preconditions: 0 ≤ first_row ≤ last_row ≤ 6; out overlaps neither L nor the tables.
void tensor_backward(const TensorElement& element, const double* L, std::ptrdiff_t ld_l, int first_row, int last_row,
                     double* out, std::ptrdiff_t ld_out) noexcept;

}  // namespace limsurf::detail
