// Exact limit evaluation of C2g0 surfaces (c2g0_limit.h, docs/c2g0_limit.md).
//
// Sector coordinates: around a valence-3 vertex c with neighbours r₀, r₁, r₂ (counter-clockwise),
// sector i is the 60° wedge of the triangle (c, rᵢ, rᵢ₊₁); its point (a, b) is a·f₁ + b·f₂ with
// f₁ = c→rᵢ and f₂ = c→rᵢ₊₁ (ring of (a, b) = a + b). The b-axis of sector i is the a-axis of
// sector i+1: (0, b)ᵢ = (b, 0)ᵢ₊₁. In the lattice of a regular patch (c2g0_patch_table.inc) f₁ is
// the direction (1,0) and f₂ the direction (1,1); the triangles of a sector are
// (a,b),(a+1,b),(a,b+1) ("up") and (a+1,b),(a+1,b+1),(a,b+1) ("down"), both counter-clockwise.
#include "c2g0_limit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <memory>
#include <utility>

#include <Eigen/LU>

#include "limsurf/core/error.h"
#include "limsurf/detail/c2g0_stencils.h"
#include "limsurf/detail/target_clones.h"
#include "limsurf/detail/vector_lanes.h"
#include "limsurf/refine/refine.h"
#include "limsurf/scheme/c2g0.h"
#include "parameter_maps.h"
#include "point_weight_cache.h"

namespace limsurf::detail {
namespace {

#include "c2g0_patch_table.inc"

using Rows = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using Dense = Eigen::MatrixXd;
using Row = C2g0Row;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

/// Lattice directions counter-clockwise; direction m at a valence-6 vertex with frame k0 is the
/// neighbour at ring index k0 + m.
constexpr int lattice_directions[6][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 0}, {-1, -1}, {0, -1}};
/// Points closer than this (in ring units of the level-0 sector) to a valence-3 vertex are the vertex.
const double vertex_distance = std::ldexp(1.0, -60);
/// The derivatives at a valence-3 vertex are taken this far away along the face's edge.
const double vertex_offset = std::ldexp(1.0, -61);
/// Levels of the stationary tables: 2^m ρ >= 2 with ρ >= 2^-61 needs m <= 62, so A^(m-1) up to A^61.
constexpr int num_tables = 62;

std::vector<Index> ring_of(const Topology& t, Index v) {
    const auto edges = t.vertex_edges(v);
    std::vector<Index> ring(edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) {
        ring[i] = t.other_vertex(edges[i], v);
    }
    return ring;
}

int index_in(const std::vector<Index>& ring, Index w) {
    const auto it = std::find(ring.begin(), ring.end(), w);
    return it == ring.end() ? -1 : static_cast<int>(it - ring.begin());
}

int mod6(int k) {
    return ((k % 6) + 6) % 6;
}

bool is_regular(const Topology& t, Index v) {
    return !t.is_boundary_vertex(v) && t.valence(v) == 6;
}

/// The C2g0 rules as rows (detail/c2g0_stencils.h, the ones refine_c2g0 applies), read off any
/// topology whose vertices in the stencil have complete one-rings.
Row vertex_row(const Topology& t, Index v) {
    Row row;
    c2g0_vertex_row(t, v, row);
    return row;
}

Row edge_row(const Topology& t, Index p, Index q) {
    Row row;
    c2g0_edge_row(t, p, q, row);
    return row;
}

// --- the lattice around a triangle -------------------------------------------------------------

/// @brief The 27 vertices of the 2-ring of the triangle (v0, v1, ·) in the order of
///   c2g0_offsets, walking the lattice through the 12 inner vertices.
/// @return false when an inner vertex is not an interior valence-6 vertex (then @p bad names it)
bool gather_lattice(const Topology& t, Index v0, Index v1, std::array<Index, 27>& out, Index& bad) {
    constexpr int span = 9;  // lattice points (-4..4)²
    constexpr int shift = 4;
    std::array<Index, span * span> vertex;
    std::array<int, span * span> frame;
    vertex.fill(invalid_index);
    frame.fill(-1);
    const auto cell = [](int x, int y) { return static_cast<std::size_t>((y + shift) * span + (x + shift)); };
    vertex[cell(0, 0)] = v0;
    {
        const auto ring = ring_of(t, v0);
        frame[cell(0, 0)] = index_in(ring, v1);
    }
    // The inner points (hex distance <= 1 from the triangle) are offsets 0..11; visit them in an
    // order in which each is a lattice neighbour of an earlier one.
    std::array<bool, 27> done{};
    for (int pass = 0; pass < 12; ++pass) {
        for (int i = 0; i < 12; ++i) {
            const int x = c2g0_offsets[i][0];
            const int y = c2g0_offsets[i][1];
            const Index p = vertex[cell(x, y)];
            if (done[at(i)] || p == invalid_index) {
                continue;
            }
            done[at(i)] = true;
            if (!is_regular(t, p)) {
                bad = p;
                return false;
            }
            const auto ring = ring_of(t, p);
            const int k0 = frame[cell(x, y)];
            for (int m = 0; m < 6; ++m) {
                const int nx = x + lattice_directions[m][0];
                const int ny = y + lattice_directions[m][1];
                const Index q = ring[at(mod6(k0 + m))];
                Index& slot = vertex[cell(nx, ny)];
                if (slot == invalid_index) {
                    slot = q;
                    if (t.valence(q) == 6 && !t.is_boundary_vertex(q)) {
                        frame[cell(nx, ny)] = mod6(index_in(ring_of(t, q), p) - (m + 3));
                    }
                }
                LIMSURF_ASSERT(slot == q, "C2g0 lattice walk: the 2-ring of a triangle is not a lattice");
            }
        }
    }
    for (int i = 0; i < 27; ++i) {
        out[at(i)] = vertex[cell(c2g0_offsets[i][0], c2g0_offsets[i][1])];
        LIMSURF_ASSERT(out[at(i)] != invalid_index, "C2g0 lattice walk: point ", i, " not reached");
    }
    return true;
}

// --- the 3-regular complex K_R -----------------------------------------------------------------

Index complex_size(int R) {
    return 1 + 3 * R * (R + 1) / 2;
}

/// Vertex (sector i, a, b) of K_R: 0 is the centre, then sector by sector, ring by ring.
Index complex_id(int R, int i, int a, int b) {
    i = ((i % 3) + 3) % 3;
    if (a == 0 && b == 0) {
        return 0;
    }
    if (a == 0) {
        i = (i + 1) % 3;
        a = b;
        b = 0;
    }
    const int r = a + b;
    return 1 + i * R * (R + 1) / 2 + r * (r - 1) / 2 + b;
}

Topology make_complex(int R) {
    std::vector<std::vector<Index>> faces;
    for (int i = 0; i < 3; ++i) {
        for (int a = 0; a < R; ++a) {
            for (int b = 0; a + b < R; ++b) {
                faces.push_back({complex_id(R, i, a, b), complex_id(R, i, a + 1, b), complex_id(R, i, a, b + 1)});
                if (a + b + 2 <= R) {
                    faces.push_back(
                        {complex_id(R, i, a + 1, b), complex_id(R, i, a + 1, b + 1), complex_id(R, i, a, b + 1)});
                }
            }
        }
    }
    return Topology::from_polygons(complex_size(R), faces);
}

/// The ends of the parent edge whose child is (a, b) at the next level (a, b not both even).
std::array<std::array<int, 2>, 2> parent_edge(int a, int b) {
    if (a % 2 != 0 && b % 2 == 0) {
        return {{{(a - 1) / 2, b / 2}, {(a + 1) / 2, b / 2}}};
    }
    if (a % 2 == 0) {
        return {{{a / 2, (b - 1) / 2}, {a / 2, (b + 1) / 2}}};
    }
    return {{{(a - 1) / 2, (b + 1) / 2}, {(a + 1) / 2, (b - 1) / 2}}};
}

/// The rows of the C2g0 local subdivision: K_4 (level n) → K_6 (level n + 1). Every K_6 vertex is
/// a vertex child of a K_4 vertex in ring <= 3 or an edge child of an edge between two of them, so
/// its stencil lies in K_4 and sees complete one-rings.
Dense local_subdivision(const Topology& k4) {
    Dense B = Dense::Zero(complex_size(6), complex_size(4));
    const auto put = [&](Index child, const Row& row) {
        for (const auto& [v, w] : row) {
            B(child, v) += w;
        }
    };
    put(0, vertex_row(k4, 0));
    for (int i = 0; i < 3; ++i) {
        for (int r = 1; r <= 6; ++r) {
            for (int b = 0; b < r; ++b) {
                const int a = r - b;
                const Index child = complex_id(6, i, a, b);
                if (a % 2 == 0 && b % 2 == 0) {
                    put(child, vertex_row(k4, complex_id(4, i, a / 2, b / 2)));
                } else {
                    const auto ends = parent_edge(a, b);
                    put(child, edge_row(k4, complex_id(4, i, ends[0][0], ends[0][1]),
                                        complex_id(4, i, ends[1][0], ends[1][1])));
                }
            }
        }
    }
    return B;
}

/// Ptex derivative rows from rows in patch coordinates (s, t) = offset + L · (u, v).
void chain(const Eigen::Matrix<double, 6, 27>& b, const Eigen::Matrix2d& L, Eigen::Matrix<double, 6, 27>& r) {
    for (int k = 0; k < 27; ++k) {
        r(0, k) = b(0, k);
        r(1, k) = L(0, 0) * b(1, k) + L(1, 0) * b(2, k);
        r(2, k) = L(0, 1) * b(1, k) + L(1, 1) * b(2, k);
        r(3, k) = L(0, 0) * L(0, 0) * b(3, k) + 2.0 * L(0, 0) * L(1, 0) * b(4, k) + L(1, 0) * L(1, 0) * b(5, k);
        r(4, k) = L(0, 0) * L(0, 1) * b(3, k) + (L(0, 0) * L(1, 1) + L(1, 0) * L(0, 1)) * b(4, k) +
                  L(1, 0) * L(1, 1) * b(5, k);
        r(5, k) = L(0, 1) * L(0, 1) * b(3, k) + 2.0 * L(0, 1) * L(1, 1) * b(4, k) + L(1, 1) * L(1, 1) * b(5, k);
    }
}

/// Graph distance from @p v to the nearest other valence-3 vertex, if below @p limit (else limit).
int distance_to_valence3(const Topology& t, Index v, int limit, Index& found) {
    std::vector<Index> frontier{v};
    std::vector<Index> seen{v};
    for (int d = 1; d < limit; ++d) {
        std::vector<Index> next;
        for (const Index x : frontier) {
            for (const Index y : ring_of(t, x)) {
                if (std::find(seen.begin(), seen.end(), y) != seen.end()) {
                    continue;
                }
                seen.push_back(y);
                next.push_back(y);
                if (t.valence(y) == 3) {
                    found = y;
                    return d;
                }
            }
        }
        frontier = std::move(next);
    }
    return limit;
}

/// The closest pair of valence-3 vertices, if closer than 4: (distance, one of them).
std::pair<int, Index> closest_valence3(const Topology& t) {
    std::pair<int, Index> best{4, invalid_index};
    for (Index v = 0; v < t.num_vertices(); ++v) {
        Index other = invalid_index;
        if (t.valence(v) == 3) {
            const int d = distance_to_valence3(t, v, 4, other);
            if (d < best.first) {
                best = {d, v};
            }
        }
    }
    return best;
}

}  // namespace

// --- the regular patch -------------------------------------------------------------------------

std::array<std::array<int, 2>, 27> c2g0_patch_offsets() {
    std::array<std::array<int, 2>, 27> out{};
    for (std::size_t i = 0; i < 27; ++i) {
        out[i] = {c2g0_offsets[i][0], c2g0_offsets[i][1]};
    }
    return out;
}

namespace {

/// The 27 functions of the regular patch, padded with a zero 28th: whole vector registers.
constexpr int padded_functions = 28;

/// What the power form of each degree-7 Bernstein function b (c2g0_bernstein) and of its
/// derivatives needs: b = c l0^e0 l1^e1 l2^e2, ∂b/∂l_x = (c e_x) l_x^(e_x − 1) Π_(z≠x) l_z^e_z, and
/// ∂²b/∂l_x∂l_y = c Π_z f_z l_z^(e_z − [z=x] − [z=y]) with f_z the falling factor (e_z(e_z − 1),
/// e_z or 1; 0 where the power would be negative). Powers are read as power[z][exponent + 1]
/// (power[z][0] = 0 stands for a negative one).
struct PowerForm {
    struct Function {
        double c = 0.0;
        int e[3] = {};
        double de[3] = {};         // c e_x
        double factor[6][3] = {};  // of the pairs (1,1), (0,1), (0,0), (1,2), (0,2), (2,2)
        int power_index[6][3] = {};
    };
    Function b[36];
    static constexpr int pairs[6][2] = {{1, 1}, {0, 1}, {0, 0}, {1, 2}, {0, 2}, {2, 2}};

    PowerForm() {
        constexpr double factorial[8] = {1, 1, 2, 6, 24, 120, 720, 5040};
        for (int n = 0; n < 36; ++n) {
            Function& f = b[n];
            f.e[1] = c2g0_bernstein[n][0];
            f.e[2] = c2g0_bernstein[n][1];
            f.e[0] = 7 - f.e[1] - f.e[2];
            f.c = factorial[7] / (factorial[f.e[0]] * factorial[f.e[1]] * factorial[f.e[2]]);
            for (int x = 0; x < 3; ++x) {
                f.de[x] = f.c * f.e[x];
            }
            for (int p = 0; p < 6; ++p) {
                const int x = pairs[p][0];
                const int y = pairs[p][1];
                for (int z = 0; z < 3; ++z) {
                    const int ez = f.e[z] - (z == x ? 1 : 0) - (z == y ? 1 : 0);
                    const int factor = x == y ? (z == x ? f.e[z] * (f.e[z] - 1) : 1) : (z == x || z == y ? f.e[z] : 1);
                    f.factor[p][z] = factor;
                    f.power_index[p][z] = factor == 0 ? 0 : ez + 1;  // factor 0: any finite power
                }
            }
        }
    }
};

/// The patch's Bézier table as a 28 × 36 matrix (function × Bernstein function), by columns.
Eigen::Matrix<double, padded_functions, 36> bezier_table() {
    Eigen::Matrix<double, padded_functions, 36> q = Eigen::Matrix<double, padded_functions, 36>::Zero();
    for (int i = 0; i < 27; ++i) {
        for (int b = 0; b < 36; ++b) {
            q(i, b) = static_cast<double>(c2g0_coefficients[i][b][0]) / static_cast<double>(c2g0_coefficients[i][b][1]);
        }
    }
    return q;
}

/// basis[r][b]: row r (value, ∂u, ∂v, ∂uu, ∂uv, ∂vv) of Bernstein function b at barycentrics
/// (l0, l1, l2) = (1 − u − v, u, v); ∂u = ∂l1 − ∂l0 and ∂v = ∂l2 − ∂l0.
void bernstein_rows(const PowerForm& form, double u, double v, double (&basis)[6][36]) {
    const double l[3] = {1.0 - u - v, u, v};
    double power[3][9];  // power[z][e + 1] = l_z^e, power[z][0] = 0
    for (int z = 0; z < 3; ++z) {
        power[z][0] = 0.0;
        power[z][1] = 1.0;
        for (int e = 1; e < 8; ++e) {
            power[z][e + 1] = power[z][e] * l[z];
        }
    }
    for (int n = 0; n < 36; ++n) {
        const PowerForm::Function& f = form.b[n];
        const double* p0 = power[0];
        const double* p1 = power[1];
        const double* p2 = power[2];
        const double d0 = f.de[0] * p0[f.e[0]] * p1[f.e[1] + 1] * p2[f.e[2] + 1];
        const double d1 = f.de[1] * p1[f.e[1]] * p0[f.e[0] + 1] * p2[f.e[2] + 1];
        const double d2 = f.de[2] * p2[f.e[2]] * p0[f.e[0] + 1] * p1[f.e[1] + 1];
        double dd[6];
        for (int p = 0; p < 6; ++p) {
            dd[p] = f.c * (f.factor[p][0] * p0[f.power_index[p][0]]) * (f.factor[p][1] * p1[f.power_index[p][1]]) *
                    (f.factor[p][2] * p2[f.power_index[p][2]]);
        }
        basis[0][n] = f.c * p0[f.e[0] + 1] * p1[f.e[1] + 1] * p2[f.e[2] + 1];
        basis[1][n] = d1 - d0;
        basis[2][n] = d2 - d0;
        basis[3][n] = dd[0] - 2.0 * dd[1] + dd[2];
        basis[4][n] = dd[3] - dd[1] - dd[4] + dd[2];
        basis[5][n] = dd[5] - 2.0 * dd[4] + dd[2];
    }
}

/// sums[r][i] = Σ_b table(i, b) basis[r][b], each a sum over b in order, the 28 functions side by
/// side in Lanes<N> vectors (detail/vector_lanes.h): the same bits for every N (this file is
/// compiled without contraction).
template <int N>
[[gnu::always_inline]] inline void table_products(const double* table, const double (&basis)[6][36],
                                                  double (&sums)[6][padded_functions]) {
    using Vector = typename Lanes<N, N>::Native;
    constexpr int parts = padded_functions / N;
    for (int r = 0; r < 6; ++r) {
        Vector sum[parts] = {};  // fully unrolled below, so held in registers
        for (int b = 0; b < 36; ++b) {
            const double x = basis[r][b];
#pragma GCC unroll 16
            for (int p = 0; p < parts; ++p) {
                Vector column;
                __builtin_memcpy(&column, table + padded_functions * b + N * p, sizeof column);
                sum[p] += column * x;
            }
        }
#pragma GCC unroll 16
        for (int p = 0; p < parts; ++p) {
            __builtin_memcpy(sums[r] + N * p, &sum[p], sizeof sum[p]);
        }
    }
}

#ifdef LIMSURF_ISA_VARIANTS
// AVX2 (4 doubles) also on AVX-512 machines: 28 sums are 7 of its registers, not whole ones of 8.
LIMSURF_TARGET_AVX2 void table_products_avx2(const double* table, const double (&basis)[6][36],
                                             double (&sums)[6][padded_functions]) {
    table_products<4>(table, basis, sums);
}
#endif

}  // namespace

void c2g0_patch_weights(double u, double v, Eigen::Matrix<double, 6, 27>& out) {
    static const PowerForm form;
    static const Eigen::Matrix<double, padded_functions, 36> table = bezier_table();
    double basis[6][36];
    bernstein_rows(form, u, v, basis);
    double sums[6][padded_functions];
#ifdef LIMSURF_ISA_VARIANTS
    if (vector_doubles() >= 4) {
        table_products_avx2(table.data(), basis, sums);
    } else {
        table_products<2>(table.data(), basis, sums);
    }
#else
    table_products<2>(table.data(), basis, sums);
#endif
    for (int r = 0; r < 6; ++r) {
        for (int i = 0; i < 27; ++i) {
            out(r, i) = sums[r][i];
        }
    }
}

// --- the evaluator -----------------------------------------------------------------------------

struct C2g0Limit::Impl {
    /// The mesh the faces are evaluated on: the control mesh, or its refinement when valence-3
    /// vertices are closer than 4 (then `refined` holds the step and faces are its children).
    Topology mesh;
    bool refined = false;
    SparseMatrix S;  ///< refined: #V_refined × #V
    bool use_tables = true;
    /// The regular patch's weights at the points evaluated so far (thread-safe): most evaluations
    /// repeat a quadrature rule's points on every face. Before they were kept, computing them took
    /// 43 % of the membrane functionals' set-up, after c2g0_patch_weights was made 3–4× faster.
    PointWeightCache<Eigen::Matrix<double, 6, 27>> patch_weights;

    /// The local subdivision around a valence-3 vertex (the same for every one).
    Topology k4;
    Topology k6;
    Dense B;                    ///< K_4 → K_6, one level
    Dense A;                    ///< K_4 → K_4, one level
    Eigen::RowVectorXd limit;   ///< ℓ: the limit mask of the centre over K_4
    std::vector<Dense> tables;  ///< tables[n] = B · R^n (n >= 1), tables[0] = B; R = A − 1ℓᵀ
    /// The 27 lattice points (K_6 vertices) of each type-0 triangle of K_6 with rings in [2, 4],
    /// keyed by its corners 0 and 1 (as make_complex lists them).
    std::map<std::pair<Index, Index>, std::array<Index, 27>> patches;

    /// The copy of K_4 around one valence-3 vertex of `mesh`.
    struct Star {
        std::vector<Index> support;  ///< control vertices (of `mesh`), without repeats
        Dense E;                     ///< #K_4 × #support: selection (repeats summed)
    };
    std::vector<Star> stars;

    /// A face of `mesh`: type 0 (its 27 lattice points) or near a valence-3 vertex.
    struct Face {
        int star = -1;                          ///< -1: type 0
        std::array<Index, 27> points{};         ///< type 0: vertices of `mesh`
        bool distinct_points = false;           ///< type 0: no vertex twice among `points`
        int sector = 0;                         ///< near: the sector of the face
        std::array<Eigen::Vector2d, 3> corner;  ///< near: sector coordinates of v0, v1, v2
    };
    std::vector<Face> faces;

    void build_local();
    void build_faces(const Topology& t);
    /// Rows over `mesh` vertices at (u, v) of face f of `mesh`.
    void evaluate_mesh(Index f, double u, double v, std::vector<Index>& support, Rows& rows, bool& at_vertex) const;
};

void C2g0Limit::Impl::build_local() {
    k4 = make_complex(4);
    k6 = make_complex(6);
    B = local_subdivision(k4);
    A = Dense::Zero(complex_size(4), complex_size(4));
    A.row(0) = B.row(0);
    for (int i = 0; i < 3; ++i) {
        for (int r = 1; r <= 4; ++r) {
            for (int b = 0; b < r; ++b) {
                A.row(complex_id(4, i, r - b, b)) = B.row(complex_id(6, i, r - b, b));
            }
        }
    }
    // ℓ (ℓᵀA = ℓᵀ, ℓ·1 = 1): any row of A^(2^8) (the other eigenvalues are at most 1/2).
    Dense power = A;
    for (int j = 0; j < 8; ++j) {
        power = power * power;
    }
    limit = power.row(0) / power.row(0).sum();
    const Dense R = A - Eigen::VectorXd::Ones(A.rows()) * limit;
    for (int i = 0; i < 3; ++i) {
        for (int a = 0; a <= 4; ++a) {
            for (int b = 0; a + b <= 4; ++b) {
                std::array<Index, 27> ids{};
                Index bad = invalid_index;
                if (a + b >= 2 && a + b + 1 <= 4) {
                    const Index q0 = complex_id(6, i, a, b);
                    const Index q1 = complex_id(6, i, a + 1, b);
                    const bool ok = gather_lattice(k6, q0, q1, ids, bad);
                    LIMSURF_ASSERT(ok, "C2g0: a triangle of K_6 in rings 2..4 is not regular");
                    (void)ok;
                    patches.emplace(std::pair{q0, q1}, ids);
                }
                if (a + b + 1 >= 2 && a + b + 2 <= 4) {
                    const Index q0 = complex_id(6, i, a + 1, b);
                    const Index q1 = complex_id(6, i, a + 1, b + 1);
                    const bool ok = gather_lattice(k6, q0, q1, ids, bad);
                    LIMSURF_ASSERT(ok, "C2g0: a triangle of K_6 in rings 2..4 is not regular");
                    (void)ok;
                    patches.emplace(std::pair{q0, q1}, ids);
                }
            }
        }
    }
    tables.reserve(num_tables);
    tables.push_back(B);
    tables.push_back(B * R);
    for (int n = 2; n < num_tables; ++n) {
        tables.push_back(tables.back() * R);
    }
}

void C2g0Limit::Impl::build_faces(const Topology& t) {
    std::vector<int> star_of(at(t.num_vertices()), -1);
    for (Index c = 0; c < t.num_vertices(); ++c) {
        if (t.valence(c) != 3) {
            continue;
        }
        // Walk K_4 into the mesh: sector i from rᵢ, b steps along f₂ then a − 1 along f₁.
        std::vector<Index> copy(at(complex_size(4)), invalid_index);
        copy[0] = c;
        const auto rc = ring_of(t, c);
        for (int i = 0; i < 3; ++i) {
            for (int r = 1; r <= 4; ++r) {
                for (int b = 0; b < r; ++b) {
                    const int a = r - b;
                    Index p = rc[at(i)];
                    int k0 = mod6(index_in(ring_of(t, p), c) + 3);
                    const auto step = [&](int m) {
                        LIMSURF_CHECK_AT(is_regular(t, p), UnsupportedError, vertex_element(p),
                                         "C2g0 limit evaluation: vertex ", p, " (valence ", t.valence(p),
                                         ") is within ring 3 of the valence-3 vertex ", c);
                        const auto ring = ring_of(t, p);
                        const Index q = ring[at(mod6(k0 + m))];
                        if (is_regular(t, q)) {
                            k0 = mod6(index_in(ring_of(t, q), p) - (m + 3));
                        }
                        p = q;
                    };
                    for (int s = 0; s < b; ++s) {
                        step(1);
                    }
                    for (int s = 1; s < a; ++s) {
                        step(0);
                    }
                    copy[at(complex_id(4, i, a, b))] = p;
                }
            }
        }
        Star star;
        for (const Index v : copy) {
            if (std::find(star.support.begin(), star.support.end(), v) == star.support.end()) {
                star.support.push_back(v);
            }
        }
        star.E = Dense::Zero(complex_size(4), static_cast<Index>(star.support.size()));
        for (std::size_t k = 0; k < copy.size(); ++k) {
            const auto col = std::find(star.support.begin(), star.support.end(), copy[k]) - star.support.begin();
            star.E(static_cast<Index>(k), static_cast<Index>(col)) += 1.0;
        }
        star_of[at(c)] = static_cast<int>(stars.size());
        stars.push_back(std::move(star));
        // The faces within ring 2 of c (types I, II₁, II₂): their images, sector and sector
        // coordinates; a face of the mesh is matched with its corners in order.
        std::vector<std::pair<std::array<Index, 3>, std::pair<int, std::array<std::array<int, 2>, 3>>>> local;
        for (int i = 0; i < 3; ++i) {
            for (int a = 0; a < 2; ++a) {
                for (int b = 0; a + b < 2; ++b) {
                    std::array<std::array<int, 2>, 3> up{{{a, b}, {a + 1, b}, {a, b + 1}}};
                    local.push_back({{copy[at(complex_id(4, i, a, b))], copy[at(complex_id(4, i, a + 1, b))],
                                      copy[at(complex_id(4, i, a, b + 1))]},
                                     {i, up}});
                    if (a + b + 2 <= 2) {
                        std::array<std::array<int, 2>, 3> down{{{a + 1, b}, {a + 1, b + 1}, {a, b + 1}}};
                        local.push_back(
                            {{copy[at(complex_id(4, i, a + 1, b))], copy[at(complex_id(4, i, a + 1, b + 1))],
                              copy[at(complex_id(4, i, a, b + 1))]},
                             {i, down}});
                    }
                }
            }
        }
        for (Index f = 0; f < t.num_faces(); ++f) {
            const auto v = t.face_vertices(f);
            for (const auto& [images, where] : local) {
                for (int rot = 0; rot < 3; ++rot) {
                    if (images[at(rot)] == v[0] && images[at((rot + 1) % 3)] == v[1] &&
                        images[at((rot + 2) % 3)] == v[2]) {
                        Face& face = faces[at(f)];
                        if (face.star == -1 && face.points[0] == invalid_index) {
                            face.star = star_of[at(c)];
                            face.sector = where.first;
                            for (int k = 0; k < 3; ++k) {
                                const auto& p = where.second[at((rot + k) % 3)];
                                face.corner[at(k)] = Eigen::Vector2d(p[0], p[1]);
                            }
                        }
                    }
                }
            }
        }
    }
}

void C2g0Limit::Impl::evaluate_mesh(Index f, double u, double v, std::vector<Index>& support, Rows& rows,
                                    bool& at_vertex) const {
    const Face& face = faces[at(f)];
    Eigen::Matrix<double, 6, 27> b;
    Eigen::Matrix<double, 6, 27> r;
    if (face.star < 0) {
        patch_weights.weights(u, v, b, c2g0_patch_weights);
        if (face.distinct_points) {
            support.assign(face.points.begin(), face.points.end());
            rows = b;
            return;
        }
        support.clear();
        rows.setZero(6, 27);
        for (int k = 0; k < 27; ++k) {  // a small closed mesh: a point stands for several lattice points
            const Index x = face.points[at(k)];
            auto it = std::find(support.begin(), support.end(), x);
            if (it == support.end()) {
                support.push_back(x);
                it = support.end() - 1;
            }
            rows.col(it - support.begin()) += b.col(k);
        }
        rows.conservativeResize(6, static_cast<Index>(support.size()));
        return;
    }
    const Star& star = stars[at(face.star)];
    Eigen::Matrix2d J;
    J.col(0) = face.corner[1] - face.corner[0];
    J.col(1) = face.corner[2] - face.corner[0];
    Eigen::Vector2d x = face.corner[0] + J * Eigen::Vector2d(u, v);
    at_vertex = x.sum() < vertex_distance;
    if (at_vertex) {
        LIMSURF_CHECK(use_tables, NumericalError, "C2g0 limit evaluation: LimitEvaluation::Subdivision does not ",
                      "evaluate at a valence-3 vertex (face ", f, ")");
        // The derivatives 2^-61 away along the edge from the vertex's corner to the next corner.
        int k = 0;
        while (k < 2 && face.corner[at(k)].sum() != 0.0) {
            ++k;
        }
        const Eigen::Vector2d uv =
            domain_corner(false, k) + vertex_offset * (domain_corner(false, k + 1) - domain_corner(false, k));
        x = face.corner[0] + J * uv;
    }
    int m = 1;
    while (std::ldexp(x.sum(), m) < 2.0) {
        ++m;
    }
    const Eigen::Vector2d xm = std::ldexp(1.0, m) * x;
    // The lattice triangle of K_6 at level m containing xm, with rings in [2, 4].
    std::array<int, 2> q0;
    std::array<int, 2> q1;
    std::array<int, 2> q2;
    if (xm.sum() >= 4.0) {
        const int a0 = std::min(static_cast<int>(std::floor(xm.x())), 3);
        const int b0 = 3 - a0;
        q0 = {a0, b0};
        q1 = {a0 + 1, b0};
        q2 = {a0, b0 + 1};
    } else {
        const int a0 = static_cast<int>(std::floor(xm.x()));
        const int b0 = static_cast<int>(std::floor(xm.y()));
        // The lower triangle (rings a0 + b0 and one more) or the upper one (rings a0 + b0 + 1 and one
        // more). Rounding can put xm just across a lattice line from where a0 + b0 says, e.g. (2/3, 1/3)
        // at level 1 lands on ring 1 or 2 by one ulp: keep to rings 2..4 whatever the rounding.
        const int ring = a0 + b0;
        if (ring >= 3 || (ring >= 2 && xm.x() - a0 + xm.y() - b0 < 1.0)) {
            q0 = {a0, b0};
            q1 = {a0 + 1, b0};
            q2 = {a0, b0 + 1};
        } else {
            q0 = {a0 + 1, b0};
            q1 = {a0 + 1, b0 + 1};
            q2 = {a0, b0 + 1};
        }
    }
    Eigen::Matrix2d M;
    M << q1[0] - q0[0], q2[0] - q0[0], q1[1] - q0[1], q2[1] - q0[1];
    const Eigen::Matrix2d Mi = M.inverse();
    const Eigen::Vector2d st = Mi * (xm - Eigen::Vector2d(q0[0], q0[1]));
    const Eigen::Matrix2d L = std::ldexp(1.0, m) * Mi * J;
    patch_weights.weights(st.x(), st.y(), b, c2g0_patch_weights);
    chain(b, L, r);
    const auto found =
        patches.find({complex_id(6, face.sector, q0[0], q0[1]), complex_id(6, face.sector, q1[0], q1[1])});
    // Checked in every build: a missed lattice case must be an error, never a read through end().
    LIMSURF_CHECK(found != patches.end(), NumericalError, "C2g0 limit evaluation: no type-0 triangle of K_6 at (",
                  x.x(), ", ", x.y(), ") (a limsurf bug: please report the mesh and point)");
    const std::array<Index, 27>& ids = found->second;
    const int n = m - 1;
    Rows local = Rows::Zero(6, complex_size(4));
    if (use_tables) {
        const Dense& T = tables[at(n)];
        for (int k = 0; k < 27; ++k) {
            local += r.col(k) * T.row(ids[at(k)]);
        }
        if (n > 0) {
            local.row(0) += limit;  // the value row sums to 1: B A^n = 1ℓᵀ + B R^n
        }
    } else {
        // Level by level, relative to the centre: A^n = D_n + 1 a_n with a_n = row 0 of A^n, so
        // D_(n+1) = A D_n − 1 (A D_n)₀ and a_(n+1) = a_n + (A D_n)₀; D_n decays like the
        // subdominant eigenvalue and keeps its relative precision (no ℓ, no tables).
        Dense D = Dense::Identity(complex_size(4), complex_size(4));
        D.col(0).array() -= 1.0;
        Eigen::RowVectorXd a = Eigen::RowVectorXd::Unit(complex_size(4), 0);
        for (int level = 0; level < n; ++level) {
            const Dense AD = A * D;
            const Eigen::RowVectorXd centre = AD.row(0);
            a += centre;
            D = AD.rowwise() - centre;
        }
        Dense P = Dense::Zero(27, complex_size(6));
        for (int k = 0; k < 27; ++k) {
            P(k, ids[at(k)]) = 1.0;
        }
        const Dense PB = P * B;
        local = r * (PB * D);
        local.row(0) += r.row(0).sum() * a;
    }
    rows = local * star.E;
    if (at_vertex) {
        rows.row(0) = limit * star.E;
    }
    support = star.support;
}

C2g0Limit::C2g0Limit(const Topology& topology, LimitEvaluation evaluation) : impl_(std::make_unique<Impl>()) {
    require_c2g0_topology(topology);
    Impl& m = *impl_;
    m.use_tables = evaluation == LimitEvaluation::Stationary;
    const auto [distance, vertex] = closest_valence3(topology);
    if (distance < 4) {
        // Valence-3 vertices at distance 2 or 3 (1 is refused above): one refinement doubles it.
        Level level = refine_c2g0(topology);
        const auto [refined_distance, refined_vertex] = closest_valence3(level.topology);
        LIMSURF_CHECK_AT(refined_distance >= 4, UnsupportedError, vertex_element(vertex),
                         "C2g0 limit evaluation: the valence-3 vertex ", vertex, " is at distance ", distance,
                         " from another one, still closer than 4 after one refinement");
        (void)refined_vertex;
        m.refined = true;
        m.S.swap(level.S0);  // Eigen 3.4: assigning a std::move-d SparseMatrix copies it
        m.mesh = std::move(level.topology);
    } else {
        m.mesh = topology;
    }
    m.build_local();
    m.faces.resize(at(m.mesh.num_faces()));
    for (Index f = 0; f < m.mesh.num_faces(); ++f) {
        const auto v = m.mesh.face_vertices(f);
        Index bad = invalid_index;
        Impl::Face& face = m.faces[at(f)];
        face.points.fill(invalid_index);
        if (gather_lattice(m.mesh, v[0], v[1], face.points, bad)) {
            std::array<Index, 27> sorted = face.points;
            std::sort(sorted.begin(), sorted.end());
            face.distinct_points = std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
            continue;
        }
        face.points.fill(invalid_index);
    }
    m.build_faces(m.mesh);
    for (Index f = 0; f < m.mesh.num_faces(); ++f) {
        const Impl::Face& face = m.faces[at(f)];
        LIMSURF_CHECK_AT(face.star >= 0 || face.points[0] != invalid_index, UnsupportedError, face_element(f),
                         "C2g0 limit evaluation: face ", f, " is neither regular nor within ring 2 of one ",
                         "valence-3 vertex");
    }
}

C2g0Limit::~C2g0Limit() = default;
C2g0Limit::C2g0Limit(C2g0Limit&&) noexcept = default;
C2g0Limit& C2g0Limit::operator=(C2g0Limit&&) noexcept = default;

void C2g0Limit::evaluate(Index face, double u, double v, int rows_needed, std::vector<Index>& support,
                         Eigen::Matrix<double, 6, Eigen::Dynamic>& rows, bool& at_vertex) const {
    const Impl& m = *impl_;
    at_vertex = false;
    if (!m.refined) {
        m.evaluate_mesh(face, u, v, support, rows, at_vertex);
    } else {
        // Child q of the Loop split (refine.h: child face 4f + q, child_map gives its corners).
        const Eigen::Vector2d p(u, v);
        const int q = child_containing(false, p);
        const Affine map = child_map(false, q);
        const Eigen::Vector2d c = map.to_child(p);
        std::vector<Index> fine;
        Rows fine_rows;
        m.evaluate_mesh(4 * face + q, c.x(), c.y(), fine, fine_rows, at_vertex);
        // Child derivatives to parent ones: child = axes⁻¹ (parent − offset).
        const Eigen::Matrix2d L = map.axes.inverse();
        Eigen::Matrix<double, 6, 27> b;
        Rows transformed(6, fine_rows.cols());
        for (Index k = 0; k < fine_rows.cols(); ++k) {
            b.setZero();
            b.col(0) = fine_rows.col(k);
            Eigen::Matrix<double, 6, 27> t;
            chain(b, L, t);
            transformed.col(k) = t.col(0);
        }
        // Over the control vertices: rows · S (rows of S for the fine support).
        support.clear();
        std::vector<Eigen::Matrix<double, 6, 1>> acc;
        for (Index k = 0; k < static_cast<Index>(fine.size()); ++k) {
            for (SparseMatrix::InnerIterator it(m.S, fine[at(k)]); it; ++it) {
                auto found = std::find(support.begin(), support.end(), it.col());
                if (found == support.end()) {
                    support.push_back(it.col());
                    acc.emplace_back(Eigen::Matrix<double, 6, 1>::Zero());
                    found = support.end() - 1;
                }
                acc[at(found - support.begin())] += it.value() * transformed.col(k);
            }
        }
        rows.resize(6, static_cast<Index>(support.size()));
        for (std::size_t k = 0; k < support.size(); ++k) {
            rows.col(static_cast<Index>(k)) = acc[k];
        }
    }
    if (rows_needed < 6) {
        rows.bottomRows(6 - rows_needed).setZero();
    }
}

}  // namespace limsurf::detail
