// The generator of the volume forms (volume-trilinear-forms, Corollaries 1 and 2),
// templated on the scalar type: exact rationals (GMP, tools/volume_forms) for the
// regular forms, 100-digit floats for the irregular ones, double for the forms the
// library generates on demand beyond the shipped tables. Private to
// src/limsurf/volume and the generator tool.
//
// A volume form of facet type τ is stored as an alternating trilinear form Ŷ^τ by its
// coefficients c_ijk for i < j < k (lexicographic order, C(m,3) of them):
//   vol(f) = Σ_{i<j<k} c_ijk det(p_i, p_j, p_k).
// Alternating forms are the paper's Ŷ (its Â is Ŷ/2 as a tensor). Because the
// regular form is alternating, Corollary 2 keeps every irregular form alternating,
// and on alternating tensors F - I is invertible (Lemma 1: the null vector v⊗v⊗v is
// symmetric), so Ŷ^τ is unique.
//
//   Regular (Corollary 1): the fixed points of E = Σ_h (S^h)^{⊗3} among alternating
//   forms with the facet's rotation and mirror symmetries form a line; it is
//   calibrated on the degenerate cube (Catmull–Clark, Doo–Sabin) or tetrahedron (Loop)
//   whose limit surface is that polyhedron. Solved exactly on the orbits of the symmetry
//   group (≈ C(m,3)/8 unknowns).
//   Irregular (Corollary 2): Ŷ^τ = b + F Ŷ^τ with F = (S^4)^{⊗3} and b the three regular
//   children's pull-backs, summed as a Neumann series by repeated squaring:
//   y ← y + (S^4)^{2^j ⊗3} y, which converges like (λ_1 λ_2)^{2^j}.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <numbers>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"
#include "limsurf/volume/facet_seed.h"

namespace limsurf::detail {

/// cos(2π d / n) in the scalar type (specialised per scalar: double below, GMP rationals and
/// floats in tools/volume_forms/multiprecision.h).
template <class Scalar>
Scalar cos_two_pi(int d, int n);

template <>
inline double cos_two_pi<double>(int d, int n) {
    return std::cos(2.0 * std::numbers::pi * static_cast<double>(d) / static_cast<double>(n));
}

/// Dense row-major matrix of any scalar.
template <class Scalar>
struct Dense {
    int rows = 0;
    int cols = 0;
    std::vector<Scalar> a;
    Dense() = default;
    Dense(int r, int c) : rows(r), cols(c), a(static_cast<std::size_t>(r) * static_cast<std::size_t>(c), Scalar(0)) {}
    Scalar& operator()(int r, int c) {
        return a[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c)];
    }
    const Scalar& operator()(int r, int c) const {
        return a[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + static_cast<std::size_t>(c)];
    }
};

/// Number of coefficients of an alternating form on m points: C(m, 3).
inline int num_alternating(int m) {
    return m * (m - 1) * (m - 2) / 6;
}

/// Position of (i < j < k) in the lexicographic list of C(m,3) coefficients.
inline int alternating_index(int m, int i, int j, int k) {
    // Triples before first index i, then pairs before j within i, then k.
    int index = 0;
    for (int a = 0; a < i; ++a) {
        index += (m - a - 1) * (m - a - 2) / 2;
    }
    for (int b = i + 1; b < j; ++b) {
        index += m - b - 1;
    }
    return index + (k - j - 1);
}

/// Sorts (a, b, c) and returns the sign of the permutation, 0 when two are equal.
inline int sort_triple(std::array<int, 3>& t) {
    int sign = 1;
    const auto swap_if = [&](int x, int y) {
        if (t[static_cast<std::size_t>(x)] > t[static_cast<std::size_t>(y)]) {
            std::swap(t[static_cast<std::size_t>(x)], t[static_cast<std::size_t>(y)]);
            sign = -sign;
        }
    };
    swap_if(0, 1);
    swap_if(1, 2);
    swap_if(0, 1);
    return (t[0] == t[1] || t[1] == t[2]) ? 0 : sign;
}

// --- exact subdivision stencils -------------------------------------------------

/// Accumulates weights per parent vertex.
template <class Scalar>
using Stencil = std::map<Index, Scalar>;

/// The stencil of child vertex @p c of one @p scheme step of @p parent, in the scalar type,
/// with the rules refine.h implements (smooth interior rules; the caller guarantees that
/// the child's parent element is interior and smooth).
template <class Scalar>
Stencil<Scalar> child_stencil(const Topology& parent, const Level& level, SchemeKind scheme, Index c) {
    Stencil<Scalar> s;
    const auto add_face_centroid = [&](Index f, const Scalar& w) {
        const auto verts = parent.face_vertices(f);
        const Scalar share = w / Scalar(static_cast<int>(verts.size()));
        for (const Index v : verts) {
            s[v] += share;
        }
    };
    if (scheme == SchemeKind::DooSabin) {
        const ParentCorner pc = doo_sabin_parent_corner(parent, c);
        const auto verts = parent.face_vertices(pc.face);
        const int n = static_cast<int>(verts.size());
        for (int j = 0; j < n; ++j) {
            const int d = ((j - pc.corner) % n + n) % n;
            const Scalar w = d == 0 ? Scalar(n + 5) / Scalar(4 * n)
                                    : (Scalar(3) + Scalar(2) * cos_two_pi<Scalar>(d, n)) / Scalar(4 * n);
            s[verts[static_cast<std::size_t>(j)]] += w;
        }
        return s;
    }
    const auto kind = level.provenance.vertex_parent_kind[static_cast<std::size_t>(c)];
    const Index p = level.provenance.vertex_parent[static_cast<std::size_t>(c)];
    if (kind == ParentKind::Face) {
        add_face_centroid(p, Scalar(1));
        return s;
    }
    if (kind == ParentKind::Edge) {
        const auto ends = parent.edge_vertices(p);
        if (scheme == SchemeKind::CatmullClark) {
            s[ends[0]] += Scalar(1) / Scalar(4);
            s[ends[1]] += Scalar(1) / Scalar(4);
            for (const Index f : parent.edge_faces(p)) {
                add_face_centroid(f, Scalar(1) / Scalar(4));
            }
        } else {
            s[ends[0]] += Scalar(3) / Scalar(8);
            s[ends[1]] += Scalar(3) / Scalar(8);
            for (const Index f : parent.edge_faces(p)) {
                for (const Index v : parent.face_vertices(f)) {
                    if (v != ends[0] && v != ends[1]) {
                        s[v] += Scalar(1) / Scalar(8);
                    }
                }
            }
        }
        return s;
    }
    const int n = static_cast<int>(parent.valence(p));
    if (scheme == SchemeKind::CatmullClark) {
        // (n-2)/n v + 1/n² Σ neighbours + 1/n² Σ face centroids
        const Scalar nn = Scalar(n * n);
        s[p] += Scalar(n - 2) / Scalar(n);
        for (const Index e : parent.vertex_edges(p)) {
            s[parent.other_vertex(e, p)] += Scalar(1) / nn;
        }
        for (const Index f : parent.vertex_faces(p)) {
            add_face_centroid(f, Scalar(1) / nn);
        }
    } else {
        // Loop: β = (5/8 - (3/8 + cos(2π/n)/4)²) / n per neighbour.
        const Scalar t = Scalar(3) / Scalar(8) + cos_two_pi<Scalar>(1, n) / Scalar(4);
        const Scalar beta = (Scalar(5) / Scalar(8) - t * t) / Scalar(n);
        s[p] += Scalar(1) - Scalar(n) * beta;
        for (const Index e : parent.vertex_edges(p)) {
            s[parent.other_vertex(e, p)] += beta;
        }
    }
    return s;
}

/// S^h: rows the child ring's points, columns the parent ring's points.
/// @throws UnsupportedError when a child point depends on a vertex outside the parent ring
template <class Scalar>
Dense<Scalar> facet_subdivision_matrix(const FacetSeed& seed, const FacetRing& parent_ring,
                                       const FacetRing& child_ring) {
    std::unordered_map<Index, int> column;
    for (std::size_t i = 0; i < parent_ring.points.size(); ++i) {
        column.emplace(parent_ring.points[i], static_cast<int>(i));
    }
    LIMSURF_CHECK(column.size() == parent_ring.points.size(), UnsupportedError,
                  "the seed facet's one-ring repeats a vertex (internal error)");
    Dense<Scalar> S(static_cast<int>(child_ring.points.size()), static_cast<int>(parent_ring.points.size()));
    for (std::size_t a = 0; a < child_ring.points.size(); ++a) {
        for (const auto& [v, w] : child_stencil<Scalar>(seed.parent, seed.child, seed.scheme, child_ring.points[a])) {
            const auto it = column.find(v);
            LIMSURF_CHECK(it != column.end(), UnsupportedError,
                          "a child of the seed facet depends on a vertex outside its one-ring (internal error)");
            S(static_cast<int>(a), it->second) += w;
        }
    }
    return S;
}

// --- trilinear forms as dense tensors -------------------------------------------

/// Dense m×m×m tensor, index (i*m + j)*m + k.
template <class Scalar>
struct Tensor3 {
    int m = 0;
    std::vector<Scalar> a;
    explicit Tensor3(int size = 0)
        : m(size), a(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * static_cast<std::size_t>(size),
                     Scalar(0)) {}
    Scalar& operator()(int i, int j, int k) { return a[index(i, j, k)]; }
    const Scalar& operator()(int i, int j, int k) const { return a[index(i, j, k)]; }
    [[nodiscard]] std::size_t index(int i, int j, int k) const {
        const auto n = static_cast<std::size_t>(m);
        return (static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)) * n + static_cast<std::size_t>(k);
    }
};

/// The alternating tensor of a coefficient list.
template <class Scalar>
Tensor3<Scalar> alternating_tensor(int m, const std::vector<Scalar>& coefficients) {
    Tensor3<Scalar> y(m);
    int index = 0;
    for (int i = 0; i < m; ++i) {
        for (int j = i + 1; j < m; ++j) {
            for (int k = j + 1; k < m; ++k) {
                const Scalar& c = coefficients[static_cast<std::size_t>(index++)];
                y(i, j, k) = c;
                y(j, k, i) = c;
                y(k, i, j) = c;
                y(j, i, k) = -c;
                y(i, k, j) = -c;
                y(k, j, i) = -c;
            }
        }
    }
    return y;
}

/// The coefficients of the alternating part of @p y (the mean of its six signed permutations).
template <class Scalar>
std::vector<Scalar> alternating_part(const Tensor3<Scalar>& y) {
    std::vector<Scalar> out;
    out.reserve(static_cast<std::size_t>(num_alternating(y.m)));
    for (int i = 0; i < y.m; ++i) {
        for (int j = i + 1; j < y.m; ++j) {
            for (int k = j + 1; k < y.m; ++k) {
                out.push_back((y(i, j, k) + y(j, k, i) + y(k, i, j) - y(j, i, k) - y(i, k, j) - y(k, j, i)) /
                              Scalar(6));
            }
        }
    }
    return out;
}

/// Pull-back z_ijk = Σ_abc y_abc S_ai S_bj S_ck of a form on S's rows to S's columns.
template <class Scalar>
Tensor3<Scalar> pull_back(const Dense<Scalar>& S, const Tensor3<Scalar>& y) {
    const int mc = S.rows;
    const int m = S.cols;
    // Mode 1: t1[i][b][c], then mode 2: t2[i][j][c], then mode 3: z[i][j][k].
    std::vector<Scalar> t1(static_cast<std::size_t>(m) * static_cast<std::size_t>(mc) * static_cast<std::size_t>(mc),
                           Scalar(0));
    const auto mc2 = static_cast<std::size_t>(mc) * static_cast<std::size_t>(mc);
    for (int a = 0; a < mc; ++a) {
        for (int i = 0; i < m; ++i) {
            const Scalar& s = S(a, i);
            if (s == 0) {
                continue;
            }
            const std::size_t src = static_cast<std::size_t>(a) * mc2;
            const std::size_t dst = static_cast<std::size_t>(i) * mc2;
            for (std::size_t bc = 0; bc < mc2; ++bc) {
                t1[dst + bc] += s * y.a[src + bc];
            }
        }
    }
    std::vector<Scalar> t2(static_cast<std::size_t>(m) * static_cast<std::size_t>(m) * static_cast<std::size_t>(mc),
                           Scalar(0));
    for (int i = 0; i < m; ++i) {
        for (int b = 0; b < mc; ++b) {
            for (int j = 0; j < m; ++j) {
                const Scalar& s = S(b, j);
                if (s == 0) {
                    continue;
                }
                const std::size_t src =
                    (static_cast<std::size_t>(i) * static_cast<std::size_t>(mc) + static_cast<std::size_t>(b)) *
                    static_cast<std::size_t>(mc);
                const std::size_t dst =
                    (static_cast<std::size_t>(i) * static_cast<std::size_t>(m) + static_cast<std::size_t>(j)) *
                    static_cast<std::size_t>(mc);
                for (int c = 0; c < mc; ++c) {
                    t2[dst + static_cast<std::size_t>(c)] += s * t1[src + static_cast<std::size_t>(c)];
                }
            }
        }
    }
    Tensor3<Scalar> z(m);
    for (std::size_t ij = 0; ij < static_cast<std::size_t>(m) * static_cast<std::size_t>(m); ++ij) {
        for (int c = 0; c < mc; ++c) {
            const Scalar& t = t2[ij * static_cast<std::size_t>(mc) + static_cast<std::size_t>(c)];
            if (t == 0) {
                continue;
            }
            for (int k = 0; k < m; ++k) {
                const Scalar& s = S(c, k);
                if (s != 0) {
                    z.a[ij * static_cast<std::size_t>(m) + static_cast<std::size_t>(k)] += t * s;
                }
            }
        }
    }
    return z;
}

template <class Scalar>
Dense<Scalar> multiply(const Dense<Scalar>& A, const Dense<Scalar>& B) {
    Dense<Scalar> C(A.rows, B.cols);
    for (int i = 0; i < A.rows; ++i) {
        for (int k = 0; k < A.cols; ++k) {
            const Scalar& a = A(i, k);
            if (a == 0) {
                continue;
            }
            for (int j = 0; j < B.cols; ++j) {
                C(i, j) += a * B(k, j);
            }
        }
    }
    return C;
}

template <class Scalar>
Scalar max_abs(const std::vector<Scalar>& v) {
    Scalar m(0);
    for (const Scalar& x : v) {
        const Scalar ax = x < 0 ? Scalar(-x) : x;
        if (ax > m) {
            m = ax;
        }
    }
    return m;
}

// --- Corollary 2: irregular facets -----------------------------------------------

/// An irregular form and how well it solves its equation.
template <class Scalar>
struct IrregularForm {
    std::vector<Scalar> coefficients;  ///< C(m,3), lexicographic
    Scalar residual{0};                ///< max |b + F y - y| / max |y|
    int squarings = 0;                 ///< Neumann terms summed: 2^squarings
};

/// Relative size of a series block below which a block that no longer shrinks is rounding noise.
template <class Scalar>
Scalar stagnation_floor() {
    return Scalar(1e-10);
}

/// @brief Solves Corollary 2 for facet type @p type given the regular form's coefficients.
/// @param tolerance stop when the next block of the Neumann series is below tolerance·max|y|, or
///   when the blocks stop shrinking below 1e-10·max|y| (the rounding floor of Scalar)
/// @throws NumericalError when the series has not converged after 40 squarings
template <class Scalar>
IrregularForm<Scalar> solve_irregular_form(SchemeKind scheme, int type, const std::vector<Scalar>& regular,
                                           const Scalar& tolerance) {
    const FacetSeed seed = make_facet_seed(scheme, type);
    const int m = static_cast<int>(seed.ring.points.size());
    const int m_regular = facet_ring_size(scheme, regular_facet_type(scheme));
    const Tensor3<Scalar> y_regular = alternating_tensor(m_regular, regular);
    Tensor3<Scalar> b(m);
    for (std::size_t h = 0; h + 1 < seed.children.size(); ++h) {
        const Tensor3<Scalar> z =
            pull_back(facet_subdivision_matrix<Scalar>(seed, seed.ring, seed.children[h]), y_regular);
        for (std::size_t i = 0; i < b.a.size(); ++i) {
            b.a[i] += z.a[i];
        }
    }
    const Dense<Scalar> S4 = facet_subdivision_matrix<Scalar>(seed, seed.ring, seed.children.back());
    IrregularForm<Scalar> out;
    Tensor3<Scalar> y = b;
    Dense<Scalar> power = S4;
    Scalar previous_block(-1);
    for (;;) {
        LIMSURF_CHECK(out.squarings < 40, NumericalError, "the volume form of ", to_string(scheme), " facet type ",
                      type, " did not converge");
        const Tensor3<Scalar> block = pull_back(power, y);
        for (std::size_t i = 0; i < y.a.size(); ++i) {
            y.a[i] += block.a[i];
        }
        ++out.squarings;
        // Keep y exactly alternating: rounding leaves a trace of the symmetric null vector of F,
        // which the series would otherwise double at every squaring.
        y = alternating_tensor(m, alternating_part(y));
        const Scalar block_size = max_abs(block.a);
        const Scalar y_size = max_abs(y.a);
        if (block_size <= tolerance * y_size) {
            break;
        }
        // A tolerance below the rounding of Scalar is never met: the blocks stop shrinking at
        // the rounding floor (exact blocks shrink at every squaring). Stop there; the residual
        // below says how good y is.
        if (previous_block >= Scalar(0) && block_size * 2 >= previous_block &&
            block_size <= stagnation_floor<Scalar>() * y_size) {
            break;
        }
        previous_block = block_size;
        power = multiply(power, power);
    }
    const Tensor3<Scalar> Fy = pull_back(S4, y);
    std::vector<Scalar> residual(y.a.size());
    for (std::size_t i = 0; i < y.a.size(); ++i) {
        residual[i] = b.a[i] + Fy.a[i] - y.a[i];
    }
    out.residual = max_abs(residual) / max_abs(y.a);
    out.coefficients = alternating_part(y);
    return out;
}

}  // namespace limsurf::detail
