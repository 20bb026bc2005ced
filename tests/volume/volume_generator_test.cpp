// The generator of the volume forms against the paper (volume-trilinear-forms): the regular forms
// of Corollary 1 (exact, GMP rationals) equal the alternation of the integral form
// Ā_ijk = ∫ B_i ∂_s B_j ∂_t B_k of the paper's polynomial bases (Doo–Sabin, Catmull–Clark); the
// paper's example coefficients, regular and irregular, under its vertex numbering; the shipped
// tables are the generator's output; the generator's stencils are the engine's rules.
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/volume/regular_form.h"
#include "limsurf/volume/shipped_forms.h"
#include "multiprecision.h"

namespace limsurf {
namespace {

using detail::Float100;
using detail::Rational;

// --- exact univariate polynomials over the rationals ---------------------------------------------

using Polynomial = std::vector<Rational>;  // coefficients of 1, s, s², ...

Polynomial multiply(const Polynomial& a, const Polynomial& b) {
    Polynomial c(a.size() + b.size() - 1, Rational(0));
    for (std::size_t i = 0; i < a.size(); ++i) {
        for (std::size_t j = 0; j < b.size(); ++j) {
            c[i + j] += a[i] * b[j];
        }
    }
    return c;
}

Polynomial derivative(const Polynomial& a) {
    Polynomial d(std::max<std::size_t>(a.size(), 2) - 1, Rational(0));
    for (std::size_t i = 1; i < a.size(); ++i) {
        d[i - 1] = a[i] * Rational(static_cast<int>(i));
    }
    return d;
}

Rational integral01(const Polynomial& a) {
    Rational sum(0);
    for (std::size_t i = 0; i < a.size(); ++i) {
        sum += a[i] / Rational(static_cast<int>(i + 1));
    }
    return sum;
}

/// The paper's univariate bases: Doo–Sabin (quadratic) and Catmull–Clark (cubic) B-splines on [0,1].
std::vector<Polynomial> univariate_basis(SchemeKind scheme) {
    if (scheme == SchemeKind::DooSabin) {
        return {{Rational(1, 2), Rational(-1), Rational(1, 2)},
                {Rational(1, 2), Rational(1), Rational(-1)},
                {Rational(0), Rational(0), Rational(1, 2)}};
    }
    return {{Rational(1, 6), Rational(-1, 2), Rational(1, 2), Rational(-1, 6)},
            {Rational(2, 3), Rational(0), Rational(-1), Rational(1, 2)},
            {Rational(1, 6), Rational(1, 2), Rational(1, 2), Rational(-1, 2)},
            {Rational(0), Rational(0), Rational(0), Rational(1, 6)}};
}

/// Ā over the tensor-product basis, indexed by the paper's numbering 1 + a + w·b (0-based here):
/// ∫∫ B_i ∂_s B_j ∂_t B_k = (∫ b_{a_i} b'_{a_j} b_{a_k} ds) (∫ b_{b_i} b_{b_j} b'_{b_k} dt).
struct IntegralForm {
    int w = 0;  ///< points per row
    std::vector<Rational> a;
    Rational operator()(int i, int j, int k) const {
        const auto n = static_cast<std::size_t>(w * w);
        return a[(static_cast<std::size_t>(i) * n + static_cast<std::size_t>(j)) * n + static_cast<std::size_t>(k)];
    }
    /// The paper's Ŷ = ⅙ Σ signed permutations of Ȳ, Ȳ_ijk = Ā_ijk − Ā_ikj.
    Rational alternating(int i, int j, int k) const {
        const auto y = [&](int p, int q, int r) { return (*this)(p, q, r) - (*this)(p, r, q); };
        return (y(i, j, k) - y(i, k, j) + y(j, k, i) - y(j, i, k) + y(k, i, j) - y(k, j, i)) / Rational(6);
    }
};

IntegralForm integral_form(SchemeKind scheme) {
    const std::vector<Polynomial> b = univariate_basis(scheme);
    const int w = static_cast<int>(b.size());
    std::vector<Polynomial> db;
    for (const Polynomial& p : b) {
        db.push_back(derivative(p));
    }
    // U(p, q, r) = ∫ b_p b'_q b_r.
    std::vector<Rational> U(static_cast<std::size_t>(w * w * w));
    for (int p = 0; p < w; ++p) {
        for (int q = 0; q < w; ++q) {
            for (int r = 0; r < w; ++r) {
                U[static_cast<std::size_t>((p * w + q) * w + r)] = integral01(multiply(multiply(b[p], db[q]), b[r]));
            }
        }
    }
    const auto u = [&](int p, int q, int r) { return U[static_cast<std::size_t>((p * w + q) * w + r)]; };
    IntegralForm form{w, {}};
    const int n = w * w;
    form.a.resize(static_cast<std::size_t>(n * n * n));
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                // ∫ B_i ∂_s B_j ∂_t B_k: s factor b_{a_i} b'_{a_j} b_{a_k}, t factor b_{b_i} b_{b_j} b'_{b_k}.
                form.a[static_cast<std::size_t>((i * n + j) * n + k)] = u(i % w, j % w, k % w) * u(i / w, k / w, j / w);
            }
        }
    }
    return form;
}

/// Our canonical regular numbering as grid points (a, b), a along s (facet_ring.h).
const std::vector<std::array<int, 2>>& grid_of(SchemeKind scheme) {
    static const std::vector<std::array<int, 2>> doo_sabin{{1, 1}, {2, 1}, {2, 2}, {1, 2}, {0, 2},
                                                           {0, 1}, {0, 0}, {1, 0}, {2, 0}};
    static const std::vector<std::array<int, 2>> catmull_clark{{1, 1}, {2, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1},
                                                               {0, 0}, {1, 0}, {2, 0}, {3, 0}, {3, 1}, {3, 2},
                                                               {3, 3}, {2, 3}, {1, 3}, {0, 3}};
    return scheme == SchemeKind::DooSabin ? doo_sabin : catmull_clark;
}

/// Our coefficient c at (i, j, k) in any order (alternating).
template <class Scalar>
Scalar coefficient(const std::vector<Scalar>& c, int m, std::array<int, 3> ijk) {
    const int sign = detail::sort_triple(ijk);
    if (sign == 0) {
        return Scalar(0);
    }
    return Scalar(sign) * c[static_cast<std::size_t>(detail::alternating_index(m, ijk[0], ijk[1], ijk[2]))];
}

/// Our index of each paper index (1-based) given our -> paper.
std::map<int, int> inverse(const std::vector<int>& ours_to_paper) {
    std::map<int, int> out;
    for (std::size_t i = 0; i < ours_to_paper.size(); ++i) {
        out[ours_to_paper[i]] = static_cast<int>(i);
    }
    return out;
}

template <class Scalar>
Scalar paper_value(const std::vector<Scalar>& c, int m, const std::vector<int>& ours_to_paper, int i, int j, int k) {
    const auto ours = inverse(ours_to_paper);
    return coefficient(c, m, {ours.at(i), ours.at(j), ours.at(k)});
}

// --- Corollary 1 against the integral form ------------------------------------------------------

class RegularForm : public ::testing::TestWithParam<SchemeKind> {};

TEST_P(RegularForm, Corollary1IsTheAlternationOfTheIntegralForm) {
    const SchemeKind scheme = GetParam();
    const auto solved = detail::solve_regular_form<Rational>(scheme);
    EXPECT_EQ(solved.null_space_dimension, 1);
    const IntegralForm integral = integral_form(scheme);
    const auto& grid = grid_of(scheme);
    const int m = static_cast<int>(grid.size());
    const auto paper = [&](int ours) {
        return grid[static_cast<std::size_t>(ours)][0] + integral.w * grid[static_cast<std::size_t>(ours)][1];
    };
    int compared = 0;
    for (int i = 0; i < m; ++i) {
        for (int j = i + 1; j < m; ++j) {
            for (int k = j + 1; k < m; ++k) {
                EXPECT_EQ(coefficient(solved.coefficients, m, {i, j, k}),
                          integral.alternating(paper(i), paper(j), paper(k)))
                    << i << ' ' << j << ' ' << k;
                ++compared;
            }
        }
    }
    EXPECT_EQ(compared, detail::num_alternating(m));
}

INSTANTIATE_TEST_SUITE_P(Volume, RegularForm, ::testing::Values(SchemeKind::DooSabin, SchemeKind::CatmullClark),
                         [](const ::testing::TestParamInfo<SchemeKind>& param) {
                             return param.param == SchemeKind::DooSabin ? std::string("DooSabin")
                                                                        : std::string("CatmullClark");
                         });

// --- the paper's example coefficients -------------------------------------------------------------

TEST(VolumeGenerator, PublishedRegularCoefficients) {
    // Doo–Sabin: Ā⁴₈,₁,₂ = 3/3200 and Â⁴₈,₁,₂ = 11/19200 (Â = Ŷ/2); paper index 1 + a + 3b.
    const IntegralForm ds = integral_form(SchemeKind::DooSabin);
    EXPECT_EQ(ds(7, 0, 1), Rational(3, 3200));
    const auto ds_form = detail::solve_regular_form<Rational>(SchemeKind::DooSabin).coefficients;
    const std::vector<int> ds_paper{5, 6, 9, 8, 7, 4, 1, 2, 3};  // ours -> paper (grid_of, 1 + a + 3b)
    EXPECT_EQ(paper_value(ds_form, 9, ds_paper, 8, 1, 2) / 2, Rational(11, 19200));
    // Catmull–Clark: Ā⁴₅,₁,₆ = 3103/48771072 and Â⁴₅,₁,₆ = 61595/877879296; paper index 1 + a + 4b.
    const IntegralForm cc = integral_form(SchemeKind::CatmullClark);
    EXPECT_EQ(cc(4, 0, 5), Rational(3103, 48771072));
    const auto cc_form = detail::solve_regular_form<Rational>(SchemeKind::CatmullClark).coefficients;
    const std::vector<int> cc_paper{6, 7, 11, 10, 9, 5, 1, 2, 3, 4, 8, 12, 16, 15, 14, 13};
    EXPECT_EQ(paper_value(cc_form, 16, cc_paper, 5, 1, 6) / 2, Rational(61595, 877879296));
    // Loop: Â⁶₅,₁,₇ = 1787/119750400, numbering in rows [1 2 3] [4 5 6 7] [8 9 10] [11 12], facet (5, 6, 9).
    // The paper's figure is drawn with the outward normal into the page: in our orientation the value
    // is the negative.
    const auto loop_form = detail::solve_regular_form<Rational>(SchemeKind::Loop).coefficients;
    const std::vector<int> loop_paper{9, 6, 5, 8, 11, 12, 10, 7, 3, 2, 1, 4};
    EXPECT_EQ(paper_value(loop_form, 12, loop_paper, 5, 1, 7) / 2, Rational(-1787, 119750400));
}

TEST(VolumeGenerator, PublishedIrregularCoefficients) {
    const auto relative = [](const Float100& a, const Float100& b) { return static_cast<double>(abs(a - b) / abs(b)); };
    const Float100 tolerance("1e-85");
    // Doo–Sabin type 3 (a triangle at paper points 5, 6, 8): Ŷ³₈,₇,₂ = 3324559/2891332800.
    std::vector<Float100> ds_regular;
    for (const Rational& c : detail::solve_regular_form<Rational>(SchemeKind::DooSabin).coefficients) {
        ds_regular.emplace_back(c);
    }
    const auto ds3 = detail::solve_irregular_form<Float100>(SchemeKind::DooSabin, 3, ds_regular, tolerance);
    const std::vector<int> ds3_paper{5, 6, 8, 7, 4, 1, 2, 3};
    EXPECT_LT(relative(paper_value(ds3.coefficients, 8, ds3_paper, 8, 7, 2), Float100(Rational(3324559, 2891332800))),
              1e-80);
    // Loop type 4 (the extraordinary vertex is paper point 9, its ring 6, 5, 8, 10):
    // Ŷ⁴₁₀,₈,₉ = 22663731969915204014725535462759500947683 / 18792363864674566857783671734314366207000000,
    // with the same orientation sign as the regular Loop coefficient.
    std::vector<Float100> loop_regular;
    for (const Rational& c : detail::solve_regular_form<Rational>(SchemeKind::Loop).coefficients) {
        loop_regular.emplace_back(c);
    }
    const auto loop4 = detail::solve_irregular_form<Float100>(SchemeKind::Loop, 4, loop_regular, tolerance);
    const std::vector<int> loop4_paper{9, 6, 5, 8, 10, 7, 3, 2, 1, 4};
    const Rational published(boost::multiprecision::mpz_int("22663731969915204014725535462759500947683"),
                             boost::multiprecision::mpz_int("18792363864674566857783671734314366207000000"));
    EXPECT_LT(relative(paper_value(loop4.coefficients, 10, loop4_paper, 10, 8, 9), -Float100(published)), 1e-80);
    EXPECT_LT(static_cast<double>(ds3.residual), 1e-120);
    EXPECT_LT(static_cast<double>(loop4.residual), 1e-120);
}

// --- shipped tables, engine rules, on-demand precision ---------------------------------------------

std::vector<double> shipped(SchemeKind scheme, int type) {
    for (const detail::ShippedForm& form : detail::shipped_forms()) {
        if (form.scheme == scheme && form.type == type) {
            return {form.coefficients, form.coefficients + detail::num_alternating(form.size)};
        }
    }
    return {};
}

TEST(VolumeGenerator, ShippedTablesAreTheGeneratedForms) {
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin}) {
        const auto exact = detail::solve_regular_form<Rational>(scheme).coefficients;
        const std::vector<double> table = shipped(scheme, detail::regular_facet_type(scheme));
        ASSERT_EQ(table.size(), exact.size());
        std::vector<Float100> regular;
        for (std::size_t i = 0; i < exact.size(); ++i) {
            EXPECT_EQ(table[i], exact[i].convert_to<double>()) << to_string(scheme) << ' ' << i;
            regular.emplace_back(exact[i]);
        }
        for (int type = 3; type <= 12; ++type) {
            ASSERT_EQ(shipped(scheme, type).size(),
                      static_cast<std::size_t>(detail::num_alternating(detail::facet_ring_size(scheme, type))));
        }
        // Irregular tables: a few types in 100 digits (the ctest volume_forms.reproducible compares all).
        for (const int type : {3, 7}) {
            const auto form = detail::solve_irregular_form<Float100>(scheme, type, regular, Float100("1e-85"));
            const std::vector<double> t = shipped(scheme, type);
            for (std::size_t i = 0; i < t.size(); ++i) {
                EXPECT_EQ(t[i], form.coefficients[i].convert_to<double>()) << to_string(scheme) << ' ' << type;
            }
        }
    }
}

TEST(VolumeGenerator, DoublePrecisionGenerationAgreesWithTheTables) {
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin}) {
        const std::vector<double> regular = shipped(scheme, detail::regular_facet_type(scheme));
        for (const int type : {5, 12}) {
            const auto form = detail::solve_irregular_form<double>(scheme, type, regular, 1e-17);
            const std::vector<double> t = shipped(scheme, type);
            double scale = 0.0;
            double worst = 0.0;
            for (std::size_t i = 0; i < t.size(); ++i) {
                scale = std::max(scale, std::abs(t[i]));
                worst = std::max(worst, std::abs(t[i] - form.coefficients[i]));
            }
            EXPECT_LT(worst, 1e-14 * scale) << to_string(scheme) << ' ' << type;
            EXPECT_LT(form.residual, 1e-14);
        }
    }
}

TEST(VolumeGenerator, ExactStencilsAreTheEngineRules) {
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin}) {
        for (const int type : {3, 5, 7, 12}) {
            const detail::FacetSeed seed = detail::make_facet_seed(scheme, type);
            int rows = 0;
            for (const detail::FacetRing& child : seed.children) {
                for (const Index c : child.points) {
                    const auto stencil = detail::child_stencil<double>(seed.parent, seed.child, scheme, c);
                    std::map<Index, double> engine;
                    for (SparseMatrix::InnerIterator it(seed.child.S0, c); it; ++it) {
                        engine[static_cast<Index>(it.col())] += it.value();
                    }
                    ASSERT_EQ(stencil.size(), engine.size()) << to_string(scheme) << ' ' << type << ' ' << c;
                    for (const auto& [v, w] : stencil) {
                        EXPECT_NEAR(w, engine.at(v), 1e-15) << to_string(scheme) << ' ' << type << ' ' << c;
                    }
                    ++rows;
                }
            }
            EXPECT_GT(rows, 30);
        }
    }
}

}  // namespace
}  // namespace limsurf
