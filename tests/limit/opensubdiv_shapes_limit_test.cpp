// Peer test of the limit basis on OpenSubdiv's regression shapes (tests/data/opensubdiv_shapes; the
// 98 Catmull–Clark and Loop shapes limsurf accepts and can evaluate, see
// tests/refine/face_split/opensubdiv_shapes_test.cpp; the two valence-360 poles are beyond the limit
// basis's documented size and refused with the reason):
//   - which ptex faces have a limit surface (holes, BoundaryInterpolation::None) is Far's answer;
//   - where Far's patch is a regular B-spline / box-spline patch, positions and first derivatives agree
//     to 1e-12 of the mesh size, second derivatives to 1e-11, at 3 points per face — with Far's
//     isolation deep enough (isolation_level) for its "regular" patches to be exact;
//   - limit positions of the control vertices agree with Far's PrimvarRefiner::Limit to 1e-12 wherever
//     Far's limit mask is exact (vertex_limits_are_exact: not at darts, interior valence-2 vertices or
//     live semi-sharp tags, where Far's masks are approximate and limsurf's value is the limit).
// Options: the file's tags; without an `interpolateboundary` tag, limsurf's default (edge-and-corner).
// Sharpness goes to both sides rounded to float, as Far stores it. Positions are perturbed so that
// symmetric shapes cannot hide an error.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/refine.h"
#include "osd_limit.h"
#include "support/opensubdiv_shapes.h"

namespace limsurf::test {
namespace {

/// Shapes with a vertex of valence 360: beyond the limit basis's documented max_limit_size (128,
/// docs/io.md "Limits"); Far evaluates them (with end caps), limsurf refuses with the reason.
bool beyond_limit_size(const OpenSubdivShape& s) {
    return s.name == "catmark_pole360" || s.name == "loop_pole360";
}

TEST(OpenSubdivShapes, PolesOfValence360AreRefusedByTheLimitBasisWithTheReason) {
    int refused = 0;
    for (const auto& s : opensubdiv_shapes()) {
        if (!beyond_limit_size(s)) {
            continue;
        }
        const BuildResult built = read_mesh(s.path);
        try {
            const LimitBasis basis(built.mesh.topology(), s.scheme);
            ADD_FAILURE() << s.name << ": the limit basis was built";
        } catch (const UnsupportedError& e) {
            EXPECT_NE(std::string(e.what()).find("has 360 edges"), std::string::npos) << e.what();
            ++refused;
        }
    }
    EXPECT_EQ(refused, 2);
}

std::vector<OpenSubdivShape> evaluated_shapes() {
    std::vector<OpenSubdivShape> out;
    for (auto& s : opensubdiv_shapes()) {
        if (s.refusal.empty() && s.scheme != SchemeKind::Bilinear && !beyond_limit_size(s)) {
            out.push_back(std::move(s));
        }
    }
    return out;
}

struct Shape {
    Topology topology;
    Points X;
    SchemeOptions options;
    double scale = 1.0;
};

Shape load(const OpenSubdivShape& s) {
    const BuildResult built = read_mesh(s.path);
    const Topology& t = built.mesh.topology();
    Shape m{with_float_sharpness(t), built.mesh.positions(), {}, 1};
    const SchemeHints& hints = built.mesh.hints();
    m.options.boundary = hints.boundary.value_or(m.options.boundary);
    m.options.creasing = hints.creasing.value_or(m.options.creasing);
    m.options.triangles = hints.triangles.value_or(m.options.triangles);
    m.scale = (m.X.colwise().maxCoeff() - m.X.colwise().minCoeff()).norm();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-0.005, 0.005);
    for (Index i = 0; i < m.X.rows(); ++i) {
        for (int k = 0; k < 3; ++k) {
            m.X(i, k) += jitter(rng) * m.scale;
        }
    }
    return m;
}

/// The largest semi-sharp value of @p t (0 when none).
double max_semi_sharpness(const Topology& t) {
    double s = 0.0;
    for (Index e = 0; e < t.num_edges(); ++e) {
        s = t.edge_sharpness(e) < infinite_sharpness ? std::max(s, t.edge_sharpness(e)) : s;
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        s = t.vertex_sharpness(v) < infinite_sharpness ? std::max(s, t.vertex_sharpness(v)) : s;
    }
    return s;
}

/// Isolation 6, or one past the largest semi-sharp value (at most Far's 10). Far flags patches at its
/// deepest isolation level "regular" even next to an irregular feature (at 4, a Loop dart's
/// neighbours on loop_cubes_infsharp are 4e-5 off; at 6 they agree with limsurf to 1e-12).
int isolation_level(const Topology& t) {
    return std::clamp(static_cast<int>(std::ceil(max_semi_sharpness(t))) + 1, 6, 10);
}

class ShapeLimit : public ::testing::TestWithParam<OpenSubdivShape> {};

TEST_P(ShapeLimit, MatchesFarOnRegularPatches) {
    const Shape m = load(GetParam());
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    // Far's adaptive isolation must outlast every semi-sharp feature: a feature still semi-sharp at the
    // isolation level is approximated (the patch is flagged regular all the same).
    const OsdLimitEvaluator osd(m.topology, m.X, GetParam().scheme, m.options, isolation_level(m.topology));
    ASSERT_EQ(osd.num_ptex_faces(), basis.num_ptex_faces());
    const double uv[3][2] = {{0.3, 0.2}, {0.1, 0.7}, {0.55, 0.4}};  // inside the triangle too
    int compared = 0;
    for (Index p = 0; p < basis.num_ptex_faces(); ++p) {
        for (const auto& [u, v] : uv) {
            const SurfacePoint point{p, u, v};
            const OsdPointEval peer = osd.evaluate(point);
            ASSERT_EQ(basis.has_limit_surface(p), peer.has_patch) << "ptex face " << p;
            if (!peer.has_patch || !peer.regular) {
                continue;
            }
            const Eigen::Matrix<double, 6, 3> ours = basis.evaluate(m.X, point);
            for (int r = 0; r < 6; ++r) {
                const double tol =
                    (r < 3 ? 1e-12 : 1e-11) * m.scale * std::max(1.0, peer.value.row(r).norm() / m.scale);
                ASSERT_LT((ours.row(r) - peer.value.row(r)).norm(), tol)
                    << "row " << r << " at ptex " << p << " (" << u << ", " << v << ")";
            }
            ++compared;
        }
    }
    EXPECT_GT(compared, 0);
}

/// Where Far's Limit masks are exact at vertex v of the last refined level: not where a tag is still
/// semi-sharp (Far treats it as infinitely sharp), not at a dart (one infinitely sharp edge: Far
/// applies the smooth mask, whose eigenvector is not the dart's) and not at an interior vertex of
/// valence 2. At those, refining further converges to limsurf's value, not to Far's (checked by hand
/// on catmark_inf_crease0, catmark_cubes_infsharp, catmark_val2_interior, catmark_gregory_test8:
/// the distance to limsurf's limit falls by the subdominant eigenvalue per level).
bool vertex_limits_are_exact(const Topology& t, Index v) {
    const auto semi = [](double s) { return s > 0.0 && s < infinite_sharpness; };
    bool exact = !semi(t.vertex_sharpness(v));
    int infinitely_sharp = 0;
    for (const Index e : t.vertex_edges(v)) {
        exact = exact && !semi(t.edge_sharpness(e));
        infinitely_sharp += t.edge_sharpness(e) >= infinite_sharpness ? 1 : 0;
    }
    const bool interior = !t.is_boundary_vertex(v);
    const bool dart = interior && infinitely_sharp == 1 && t.vertex_sharpness(v) < infinite_sharpness;
    return exact && !dart && !(interior && t.valence(v) == 2);
}

TEST_P(ShapeLimit, MatchesFarVertexLimits) {
    const Shape m = load(GetParam());
    const LimitBasis basis(m.topology, GetParam().scheme, m.options);
    // Refine with limsurf's engine (equal to Far's: the refine peer test) until the semi-sharp tags have
    // decayed (while the mesh stays small); control vertex v is child vertex v.
    Topology refined = m.topology;
    Points refined_X = m.X;
    while (max_semi_sharpness(refined) > 0.0 && refined.num_faces() < 50000) {
        Level next = refine(refined, GetParam().scheme, m.options);
        refined_X = next.S0 * refined_X;
        refined = std::move(next.topology);
    }
    const OsdVertexLimits osd = osd_vertex_limits(refined, refined_X, GetParam().scheme, m.options);
    const Points ours = basis.vertex_limit_matrix() * m.X;
    int compared = 0;
    for (Index v = 0; v < m.topology.num_vertices(); ++v) {
        bool has_limit = false;
        for (const Index f : m.topology.vertex_faces(v)) {
            has_limit = has_limit || basis.has_limit_surface(basis.first_ptex_face(f));
        }
        if (!has_limit || !vertex_limits_are_exact(refined, v)) {
            continue;
        }
        EXPECT_LT((ours.row(v) - osd.position.row(v)).norm(), 1e-12 * m.scale) << "vertex " << v;
        ++compared;
    }
    // Every vertex of catmark_val2_back2back has valence 2: nothing where Far's masks are exact.
    EXPECT_EQ(compared > 0, GetParam().name != "catmark_val2_back2back");
}

std::string shape_name(const ::testing::TestParamInfo<OpenSubdivShape>& param) {
    return param.param.name;
}

INSTANTIATE_TEST_SUITE_P(OpenSubdivShapes, ShapeLimit, ::testing::ValuesIn(evaluated_shapes()), shape_name);

}  // namespace
}  // namespace limsurf::test
