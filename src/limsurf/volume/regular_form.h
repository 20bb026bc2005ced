// The regular volume forms by Corollary 1 of volume-trilinear-forms, in exact
// arithmetic (the generator tool and the tests instantiate it with GMP rationals).
// Private to src/limsurf/volume and tools/volume_forms.
//
// Unknowns: an alternating form on the regular facet's m points, invariant under the
// facet's rotations and changing sign under its mirror (reversing the orientation
// negates the volume). The symmetry group splits the C(m,3) coefficients into orbits;
// one unknown per orbit (orbits mapped to minus themselves are zero). The equations
// E y = y are taken at one representative per orbit (E commutes with the symmetries),
// a square system whose null space is a line. The line is calibrated on the paper's
// degenerate mesh: a cube (Catmull–Clark: bilinearly refined three times; Doo–Sabin:
// twice) or tetrahedron (Loop: linearly refined three times) with every vertex moved
// onto the nearest corner (of a regular tetrahedron, measured affinely), whose limit surface is the polyhedron itself.
// Facets next to its corners have every control point on one corner and contribute nothing, so the regular facets alone
// must sum to the polyhedron's volume.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"
#include "limsurf/volume/form_generator.h"

namespace limsurf::detail {

/// A permutation of the facet's points and the sign it multiplies the form by.
struct FacetSymmetry {
    std::vector<int> permutation;  ///< ring_b[a] = ring_0[permutation[a]]
    int sign = 1;
};

/// The symmetries of the seed's regular facet: rotation by one anchor, and the mirror.
inline std::vector<FacetSymmetry> regular_symmetries(const FacetSeed& seed) {
    const auto to_permutation = [&](const FacetRing& other) {
        std::vector<int> p(other.points.size());
        for (std::size_t a = 0; a < other.points.size(); ++a) {
            for (std::size_t i = 0; i < seed.ring.points.size(); ++i) {
                if (seed.ring.points[i] == other.points[a]) {
                    p[a] = static_cast<int>(i);
                }
            }
        }
        return p;
    };
    return {{to_permutation(rotated_ring(seed, 1)), 1}, {to_permutation(mirrored_ring(seed)), -1}};
}

/// Orbits of the sorted triples under the symmetries.
struct TripleOrbits {
    std::vector<int> orbit;           ///< per sorted triple (alternating_index): its orbit, or -1 when forced to zero
    std::vector<int> sign;            ///< coefficient = sign × the orbit's unknown
    std::vector<int> representative;  ///< per orbit: a sorted triple
};

inline TripleOrbits triple_orbits(int m, const std::vector<FacetSymmetry>& symmetries) {
    std::vector<std::array<int, 3>> triples;
    for (int i = 0; i < m; ++i) {
        for (int j = i + 1; j < m; ++j) {
            for (int k = j + 1; k < m; ++k) {
                triples.push_back({i, j, k});
            }
        }
    }
    const std::size_t count = triples.size();
    std::vector<int> raw_orbit(count, -1);
    std::vector<int> sign(count, 0);
    std::vector<bool> zero;
    int orbits = 0;
    for (std::size_t t = 0; t < count; ++t) {
        if (raw_orbit[t] != -1) {
            continue;
        }
        const int q = orbits++;
        zero.push_back(false);
        raw_orbit[t] = q;
        sign[t] = 1;
        std::deque<std::size_t> queue{t};
        while (!queue.empty()) {
            const std::size_t u = queue.front();
            queue.pop_front();
            for (const FacetSymmetry& g : symmetries) {
                std::array<int, 3> image{g.permutation[static_cast<std::size_t>(triples[u][0])],
                                         g.permutation[static_cast<std::size_t>(triples[u][1])],
                                         g.permutation[static_cast<std::size_t>(triples[u][2])]};
                const int parity = sort_triple(image);
                const auto v = static_cast<std::size_t>(alternating_index(m, image[0], image[1], image[2]));
                const int sv = sign[u] * parity * g.sign;
                if (raw_orbit[v] == -1) {
                    raw_orbit[v] = q;
                    sign[v] = sv;
                    queue.push_back(v);
                } else if (sign[v] != sv) {
                    zero[static_cast<std::size_t>(q)] = true;
                }
            }
        }
    }
    TripleOrbits out;
    std::vector<int> renumber(static_cast<std::size_t>(orbits), -1);
    out.orbit.assign(count, -1);
    out.sign = sign;
    for (std::size_t t = 0; t < count; ++t) {
        const auto q = static_cast<std::size_t>(raw_orbit[t]);
        if (zero[q]) {
            continue;
        }
        if (renumber[q] == -1) {
            renumber[q] = static_cast<int>(out.representative.size());
            out.representative.push_back(static_cast<int>(t));
        }
        out.orbit[t] = renumber[q];
    }
    return out;
}

/// Null space of a square matrix by exact Gauss–Jordan elimination (exact scalars only).
template <class Scalar>
std::vector<std::vector<Scalar>> null_space(Dense<Scalar> A) {
    const int n = A.cols;
    std::vector<int> pivot_column;
    int row = 0;
    for (int col = 0; col < n && row < A.rows; ++col) {
        int p = row;
        while (p < A.rows && A(p, col) == 0) {
            ++p;
        }
        if (p == A.rows) {
            continue;
        }
        for (int c = 0; c < n; ++c) {
            std::swap(A(row, c), A(p, c));
        }
        const Scalar inv = Scalar(1) / A(row, col);
        for (int c = 0; c < n; ++c) {
            A(row, c) *= inv;
        }
        for (int r = 0; r < A.rows; ++r) {
            if (r == row || A(r, col) == 0) {
                continue;
            }
            const Scalar f = A(r, col);
            for (int c = 0; c < n; ++c) {
                if (A(row, c) != 0) {
                    A(r, c) -= f * A(row, c);
                }
            }
        }
        pivot_column.push_back(col);
        ++row;
    }
    std::vector<bool> is_pivot(static_cast<std::size_t>(n), false);
    for (const int c : pivot_column) {
        is_pivot[static_cast<std::size_t>(c)] = true;
    }
    std::vector<std::vector<Scalar>> basis;
    for (int free = 0; free < n; ++free) {
        if (is_pivot[static_cast<std::size_t>(free)]) {
            continue;
        }
        std::vector<Scalar> x(static_cast<std::size_t>(n), Scalar(0));
        x[static_cast<std::size_t>(free)] = Scalar(1);
        for (std::size_t r = 0; r < pivot_column.size(); ++r) {
            x[static_cast<std::size_t>(pivot_column[r])] = -A(static_cast<int>(r), free);
        }
        basis.push_back(std::move(x));
    }
    return basis;
}

/// The degenerate calibration mesh (see the header comment) with integer corner coordinates.
struct DegenerateMesh {
    Topology topology;
    std::vector<std::array<int, 3>> positions;
    int volume_numerator = 1;  ///< enclosed volume = numerator / denominator
    int volume_denominator = 1;
};

inline DegenerateMesh degenerate_mesh(SchemeKind scheme) {
    const bool tetrahedron = scheme == SchemeKind::Loop;
    const std::vector<std::array<int, 3>> corners =
        tetrahedron ? std::vector<std::array<int, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}
                    : std::vector<std::array<int, 3>>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                                      {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    const std::vector<std::vector<Index>> faces =
        tetrahedron ? std::vector<std::vector<Index>>{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}
                    : std::vector<std::vector<Index>>{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                      {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    Topology t = Topology::from_polygons(static_cast<Index>(corners.size()), faces);
    Points X(static_cast<Eigen::Index>(corners.size()), 3);
    for (std::size_t v = 0; v < corners.size(); ++v) {
        for (int c = 0; c < 3; ++c) {
            X(static_cast<Eigen::Index>(v), c) = corners[v][static_cast<std::size_t>(c)];
        }
    }
    const int times = scheme == SchemeKind::DooSabin ? 2 : 3;
    for (int i = 0; i < times; ++i) {
        Level level = tetrahedron ? refine_linear(t) : refine_bilinear(t);
        X = Points(level.S0 * X);
        t = std::move(level.topology);
    }
    DegenerateMesh mesh{std::move(t), {}, 1, tetrahedron ? 6 : 1};
    for (Eigen::Index v = 0; v < X.rows(); ++v) {
        // The nearest corner: of the cube, each coordinate rounded (ties down); of the tetrahedron,
        // the corner of the largest barycentric coordinate (ties to the first), which is the nearest
        // corner of a regular tetrahedron — the paper's construction — in affine terms. Exact,
        // since X holds dyadic fractions.
        if (!tetrahedron) {
            mesh.positions.push_back({X(v, 0) <= 0.5 ? 0 : 1, X(v, 1) <= 0.5 ? 0 : 1, X(v, 2) <= 0.5 ? 0 : 1});
            continue;
        }
        const std::array<double, 4> barycentric{1.0 - X(v, 0) - X(v, 1) - X(v, 2), X(v, 0), X(v, 1), X(v, 2)};
        std::size_t best = 0;
        for (std::size_t c = 1; c < 4; ++c) {
            if (barycentric[c] > barycentric[best]) {
                best = c;
            }
        }
        mesh.positions.push_back(corners[best]);
    }
    return mesh;
}

/// True when every control point the element's surface depends on sits on one corner.
inline bool collapsed(const DegenerateMesh& mesh, SchemeKind scheme, Index element) {
    const Topology& t = mesh.topology;
    std::vector<Index> support;
    const auto add_faces_around = [&](Index v) {
        for (const Index f : t.vertex_faces(v)) {
            for (const Index u : t.face_vertices(f)) {
                support.push_back(u);
            }
        }
    };
    if (scheme == SchemeKind::DooSabin) {
        add_faces_around(element);
    } else {
        for (const Index v : t.face_vertices(element)) {
            add_faces_around(v);
        }
    }
    for (const Index u : support) {
        if (mesh.positions[static_cast<std::size_t>(u)] != mesh.positions[static_cast<std::size_t>(support[0])]) {
            return false;
        }
    }
    return true;
}

template <class Scalar>
Scalar det3(const std::array<int, 3>& a, const std::array<int, 3>& b, const std::array<int, 3>& c) {
    const long d = static_cast<long>(a[0]) * (b[1] * c[2] - b[2] * c[1]) -
                   static_cast<long>(a[1]) * (b[0] * c[2] - b[2] * c[0]) +
                   static_cast<long>(a[2]) * (b[0] * c[1] - b[1] * c[0]);
    return Scalar(static_cast<int>(d));
}

/// The regular form and the facts of its derivation.
template <class Scalar>
struct RegularForm {
    std::vector<Scalar> coefficients;  ///< C(m,3), lexicographic
    int unknowns = 0;                  ///< symmetry orbits
    int null_space_dimension = 0;      ///< of (E - I) on the orbits: 1 expected
};

/// @brief Corollary 1 with the facet's symmetries, calibrated on the degenerate mesh.
/// @throws NumericalError when the null space is not a line or the calibration fails
template <class Scalar>
RegularForm<Scalar> solve_regular_form(SchemeKind scheme) {
    const int type = regular_facet_type(scheme);
    const FacetSeed seed = make_facet_seed(scheme, type);
    const int m = static_cast<int>(seed.ring.points.size());
    const TripleOrbits orbits = triple_orbits(m, regular_symmetries(seed));
    const int unknowns = static_cast<int>(orbits.representative.size());
    std::vector<std::array<int, 3>> triples;
    for (int i = 0; i < m; ++i) {
        for (int j = i + 1; j < m; ++j) {
            for (int k = j + 1; k < m; ++k) {
                triples.push_back({i, j, k});
            }
        }
    }
    Dense<Scalar> R(unknowns, unknowns);
    for (const FacetRing& child : seed.children) {
        const Dense<Scalar> S = facet_subdivision_matrix<Scalar>(seed, seed.ring, child);
        for (int r = 0; r < unknowns; ++r) {
            const auto& t = triples[static_cast<std::size_t>(orbits.representative[static_cast<std::size_t>(r)])];
            for (int a = 0; a < m; ++a) {
                if (S(a, t[0]) == 0) {
                    continue;
                }
                for (int b = 0; b < m; ++b) {
                    if (S(b, t[1]) == 0) {
                        continue;
                    }
                    const Scalar ab = S(a, t[0]) * S(b, t[1]);
                    for (int c = 0; c < m; ++c) {
                        if (S(c, t[2]) == 0) {
                            continue;
                        }
                        std::array<int, 3> image{a, b, c};
                        const int parity = sort_triple(image);
                        if (parity == 0) {
                            continue;
                        }
                        const auto u = static_cast<std::size_t>(alternating_index(m, image[0], image[1], image[2]));
                        if (orbits.orbit[u] < 0) {
                            continue;
                        }
                        R(r, orbits.orbit[u]) += ab * S(c, t[2]) * Scalar(parity * orbits.sign[u]);
                    }
                }
            }
        }
    }
    for (int r = 0; r < unknowns; ++r) {
        R(r, r) -= Scalar(1);
    }
    const auto basis = null_space(R);
    RegularForm<Scalar> out;
    out.unknowns = unknowns;
    out.null_space_dimension = static_cast<int>(basis.size());
    LIMSURF_CHECK(basis.size() == 1, NumericalError, "Corollary 1 for ", to_string(scheme),
                  ": the null space has dimension ", basis.size(), ", expected 1");
    std::vector<Scalar> y(triples.size(), Scalar(0));
    for (std::size_t t = 0; t < triples.size(); ++t) {
        if (orbits.orbit[t] >= 0) {
            y[t] = basis[0][static_cast<std::size_t>(orbits.orbit[t])] * Scalar(orbits.sign[t]);
        }
    }
    // Calibration.
    const DegenerateMesh mesh = degenerate_mesh(scheme);
    const Index elements = num_facet_elements(mesh.topology, scheme);
    Scalar sum(0);
    for (Index e = 0; e < elements; ++e) {
        const auto ring = typed_facet(mesh.topology, scheme, e);
        if (!ring || ring->type != type) {
            LIMSURF_CHECK(collapsed(mesh, scheme, e), NumericalError,
                          "the degenerate calibration mesh has an irregular element that is not collapsed");
            continue;
        }
        for (std::size_t t = 0; t < triples.size(); ++t) {
            if (y[t] == 0) {
                continue;
            }
            const auto& p = ring->points;
            const Scalar d =
                det3<Scalar>(mesh.positions[static_cast<std::size_t>(p[static_cast<std::size_t>(triples[t][0])])],
                             mesh.positions[static_cast<std::size_t>(p[static_cast<std::size_t>(triples[t][1])])],
                             mesh.positions[static_cast<std::size_t>(p[static_cast<std::size_t>(triples[t][2])])]);
            if (d != 0) {
                sum += y[t] * d;
            }
        }
    }
    LIMSURF_CHECK(sum != 0, NumericalError, "the calibration volume is zero");
    const Scalar scale = Scalar(mesh.volume_numerator) / (Scalar(mesh.volume_denominator) * sum);
    for (Scalar& c : y) {
        c *= scale;
    }
    out.coefficients = std::move(y);
    return out;
}

}  // namespace limsurf::detail
