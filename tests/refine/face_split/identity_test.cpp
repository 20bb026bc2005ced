// Identity tests of the face-split schemes: affine invariance, counts, Euler
// characteristic, linear precision on planar grids, sharpness propagation,
// tuned weights, provenance.
#include <algorithm>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"
#include "refine/face_split/face_split_helpers.h"

namespace limsurf::test {
namespace {

const std::vector<SchemeOptions> all_options() {
    std::vector<SchemeOptions> out;
    for (const auto boundary :
         {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::None}) {
        for (const auto creasing : {CreasingMethod::Uniform, CreasingMethod::Chaikin}) {
            for (const auto triangles : {TriangleSubdivision::CatmullClark, TriangleSubdivision::Smooth}) {
                out.push_back({boundary, creasing, triangles});
            }
        }
    }
    return out;
}

bool is_smooth_scheme(SchemeKind kind) {
    return kind == SchemeKind::CatmullClark || kind == SchemeKind::Loop;
}

class EveryBundledMesh : public ::testing::TestWithParam<BundledMesh> {};

TEST_P(EveryBundledMesh, RowsSumToOneAndAreNonNegative) {
    const auto mesh = load_bundled(GetParam().name);
    for (const auto kind : face_split_schemes(mesh.topology)) {
        for (const auto& options : all_options()) {
            const Level level = refine(mesh.topology, kind, options);
            ASSERT_EQ(level.S0.rows(), level.topology.num_vertices());
            ASSERT_EQ(level.S0.cols(), mesh.topology.num_vertices());
            for (Index r = 0; r < level.S0.rows(); ++r) {
                double sum = 0.0;
                for (SparseMatrix::InnerIterator it(level.S0, r); it; ++it) {
                    sum += it.value();
                    // TRI_SUB_SMOOTH's 0.47 face weight makes the edge's vertex weights negative.
                    if (is_smooth_scheme(kind) && options.triangles == TriangleSubdivision::CatmullClark) {
                        EXPECT_GE(it.value(), 0.0) << to_string(kind) << " row " << r;
                    }
                }
                EXPECT_NEAR(sum, 1.0, 1e-14) << to_string(kind) << " row " << r;
            }
        }
    }
}

TEST_P(EveryBundledMesh, CountsEulerAndGenusOverThreeLevels) {
    const auto mesh = load_bundled(GetParam().name);
    for (const auto kind : face_split_schemes(mesh.topology)) {
        const Topology* parent = &mesh.topology;
        std::vector<Level> levels;
        levels.reserve(3);
        for (int l = 0; l < 3; ++l) {
            levels.push_back(refine(*parent, kind));
            const Topology& child = levels.back().topology;
            const Index V = parent->num_vertices(), E = parent->num_edges(), F = parent->num_faces();
            if (kind == SchemeKind::CatmullClark || kind == SchemeKind::Bilinear) {
                EXPECT_EQ(child.num_vertices(), V + E + F);
                EXPECT_EQ(child.num_edges(), 2 * E + parent->num_corners());
                EXPECT_EQ(child.num_faces(), parent->num_corners());
                EXPECT_TRUE(child.all_faces_have_degree(4));
            } else {
                EXPECT_EQ(child.num_vertices(), V + E);
                EXPECT_EQ(child.num_edges(), 2 * E + 3 * F);
                EXPECT_EQ(child.num_faces(), 4 * F);
            }
            EXPECT_EQ(child.euler_characteristic(), GetParam().euler_characteristic);
            EXPECT_EQ(child.genus(), GetParam().genus);
            EXPECT_EQ(child.num_boundary_loops(), GetParam().num_boundary_loops);
            EXPECT_EQ(child.num_components(), GetParam().num_components);
            const auto& p = levels.back().provenance;
            EXPECT_EQ(p.vertex_parent.size(), static_cast<std::size_t>(child.num_vertices()));
            EXPECT_EQ(p.vertex_parent_kind.size(), static_cast<std::size_t>(child.num_vertices()));
            EXPECT_EQ(p.face_parent.size(), static_cast<std::size_t>(child.num_faces()));
            EXPECT_EQ(p.face_parent_kind.size(), static_cast<std::size_t>(child.num_faces()));
            EXPECT_EQ(p.face_parent_corner.size(), static_cast<std::size_t>(child.num_faces()));
            parent = &child;
        }
        // Refining twice equals applying the product of the two operators.
        const Points p2 = levels[1].S0 * (levels[0].S0 * mesh.positions);
        const SparseMatrix product = levels[1].S0 * levels[0].S0;
        const Points q2 = product * mesh.positions;
        // Rounding is relative to the coordinates (the bundled shells are 10 to 300 units across).
        EXPECT_LT((p2 - q2).cwiseAbs().maxCoeff(), 1e-14 * std::max(1.0, mesh.positions.cwiseAbs().maxCoeff()));
    }
}

INSTANTIATE_TEST_SUITE_P(FaceSplit, EveryBundledMesh, ::testing::ValuesIn(bundled_meshes()),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(FaceSplitProvenance, QuadSplitChildrenFollowTheContract) {
    const auto mesh = load_bundled("cube_ngons");
    const Level level = refine_catmull_clark(mesh.topology);
    const Topology& t = mesh.topology;
    const Index V = t.num_vertices(), F = t.num_faces();
    Index child = 0;
    for (Index f = 0; f < F; ++f) {
        const auto verts = t.face_vertices(f);
        const auto edges = t.face_edges(f);
        const auto n = verts.size();
        for (std::size_t k = 0; k < n; ++k, ++child) {
            const auto c = level.topology.face_vertices(child);
            EXPECT_EQ(c[0], verts[k]);
            EXPECT_EQ(c[1], V + F + edges[k]);
            EXPECT_EQ(c[2], V + f);
            EXPECT_EQ(c[3], V + F + edges[(k + n - 1) % n]);
            EXPECT_EQ(level.provenance.face_parent[static_cast<std::size_t>(child)], f);
            EXPECT_EQ(level.provenance.face_parent_corner[static_cast<std::size_t>(child)], static_cast<Index>(k));
        }
    }
    EXPECT_EQ(level.provenance.vertex_parent_kind[static_cast<std::size_t>(V)], ParentKind::Face);
    EXPECT_EQ(level.provenance.vertex_parent_kind[static_cast<std::size_t>(V + F)], ParentKind::Edge);
}

TEST(FaceSplitProvenance, TriangleSplitMiddleFaceHasNoCorner) {
    const auto mesh = load_bundled("tetrahedron");
    const Level level = refine_loop(mesh.topology);
    EXPECT_EQ(level.provenance.face_parent_corner[3], invalid_index);
    EXPECT_EQ(level.provenance.face_parent_corner[5], 1);
    const auto edges = mesh.topology.face_edges(0);
    const auto middle = level.topology.face_vertices(3);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(middle[k], mesh.topology.num_vertices() + edges[k]);
    }
}

TEST(FaceSplitErrors, LoopAndLinearRefuseNonTriangles) {
    const auto mesh = load_bundled("cube_ngons");
    Index first = 0;
    while (mesh.topology.face_degree(first) == 3) {
        ++first;
    }
    const std::string expected = "face " + std::to_string(first) + " has " +
                                 std::to_string(mesh.topology.face_degree(first)) + " vertices: Loop needs triangles";
    try {
        (void)refine_loop(mesh.topology);
        FAIL() << "no exception";
    } catch (const UnsupportedError& e) {
        EXPECT_EQ(std::string(e.what()), expected);
    }
    EXPECT_THROW((void)refine_linear(mesh.topology), UnsupportedError);
}

// On a uniform planar grid the smooth schemes reproduce the linear refinement
// (linear precision), interior and boundary alike (the boundary crease rule
// reproduces evenly spaced collinear points); only convex corners that are not
// sharp corners move.
void expect_linear_precision(const std::string& name, SchemeKind smooth, SchemeKind linear,
                             BoundaryInterpolation boundary, bool corners_reproduced) {
    auto mesh = load_bundled(name);
    // A general affine image of the plane: positions stay planar, spacing uniform.
    Points p(mesh.positions.rows(), 3);
    for (Index i = 0; i < p.rows(); ++i) {
        const double x = mesh.positions(i, 0), y = mesh.positions(i, 1);
        p.row(i) << 0.5 + 2.0 * x - 0.25 * y, -1.0 + 0.5 * x + 1.5 * y, 3.0 + 0.75 * x - 0.5 * y;
    }
    const SchemeOptions options{boundary, CreasingMethod::Uniform, TriangleSubdivision::CatmullClark};
    const Level a = refine(mesh.topology, smooth, options);
    const Level b = refine(mesh.topology, linear, options);
    const Points pa = a.S0 * p;
    const Points pb = b.S0 * p;
    for (Index i = 0; i < pa.rows(); ++i) {
        const bool corner = i < mesh.positions.rows() && std::abs(std::abs(mesh.positions(i, 0)) - 1.0) < 1e-12 &&
                            std::abs(std::abs(mesh.positions(i, 1)) - 1.0) < 1e-12;
        if (corner && !corners_reproduced) {
            continue;
        }
        EXPECT_LT((pa.row(i) - pb.row(i)).norm(), 1e-14) << name << " child vertex " << i;
    }
    // Constants.
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(mesh.topology.num_vertices());
    EXPECT_LT(((a.S0 * ones).array() - 1.0).abs().maxCoeff(), 1e-14);
}

TEST(FaceSplitLinearPrecision, CatmullClarkOnQuadGrid) {
    expect_linear_precision("quad_grid", SchemeKind::CatmullClark, SchemeKind::Bilinear,
                            BoundaryInterpolation::EdgeAndCorner, true);
    expect_linear_precision("quad_grid", SchemeKind::CatmullClark, SchemeKind::Bilinear,
                            BoundaryInterpolation::EdgeOnly, false);
}

TEST(FaceSplitLinearPrecision, LoopOnTriGrid) {
    // tri_grid's two convex corners with two triangles are smooth boundary crease vertices: skip all corners.
    expect_linear_precision("tri_grid", SchemeKind::Loop, SchemeKind::Linear, BoundaryInterpolation::EdgeAndCorner,
                            false);
}

TEST(FaceSplitLinearPrecision, PlanarMeshesStayPlanar) {
    for (const char* name : {"disk_ev5_quads", "annulus", "pentagon", "disk_ev7_tris", "hexagon_fan"}) {
        const auto mesh = load_bundled(name);
        for (const auto kind : face_split_schemes(mesh.topology)) {
            const Level level = refine(mesh.topology, kind);
            const Points p = level.S0 * mesh.positions;
            EXPECT_LT(p.col(2).cwiseAbs().maxCoeff(), 1e-15) << name;
        }
    }
}

Index child_edge(const Level& level, Index a, Index b) {
    return level.topology.find_edge(a, b);
}

TEST(FaceSplitSharpness, UniformDecayOfACrease) {
    const auto mesh = load_bundled("quad_torus");
    SharpnessTags tags;
    const auto ends = mesh.topology.edge_vertices(0);
    tags.creases.push_back({ends[0], ends[1], 2.5, 0});
    tags.corners.push_back({ends[0], 1.25, 0});
    Topology t = with_tags(mesh.topology, tags);
    Index a = ends[0], b = ends[1], e = 0;
    for (const double expected : {1.5, 0.5, 0.0}) {
        const Level level = refine_catmull_clark(t);
        const Index mid = t.num_vertices() + t.num_faces() + e;
        EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, a, mid)), expected);
        EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, mid, b)), expected);
        EXPECT_EQ(level.topology.vertex_sharpness(a), expected == 1.5 ? 0.25 : 0.0);
        b = mid;
        e = child_edge(level, a, mid);
        t = level.topology;
    }
    EXPECT_FALSE(t.has_sharpness());
}

TEST(FaceSplitSharpness, ChaikinOnACreasePath) {
    // A path a - b - c along one ring of the torus with sharpness 2.5 then 1.25.
    const auto mesh = load_bundled("quad_torus");
    const Topology& t0 = mesh.topology;
    const Index b = 9;
    const auto edges = t0.vertex_edges(b);
    const Index e0 = edges[0], e1 = edges[2];  // opposite edges through b
    const Index a = t0.other_vertex(e0, b), c = t0.other_vertex(e1, b);
    SharpnessTags tags;
    tags.creases.push_back({a, b, 2.5, 0});
    tags.creases.push_back({b, c, 1.25, 0});
    const Topology t = with_tags(t0, tags);
    const SchemeOptions chaikin{BoundaryInterpolation::EdgeAndCorner, CreasingMethod::Chaikin,
                                TriangleSubdivision::CatmullClark};
    const Level level = refine_catmull_clark(t, chaikin);
    const Index base = t.num_vertices() + t.num_faces();
    // At b both edges are semi-sharp: 3/4 s + 1/4 (other) - 1.
    EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, b, base + e0)), 0.75 * 2.5 + 0.25 * 1.25 - 1.0);
    EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, b, base + e1)), 0.75 * 1.25 + 0.25 * 2.5 - 1.0);
    // At a and c the edge is the only semi-sharp one: plain decrement.
    EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, a, base + e0)), 1.5);
    EXPECT_EQ(level.topology.edge_sharpness(child_edge(level, c, base + e1)), 0.25);
    // New interior edges are smooth.
    for (const Index f : t.edge_faces(e0)) {
        const Index e = child_edge(level, t.num_vertices() + f, base + e0);
        ASSERT_NE(e, invalid_index);
        EXPECT_EQ(level.topology.edge_sharpness(e), 0.0);
    }
}

TEST(FaceSplitSharpness, HolesAreCarriedToAllChildren) {
    const auto mesh = load_bundled("cube_ngons");
    Index pentagon = 0;
    while (mesh.topology.face_degree(pentagon) != 5) {
        ++pentagon;
    }
    SharpnessTags tags;
    tags.holes.push_back({pentagon, 0});
    const Topology t = with_tags(mesh.topology, tags);
    const Level level = refine_catmull_clark(t);
    for (Index f = 0; f < level.topology.num_faces(); ++f) {
        EXPECT_EQ(level.topology.is_hole(f), level.provenance.face_parent[static_cast<std::size_t>(f)] == pentagon);
    }
}

TEST(FaceSplitTunedWeights, DefaultIsCatmullClarkBitForBit) {
    for (const char* name : {"disk_ev5_quads", "genus2", "cube_ngons", "quad_valence_5"}) {
        const auto mesh = load_bundled(name);
        const Level plain = refine_catmull_clark(mesh.topology);
        const Level preset = refine_catmull_clark(mesh.topology, {}, TunedWeights::preset("catmull-clark"));
        ASSERT_EQ(plain.S0.nonZeros(), preset.S0.nonZeros());
        for (Index i = 0; i < plain.S0.nonZeros(); ++i) {
            EXPECT_EQ(plain.S0.valuePtr()[i], preset.S0.valuePtr()[i]);
            EXPECT_EQ(plain.S0.innerIndexPtr()[i], preset.S0.innerIndexPtr()[i]);
        }
    }
}

// The paper's convention (Fig. 1): a valence-5 vertex's α changes its own vertex row, its β the
// rows of its edges, its γ the rows of its faces (and, through the new face points, the rows of
// its neighbours' vertex rules and of the edges of its faces). Every other row is Catmull–Clark's.
TEST(FaceSplitTunedWeights, CupChangesOnlyTheRowsAroundValenceFiveInteriorVertices) {
    for (const char* name : {"disk_ev5_quads", "quad_valence_5", "genus2"}) {
        const auto mesh = load_bundled(name);
        const Topology& t = mesh.topology;
        const Level plain = refine_catmull_clark(t);
        const Level cup = refine_catmull_clark(t, {}, TunedWeights::preset("cup"));
        const auto tuned = [&](Index v) { return !t.is_boundary_vertex(v) && t.valence(v) == 5; };
        // A face point moves when its corners' γ differ (all tuned alike is the centroid again).
        std::vector<bool> tuned_face(static_cast<std::size_t>(t.num_faces()), false);
        for (Index f = 0; f < t.num_faces(); ++f) {
            const auto corners = t.face_vertices(f);
            const auto count = std::count_if(corners.begin(), corners.end(), tuned);
            tuned_face[static_cast<std::size_t>(f)] = count > 0 && count < static_cast<std::ptrdiff_t>(corners.size());
        }
        const auto touches_tuned_face = [&](std::span<const Index> faces) {
            return std::any_of(faces.begin(), faces.end(),
                               [&](Index f) { return tuned_face[static_cast<std::size_t>(f)]; });
        };
        int changed = 0;
        for (Index r = 0; r < plain.S0.rows(); ++r) {
            bool expected = false;
            if (r < t.num_vertices()) {
                expected = tuned(r) || (!t.is_boundary_vertex(r) && touches_tuned_face(t.vertex_faces(r)));
            } else if (r < t.num_vertices() + t.num_faces()) {
                expected = tuned_face[static_cast<std::size_t>(r - t.num_vertices())];
            } else {
                const Index e = r - t.num_vertices() - t.num_faces();
                const auto ends = t.edge_vertices(e);
                expected =
                    !t.is_boundary_edge(e) && (tuned(ends[0]) || tuned(ends[1]) || touches_tuned_face(t.edge_faces(e)));
            }
            const double diff = (Eigen::RowVectorXd(plain.S0.row(r)) - Eigen::RowVectorXd(cup.S0.row(r))).norm();
            EXPECT_EQ(diff != 0.0, expected) << name << " row " << r;
            changed += expected ? 1 : 0;
            for (SparseMatrix::InnerIterator it(cup.S0, r); it; ++it) {
                EXPECT_GE(it.value(), 0.0);
            }
            EXPECT_NEAR(Eigen::RowVectorXd(cup.S0.row(r)).sum(), 1.0, 1e-14) << name << " row " << r;
        }
        EXPECT_GT(changed, 0) << name;
    }
}

// The three rules with the paper's reading of α, β, γ, written out for one valence-5 vertex.
TEST(FaceSplitTunedWeights, TheRulesAreThePapersFigureOne) {
    const auto mesh = load_bundled("quad_valence_5");
    const Topology& t = mesh.topology;
    const auto tuned = [&](Index u) { return !t.is_boundary_vertex(u) && t.valence(u) == 5; };
    Index v = invalid_index;
    for (Index u = 0; u < t.num_vertices() && v == invalid_index; ++u) {
        v = tuned(u) ? u : invalid_index;
    }
    ASSERT_NE(v, invalid_index);
    const double alpha = 13.9851, beta = 0.824885, gamma = 0.824885;  // Table 1, saddle
    const Level level = refine_catmull_clark(t, {}, TunedWeights::preset("saddle"));
    const Eigen::MatrixXd S(level.S0);
    const auto face_point = [&](Index f) {
        Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(t.num_vertices());
        double sum = 0.0;
        for (const Index c : t.face_vertices(f)) {
            const double w = tuned(c) ? gamma : 1.0;
            row[c] += w;
            sum += w;
        }
        return Eigen::RowVectorXd(row / sum);
    };
    for (const Index f : t.vertex_faces(v)) {
        EXPECT_LT((S.row(t.num_vertices() + f) - face_point(f)).norm(), 1e-15);
    }
    Eigen::RowVectorXd vertex_row = Eigen::RowVectorXd::Zero(t.num_vertices());
    vertex_row[v] = alpha;
    for (const Index e : t.vertex_edges(v)) {
        const Index w = t.other_vertex(e, v);
        vertex_row[w] += 1.0;
        const auto faces = t.edge_faces(e);
        Eigen::RowVectorXd edge_row = face_point(faces[0]) + face_point(faces[1]);
        const double beta_w = tuned(w) ? beta : 1.0;
        edge_row[v] += beta;
        edge_row[w] += beta_w;
        EXPECT_LT((S.row(t.num_vertices() + t.num_faces() + e) - edge_row / (beta + beta_w + 2.0)).norm(), 1e-15);
    }
    for (const Index f : t.vertex_faces(v)) {
        vertex_row += face_point(f);
    }
    EXPECT_LT((S.row(v) - vertex_row / (alpha + 10.0)).norm(), 1e-15);
}

}  // namespace
}  // namespace limsurf::test
