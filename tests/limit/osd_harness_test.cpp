// Self-test of the two limit-evaluation references (tests/limit/support):
// OpenSubdiv's patch evaluation (osd_limit.h) and deep subdivision with limsurf's
// refinement (deep_subdivision.h) agree to 1e-12 of the bounding-box diagonal,
// second derivatives included, wherever both are exact (OpenSubdiv's regular
// patches); the corrections of Far 3.5's derivative defects match central
// differences of Far's own positions; Far's vertex limits match its patches.
#include <cmath>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "deep_subdivision.h"
#include "limsurf/io/mesh_io.h"
#include "osd_limit.h"
#include "support/mesh_zoo.h"

namespace limsurf::test {
namespace {

struct Mesh {
    Topology topology;
    Points positions;
    double diagonal = 0.0;
};

Mesh load(const std::string& name) {
    const BuildResult built = read_mesh(find_bundled(name).path);
    Mesh m{built.mesh.topology(), built.mesh.positions()};
    m.diagonal = (m.positions.colwise().maxCoeff() - m.positions.colwise().minCoeff()).norm();
    return m;
}

/// Moves every control point by a random offset of up to @p amount times the diagonal.
void perturb(Mesh& m, double amount) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> uniform(-amount * m.diagonal, amount * m.diagonal);
    for (Index i = 0; i < m.positions.size(); ++i) {
        m.positions.data()[i] += uniform(rng);
    }
}

/// @p per_face random points in every ptex face (triangles: u + v <= 1).
std::vector<SurfacePoint> random_points(Index num_ptex, bool triangles, int per_face, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::vector<SurfacePoint> points;
    for (Index p = 0; p < num_ptex; ++p) {
        for (int i = 0; i < per_face; ++i) {
            double u = uniform(rng);
            double v = uniform(rng);
            if (triangles && u + v > 1.0) {
                u = 1.0 - u;
                v = 1.0 - v;
            }
            points.push_back({p, u, v});
        }
    }
    return points;
}

const char* row_name(int r) {
    static const char* names[] = {"position", "du", "dv", "duu", "duv", "dvv"};
    return names[r];
}

/// OpenSubdiv's regular patches (isolated to `levels`, so their depth is <= levels)
/// against deep subdivision `levels` deep, on randomly perturbed control points.
/// Closed smooth meshes: every regular Far patch must be a regular deep-subdivision patch.
/// With boundaries or creases (`features`), Far's regular boundary patches and patches with
/// sharp edges only in their outer ring are skipped (deep subdivision refuses them).
void compare_regular(const std::string& name, SchemeKind scheme, int levels, int per_face,
                     const SchemeOptions& options = {}, bool features = false) {
    SCOPED_TRACE(name);
    Mesh m = load(name);
    perturb(m, 0.02);
    const OsdLimitEvaluator osd(m.topology, m.positions, scheme, options, levels);
    const DeepSubdivision deep(m.topology, m.positions, scheme, options, levels);
    ASSERT_EQ(osd.num_ptex_faces(), deep.num_ptex_faces());
    const auto points = random_points(osd.num_ptex_faces(), scheme == SchemeKind::Loop, per_face, 17);
    const double tolerance = 1e-12 * m.diagonal;
    int compared = 0, non_quad_root = 0, rotated = 0, deepest = 0;
    double worst[6] = {};
    for (const SurfacePoint& p : points) {
        const OsdPointEval o = osd.evaluate(p);
        if (!o.regular) {
            continue;
        }
        ASSERT_LE(o.depth, levels);
        if (!deep.is_regular_at(p)) {
            ASSERT_TRUE(features) << "ptex " << p.face << " (" << p.u << ", " << p.v << ")";
            continue;
        }
        const Eigen::Matrix<double, 6, 3> d = deep.evaluate(p);
        for (int r = 0; r < 6; ++r) {
            const double error = (o.value.row(r) - d.row(r)).norm();
            worst[r] = std::max(worst[r], error);
            EXPECT_LE(error, tolerance) << row_name(r) << " at ptex " << p.face << " (" << p.u << ", " << p.v
                                        << "), depth " << o.depth << "\nosd  " << o.value.row(r) << "\ndeep "
                                        << d.row(r);
        }
        ++compared;
        non_quad_root += o.non_quad_root ? 1 : 0;
        rotated += o.triangle_rotated ? 1 : 0;
        deepest = std::max(deepest, o.depth);
    }
    EXPECT_GE(compared, static_cast<int>(points.size()) / (features ? 5 : 3)) << "too few regular points";
    if (!m.topology.all_faces_have_degree(scheme == SchemeKind::Loop ? 3 : 4)) {
        EXPECT_GT(non_quad_root, 0) << "no n-gon sub-face patch compared";
    }
    if (scheme == SchemeKind::Loop && deepest > 0) {
        EXPECT_GT(rotated, 0) << "no rotated sub-triangle compared";
    }
    std::cout << name << ": " << compared << " of " << points.size() << " points compared (" << non_quad_root
              << " in n-gon sub-faces, " << rotated << " in rotated triangles); worst error / diagonal:";
    for (int r = 0; r < 6; ++r) {
        std::cout << ' ' << row_name(r) << ' ' << worst[r] / m.diagonal;
    }
    std::cout << '\n';
}

TEST(LimitReferences, CatmullClarkRegularPatchesAgree) {
    compare_regular("cube", SchemeKind::CatmullClark, 5, 12);
    compare_regular("quad_torus", SchemeKind::CatmullClark, 2, 6);
    compare_regular("cube_ngons", SchemeKind::CatmullClark, 4, 8);
    compare_regular("quad_valence_5", SchemeKind::CatmullClark, 4, 6);
    compare_regular("genus2", SchemeKind::CatmullClark, 3, 4);
}

TEST(LimitReferences, LoopRegularPatchesAgree) {
    compare_regular("icosahedron", SchemeKind::Loop, 4, 10);
    compare_regular("tri_torus", SchemeKind::Loop, 2, 4);
    compare_regular("tri_valence_7", SchemeKind::Loop, 4, 6);
}

/// Boundaries (three rules), semi-sharp and infinitely sharp creases, a corner and
/// Chaikin creasing: the interior regular patches still agree (the tags reach Far).
TEST(LimitReferences, RegularPatchesAgreeWithBoundariesAndCreases) {
    for (const auto boundary :
         {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::None}) {
        const SchemeOptions options{boundary, CreasingMethod::Uniform, TriangleSubdivision::CatmullClark};
        compare_regular("disk_ev5_quads", SchemeKind::CatmullClark, 3, 3, options, true);
        compare_regular("disk_ev7_tris", SchemeKind::Loop, 3, 3, options, true);
    }
    for (const auto creasing : {CreasingMethod::Uniform, CreasingMethod::Chaikin}) {
        const SchemeOptions options{BoundaryInterpolation::EdgeAndCorner, creasing, TriangleSubdivision::CatmullClark};
        compare_regular("cube_creases", SchemeKind::CatmullClark, 4, 12, options, true);
    }
}

/// Central differences of Far's positions within one patch.
struct Differences {
    Eigen::Matrix<double, 5, 3> d;  // du, dv, duu, duv, dvv
    bool same_patch = true;
};

Differences central_differences(const OsdLimitEvaluator& osd, const SurfacePoint& p, int patch, double h) {
    Differences out;
    const auto at = [&](double du, double dv) -> Eigen::RowVector3d {
        const OsdPointEval e = osd.evaluate({p.face, p.u + du, p.v + dv});
        out.same_patch = out.same_patch && e.has_patch && e.patch == patch;
        return e.value.row(0);
    };
    const Eigen::RowVector3d c = at(0, 0);
    const Eigen::RowVector3d up = at(h, 0), um = at(-h, 0), vp = at(0, h), vm = at(0, -h);
    const Eigen::RowVector3d pp = at(h, h), pm = at(h, -h), mp = at(-h, h), mm = at(-h, -h);
    out.d.row(0) = (up - um) / (2 * h);
    out.d.row(1) = (vp - vm) / (2 * h);
    out.d.row(2) = (up - 2 * c + um) / (h * h);
    out.d.row(3) = (pp - pm - mp + mm) / (4 * h * h);
    out.d.row(4) = (vp - 2 * c + vm) / (h * h);
    return out;
}

/// Far's derivatives (corrected) against central differences of its positions, at points
/// whose difference stencil stays inside one patch; counts the points where the
/// correction mattered (the uncorrected derivatives would have failed).
void check_against_differences(const std::string& name, SchemeKind scheme, bool want_non_quad_root, bool want_rotated) {
    SCOPED_TRACE(name);
    const Mesh m = load(name);
    const OsdLimitEvaluator osd(m.topology, m.positions, scheme, SchemeOptions{}, 3);
    const auto points = random_points(osd.num_ptex_faces(), scheme == SchemeKind::Loop, 10, 5);
    constexpr double h = 1e-4;
    const double tolerance = 1e-5 * m.diagonal;
    int checked = 0, corrected_non_quad = 0, corrected_rotated = 0;
    for (const SurfacePoint& p : points) {
        if (p.u < 2 * h || p.v < 2 * h || p.u > 1 - 2 * h || p.v > 1 - 2 * h ||
            (scheme == SchemeKind::Loop && p.u + p.v > 1 - 4 * h)) {
            continue;
        }
        const OsdPointEval o = osd.evaluate(p);
        ASSERT_TRUE(o.has_patch);
        if (!o.regular) {
            continue;  // Far's Gregory derivatives are not those of its positions (see osd_limit.h)
        }
        const Differences fd = central_differences(osd, p, o.patch, h);
        if (!fd.same_patch) {
            continue;
        }
        ++checked;
        for (int r = 1; r < 6; ++r) {
            EXPECT_LE((o.value.row(r) - fd.d.row(r - 1)).norm(), tolerance)
                << row_name(r) << " at ptex " << p.face << " (" << p.u << ", " << p.v << "), depth " << o.depth
                << (o.non_quad_root ? " non-quad root" : "") << (o.triangle_rotated ? " rotated" : "")
                << (o.end_cap ? " end cap" : "") << "\nosd " << o.value.row(r) << "\nfd  " << fd.d.row(r - 1);
        }
        // What Far 3.5 returns before the correction.
        Eigen::Matrix<double, 6, 3> raw = o.value;
        if (o.non_quad_root) {
            raw.middleRows(1, 2) *= 2.0;
            raw.bottomRows(3) *= 4.0;
        }
        if (o.triangle_rotated) {
            raw.bottomRows(3) *= -1.0;
        }
        bool raw_fails = false;
        for (int r = 1; r < 6; ++r) {
            raw_fails = raw_fails || (raw.row(r) - fd.d.row(r - 1)).norm() > tolerance;
        }
        corrected_non_quad += o.non_quad_root && raw_fails ? 1 : 0;
        corrected_rotated += o.triangle_rotated && raw_fails ? 1 : 0;
    }
    EXPECT_GE(checked, static_cast<int>(points.size()) / 2);
    if (want_non_quad_root) {
        EXPECT_GT(corrected_non_quad, 0) << "no point where the n-gon correction mattered";
    }
    if (want_rotated) {
        EXPECT_GT(corrected_rotated, 0) << "no point where the rotated-triangle correction mattered";
    }
}

TEST(LimitReferences, NonQuadRootDerivativesCorrected) {
    check_against_differences("cube_ngons", SchemeKind::CatmullClark, true, false);
    check_against_differences("dodecahedron", SchemeKind::CatmullClark, true, false);
    check_against_differences("tetrahedron", SchemeKind::CatmullClark, true, false);
    check_against_differences("cube", SchemeKind::CatmullClark, false, false);
}

TEST(LimitReferences, RotatedTriangleDerivativesCorrected) {
    check_against_differences("icosahedron", SchemeKind::Loop, false, true);
    check_against_differences("tri_valence_4", SchemeKind::Loop, false, true);
}

TEST(LimitReferences, VertexLimitsMatchPatchCorners) {
    for (const auto& [name, scheme] : {std::pair<std::string, SchemeKind>{"cube", SchemeKind::CatmullClark},
                                       {"cube_ngons", SchemeKind::CatmullClark},
                                       {"genus2", SchemeKind::CatmullClark},
                                       {"icosahedron", SchemeKind::Loop},
                                       {"tri_valence_7", SchemeKind::Loop}}) {
        SCOPED_TRACE(name);
        Mesh m = load(name);
        perturb(m, 0.05);  // no symmetry to hide a wrong tangent plane
        const SchemeOptions options;
        const OsdVertexLimits limits = osd_vertex_limits(m.topology, m.positions, scheme, options);
        ASSERT_EQ(limits.position.rows(), m.topology.num_vertices());
        // Isolated as deep as Far goes: its end caps (Gregory and B-spline alike) reproduce
        // the limit position at their corners exactly but the tangent plane only approximately,
        // the error shrinking with the isolation level (cube_ngons, valence 3: 1 - cos(angle) =
        // 1e-6 at isolation 4, 4e-10 at 8, 7e-12 at 10).
        const OsdLimitEvaluator osd(m.topology, m.positions, scheme, options, 10);
        // Corner (0, 0) of every ptex face is a control vertex: corner k of the face (one
        // ptex face) or of sub-face k.
        Index p = 0;
        for (Index f = 0; f < m.topology.num_faces(); ++f) {
            const auto corners = m.topology.face_vertices(f);
            const bool one_ptex = scheme == SchemeKind::Loop || corners.size() == 4;
            for (std::size_t k = 0; k < (one_ptex ? 1 : corners.size()); ++k, ++p) {
                const Index v = corners[k];
                const OsdPointEval o = osd.evaluate({p, 0.0, 0.0});
                ASSERT_TRUE(o.has_patch);
                EXPECT_LE((o.value.row(0) - limits.position.row(v)).norm(), 1e-12 * m.diagonal)
                    << "vertex " << v << " ptex " << p;
                const Eigen::Vector3d n_patch = o.value.row(1).cross(o.value.row(2)).normalized();
                const Eigen::Vector3d n_limit = limits.tangent1.row(v).cross(limits.tangent2.row(v)).normalized();
                EXPECT_NEAR(n_patch.dot(n_limit), 1.0, 1e-10) << "vertex " << v << " ptex " << p;
            }
        }
        ASSERT_EQ(p, osd.num_ptex_faces());
    }
}

TEST(LimitReferences, BSplineEndCapsLeaveRegularPatchesAlone) {
    const Mesh m = load("cube");
    const auto points = random_points(6, false, 20, 3);
    const auto gregory = osd_evaluate(m.topology, m.positions, SchemeKind::CatmullClark, {}, points, 4);
    const auto bspline =
        osd_evaluate(m.topology, m.positions, SchemeKind::CatmullClark, {}, points, 4, OsdEndCaps::BSplineBasis);
    int regular = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        ASSERT_EQ(gregory[i].regular, bspline[i].regular);
        if (gregory[i].regular) {
            EXPECT_LE((gregory[i].value - bspline[i].value).norm(), 1e-13 * m.diagonal);
            ++regular;
        } else {
            EXPECT_TRUE(bspline[i].end_cap);
        }
    }
    EXPECT_GT(regular, 0);
}

TEST(LimitReferences, DeepSubdivisionRefusesIrregularPatches) {
    const Mesh m = load("cube");
    const DeepSubdivision deep(m.topology, m.positions, SchemeKind::CatmullClark, {}, 3);
    EXPECT_FALSE(deep.is_regular_at({0, 0.0, 0.0}));  // an extraordinary vertex of valence 3
    EXPECT_THROW((void)deep.evaluate({0, 0.01, 0.01}), std::runtime_error);
    EXPECT_TRUE(deep.is_regular_at({0, 0.5, 0.5}));
    EXPECT_THROW((void)deep.evaluate({6, 0.5, 0.5}), std::runtime_error);  // no such ptex face
    EXPECT_THROW((void)deep.evaluate({0, 1.5, 0.5}), std::runtime_error);  // outside the domain
    const Mesh tri = load("icosahedron");
    EXPECT_THROW((void)deep_subdivision_limit(tri.topology, tri.positions, SchemeKind::Loop, {}, {0, 0.0, 0.0}, 3),
                 std::runtime_error);
}

/// Deep subdivision converges to the exact values at a fixed point as levels grow: the same
/// point at levels 3 and 5 (both regular there) gives the same values.
TEST(LimitReferences, DeepSubdivisionIndependentOfDepth) {
    const Mesh m = load("cube_ngons");
    const SurfacePoint p{4, 0.625, 0.4375};
    const DeepSubdivision deep3(m.topology, m.positions, SchemeKind::CatmullClark, {}, 3);
    const DeepSubdivision deep5(m.topology, m.positions, SchemeKind::CatmullClark, {}, 5);
    ASSERT_TRUE(deep3.is_regular_at(p));
    EXPECT_LE((deep3.evaluate(p) - deep5.evaluate(p)).norm(), 1e-12 * m.diagonal);
}

}  // namespace
}  // namespace limsurf::test
