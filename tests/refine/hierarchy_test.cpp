// Hierarchy: size prediction against the real counts, accumulated operators
// against successive products, refusal before allocating.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/core/memory.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/refine/hierarchy.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

RefineOptions options_for(SchemeKind scheme, int levels) {
    RefineOptions options;
    options.scheme = scheme;
    options.levels = levels;
    return options;
}

void expect_predicted_sizes(const test::BundledMesh& mesh, SchemeKind scheme, int levels) {
    SCOPED_TRACE(std::string(mesh.name) + " " + to_string(scheme));
    const BuildResult built = read_mesh(mesh.path);
    const Hierarchy hierarchy(built.mesh.topology(), options_for(scheme, levels));
    const auto predicted = predict_sizes(built.mesh.topology(), scheme, levels);
    ASSERT_EQ(predicted.size(), static_cast<std::size_t>(levels) + 1);
    for (int l = 0; l <= levels; ++l) {
        const Topology& t = hierarchy.topology(l);
        const LevelSize& p = predicted[static_cast<std::size_t>(l)];
        EXPECT_EQ(t.num_vertices(), p.vertices) << "level " << l;
        EXPECT_EQ(t.num_edges(), p.edges) << "level " << l;
        EXPECT_EQ(t.num_faces(), p.faces) << "level " << l;
        EXPECT_EQ(t.num_corners(), p.corners) << "level " << l;
        EXPECT_EQ(t.euler_characteristic(), built.mesh.topology().euler_characteristic()) << "level " << l;
        EXPECT_EQ(t.genus(), built.mesh.topology().genus()) << "level " << l;
    }
}

TEST(Hierarchy, PredictedSizesAreExactForTheFaceSplitSchemes) {
    for (const auto& mesh : test::bundled_meshes()) {
        expect_predicted_sizes(mesh, SchemeKind::CatmullClark, 2);
        expect_predicted_sizes(mesh, SchemeKind::Bilinear, 2);
    }
    for (const auto& mesh : test::triangle_meshes()) {
        expect_predicted_sizes(mesh, SchemeKind::Loop, 2);
        expect_predicted_sizes(mesh, SchemeKind::Linear, 2);
    }
}

TEST(Hierarchy, PredictedSizesAreExactForDooSabinOnClosedMeshes) {
    for (const auto& mesh : test::closed_meshes()) {
        if (read_mesh(mesh.path).mesh.topology().has_sharpness()) {
            continue;  // Doo–Sabin refuses creases (no crease rules yet)
        }
        expect_predicted_sizes(mesh, SchemeKind::DooSabin, 2);
    }
}

TEST(Hierarchy, PredictedSizesBoundDooSabinWithBoundary) {
    for (const auto& mesh : test::meshes_with_boundary()) {
        SCOPED_TRACE(mesh.name);
        const BuildResult built = read_mesh(mesh.path);
        if (built.mesh.topology().has_sharpness()) {
            continue;  // Doo-Sabin has no crease rule (square_inclusion's interface)
        }
        const Hierarchy hierarchy(built.mesh.topology(), options_for(SchemeKind::DooSabin, 2));
        const auto predicted = predict_sizes(built.mesh.topology(), SchemeKind::DooSabin, 2);
        for (int l = 0; l <= 2; ++l) {
            const Topology& t = hierarchy.topology(l);
            const LevelSize& p = predicted[static_cast<std::size_t>(l)];
            EXPECT_LE(t.num_vertices(), p.vertices);
            EXPECT_LE(t.num_edges(), p.edges);
            EXPECT_LE(t.num_faces(), p.faces);
            EXPECT_LE(t.num_corners(), p.corners);
        }
    }
}

TEST(Hierarchy, AccumulatedOperatorIsTheProductOfTheSteps) {
    const BuildResult built = read_mesh(test::find_bundled("cube_ngons").path);
    const Hierarchy hierarchy(built.mesh.topology(), options_for(SchemeKind::CatmullClark, 3));
    EXPECT_EQ(hierarchy.num_steps(), 3);
    const SparseMatrix& a0 = hierarchy.accumulated(0);
    EXPECT_EQ(a0.rows(), built.mesh.num_vertices());
    EXPECT_DOUBLE_EQ(Eigen::MatrixXd(a0).trace(), built.mesh.num_vertices());
    const SparseMatrix expected = hierarchy.step(3).S0 * (hierarchy.step(2).S0 * hierarchy.step(1).S0);
    const SparseMatrix& a3 = hierarchy.accumulated(3);
    ASSERT_EQ(a3.rows(), hierarchy.topology(3).num_vertices());
    ASSERT_EQ(a3.cols(), built.mesh.num_vertices());
    EXPECT_LT((Eigen::MatrixXd(a3) - Eigen::MatrixXd(expected)).cwiseAbs().maxCoeff(), 1e-15);
    const Points by_steps = hierarchy.positions(3, built.mesh.positions());
    const Points by_operator = a3 * built.mesh.positions();
    EXPECT_LT((by_steps - by_operator).cwiseAbs().maxCoeff(), 1e-14);
    const Eigen::VectorXd row_sums = Eigen::MatrixXd(a3).rowwise().sum();
    EXPECT_LT((row_sums.array() - 1.0).abs().maxCoeff(), 1e-14);
}

TEST(Hierarchy, AccumulatedOperatorsAreEigensProductsBitForBitOnAnyNumberOfThreads) {
    // A_l = S_l A_(l-1), A_0 = I, for the vertex, edge and face operators; the library forms each
    // product row by row on its own threads, which must give Eigen's product exactly.
    const BuildResult built = read_mesh(test::find_bundled("genus2").path);
    for (const int threads : {1, 2}) {
        RefineOptions options = options_for(SchemeKind::CatmullClark, 3);
        options.forms = true;
        options.num_threads = threads;
        const Hierarchy hierarchy(built.mesh.topology(), options);
        for (int k = 0; k <= 2; ++k) {
            const Topology& base = hierarchy.topology(0);
            const Index n = k == 0 ? base.num_vertices() : k == 1 ? base.num_edges() : base.num_faces();
            SparseMatrix expected(n, n);
            expected.setIdentity();
            for (int l = 1; l <= 3; ++l) {
                const Level& s = hierarchy.step(l);
                expected = SparseMatrix(SparseMatrix(k == 0 ? s.S0 : k == 1 ? s.S1 : s.S2) * expected);
            }
            const SparseMatrix& a = hierarchy.accumulated_form(k, 3);
            ASSERT_GE(a.rows(), 2048) << "too few rows to split over threads";
            ASSERT_EQ(a.nonZeros(), expected.nonZeros()) << k;
            EXPECT_TRUE(std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.rows() + 1, expected.outerIndexPtr()))
                << k;
            EXPECT_TRUE(std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), expected.innerIndexPtr()))
                << k;
            EXPECT_TRUE(std::equal(a.valuePtr(), a.valuePtr() + a.nonZeros(), expected.valuePtr())) << k;
        }
    }
}

TEST(Hierarchy, EveryRefinedLevelPassesFullValidation) {
    // Refinement builds child topologies without validating them in release
    // builds (they are valid by construction); check that claim explicitly.
    struct Case {
        const char* mesh;
        SchemeKind scheme;
    };
    for (const Case& c : {Case{"cube_ngons", SchemeKind::CatmullClark},
                          Case{"disk_ev5_quads", SchemeKind::CatmullClark}, Case{"annulus", SchemeKind::Bilinear},
                          Case{"tri_grid", SchemeKind::Loop}, Case{"disk_ev7_tris", SchemeKind::Linear},
                          Case{"genus2", SchemeKind::DooSabin}, Case{"cylinder_open", SchemeKind::DooSabin}}) {
        SCOPED_TRACE(std::string(c.mesh) + " " + to_string(c.scheme));
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        const Hierarchy hierarchy(built.mesh.topology(), options_for(c.scheme, 2));
        for (int l = 1; l <= 2; ++l) {
            const ControlMesh level(hierarchy.topology(l), hierarchy.positions(l, built.mesh.positions()));
            const ValidationReport report = validate(to_polygon_soup(level));
            EXPECT_FALSE(report.has_errors()) << "level " << l << ": " << report.summary();
        }
    }
}

TEST(Hierarchy, LevelZeroIsTheBase) {
    const BuildResult built = read_mesh(test::find_bundled("cube").path);
    const Hierarchy hierarchy(built.mesh.topology(), options_for(SchemeKind::CatmullClark, 0));
    EXPECT_EQ(hierarchy.num_steps(), 0);
    EXPECT_EQ(hierarchy.topology(0).num_faces(), 6);
    EXPECT_EQ(hierarchy.positions(0, built.mesh.positions()), built.mesh.positions());
    EXPECT_THROW((void)hierarchy.step(1), InputError);
    EXPECT_THROW((void)hierarchy.topology(1), InputError);
}

TEST(Hierarchy, RefusesBeforeAllocatingTooMuch) {
    const BuildResult built = read_mesh(test::find_bundled("quad_torus").path);
    RefineOptions options = options_for(SchemeKind::CatmullClark, 12);
    try {
        const Hierarchy hierarchy(built.mesh.topology(), options);
        FAIL() << "expected a refusal";
    } catch (const InputError& error) {
        // 48 quads × 4^12 = 805 306 368 faces
        EXPECT_NE(std::string(error.what()).find("would make 805306368 faces at level 12"), std::string::npos)
            << error.what();
    }
    options.levels = 17;
    EXPECT_THROW(Hierarchy(built.mesh.topology(), options), InputError);
    options.levels = 2;
    options.max_faces = 100;  // 48 × 16 = 768 > 100
    EXPECT_THROW(Hierarchy(built.mesh.topology(), options), InputError);
}

TEST(Hierarchy, TunedWeightsMustNameControlVertices) {
    const BuildResult built = read_mesh(test::find_bundled("quad_valence_5").path);
    RefineOptions options = options_for(SchemeKind::CatmullClark, 2);
    options.weights.set_vertex(built.mesh.num_vertices(), {13.4575, 0.999938, 0.999938});
    try {
        const Hierarchy hierarchy(built.mesh.topology(), options);
        FAIL() << "expected a refusal";
    } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()), "tuned weights name vertex 17 but the control mesh has 17 vertices");
    }
    options.weights = TunedWeights();
    options.weights.set_vertex(0, {13.4575, 0.999938, 0.999938});  // a pole of valence 5
    EXPECT_NO_THROW(Hierarchy(built.mesh.topology(), options));
}

TEST(Hierarchy, ApplyChecksTheRowCount) {
    const BuildResult built = read_mesh(test::find_bundled("cube").path);
    const Hierarchy hierarchy(built.mesh.topology(), options_for(SchemeKind::Bilinear, 1));
    EXPECT_THROW((void)hierarchy.apply(1, Eigen::MatrixXd::Zero(7, 1)), InputError);
    const Eigen::MatrixXd ones = hierarchy.apply(1, Eigen::MatrixXd::Ones(8, 2));
    EXPECT_EQ(ones.rows(), 26);  // 8 + 12 + 6
    EXPECT_LT((ones.array() - 1.0).abs().maxCoeff(), 1e-15);
}

TEST(Hierarchy, TheFirstStepsNonZerosAreCountedRuleByRule) {
    // Exact on closed meshes without creases (every vertex and edge point holds its faces' points);
    // an upper bound where boundaries and creases use shorter rules. Later levels: the formula from
    // the counts bounds the real S0 too.
    for (const auto& mesh : test::bundled_meshes()) {
        SCOPED_TRACE(mesh.name);
        const BuildResult built = read_mesh(mesh.path);
        const Topology& t = built.mesh.topology();
        std::vector<SchemeKind> schemes{SchemeKind::CatmullClark, SchemeKind::Bilinear};
        if (t.all_faces_have_degree(3)) {
            schemes.push_back(SchemeKind::Loop);
            schemes.push_back(SchemeKind::Linear);
        }
        if (!t.has_sharpness()) {
            schemes.push_back(SchemeKind::DooSabin);
        }
        for (const SchemeKind scheme : schemes) {
            SCOPED_TRACE(to_string(scheme));
            const Hierarchy h(t, options_for(scheme, 2));
            const auto predicted = predict_sizes(t, scheme, 2);
            const auto nonzeros = [&](int l) { return static_cast<std::int64_t>(h.step(l).S0.nonZeros()); };
            EXPECT_GE(predicted[0].step_nonzeros, nonzeros(1));
            EXPECT_GE(predicted[1].step_nonzeros, nonzeros(2));
            const bool smooth_closed = t.is_closed() && !t.has_sharpness();
            if (smooth_closed && scheme != SchemeKind::Bilinear && scheme != SchemeKind::Linear) {
                EXPECT_EQ(predicted[0].step_nonzeros, nonzeros(1));
            }
        }
    }
}

TEST(Hierarchy, RefusesWorkBeyondItsMemoryBudgetBeforeAllocating) {
    const BuildResult built = read_mesh(test::find_bundled("cube").path);
    RefineOptions options = options_for(SchemeKind::CatmullClark, 6);
    const std::int64_t peak = estimated_peak_bytes(predict_sizes(built.mesh.topology(), options.scheme, 6));
    options.max_memory = peak - 1;
    try {
        const Hierarchy h(built.mesh.topology(), options);
        FAIL() << "expected a refusal";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("needs about " + format_bytes(peak) + " at its peak"),
                  std::string::npos)
            << error.what();
        EXPECT_NE(std::string(error.what()).find("(max_memory)"), std::string::npos) << error.what();
        EXPECT_FALSE(error.element().has_value());
    }
    options.max_memory = peak;
    EXPECT_NO_THROW(Hierarchy(built.mesh.topology(), options));
    // reserved_bytes counts into the peak.
    options.reserved_bytes = 1;
    EXPECT_THROW(Hierarchy(built.mesh.topology(), options), InputError);
}

TEST(Hierarchy, DenseMasksOverAHugeFaceAreRefusedNamingTheFace) {
    // Two 5000-gons glued at their rims: Catmull–Clark's vertex and edge points each hold a
    // whole face point (2 · 5000² weights); the refusal names the face (its ErrorElement).
    constexpr Index n = 5000;
    std::vector<Index> top(n);
    std::vector<Index> bottom(n);
    for (Index i = 0; i < n; ++i) {
        top[static_cast<std::size_t>(i)] = i;
        bottom[static_cast<std::size_t>(i)] = n - 1 - i;
    }
    const Topology pillow = Topology::from_polygons(n, {top, bottom});
    RefineOptions options = options_for(SchemeKind::CatmullClark, 1);
    options.max_memory = std::int64_t{64} << 20;
    try {
        const Hierarchy h(pillow, options);
        FAIL() << "expected a refusal";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("the masks over face 0's 5000 corners"), std::string::npos)
            << error.what();
        ASSERT_TRUE(error.element().has_value());
        EXPECT_EQ(error.element()->kind, ErrorElement::Kind::Face);
        EXPECT_EQ(error.element()->index, 0);
    }
    // Bilinear's face point is the only dense row: linear, and within the budget.
    options.scheme = SchemeKind::Bilinear;
    EXPECT_NO_THROW(Hierarchy(pillow, options));
}

}  // namespace
}  // namespace limsurf

namespace limsurf {
namespace {

/// refine_finest keeps only the finest level: the same topology and positions, bit for bit, as the
/// Hierarchy's level L, and the same counts per level. Its steps never store S0: they carry the
/// points through each row as it is built, and must sum them as Eigen's S0 product does.
/// refine_finest_faces writes what a writer gets from refine_finest's result (to_polygon_soup of
/// its ControlMesh): the same positions, face list and tags in the same order, field for field.
void expect_faces_equal_finest(const FinestFaces& faces, const FinestLevel& finest) {
    const PolygonSoup expected = to_polygon_soup(ControlMesh(finest.topology, finest.positions));
    EXPECT_EQ(faces.counts, finest.counts);
    ASSERT_EQ(faces.mesh.positions.rows(), expected.positions.rows());
    EXPECT_TRUE((faces.mesh.positions.array() == expected.positions.array()).all()) << "positions differ";
    EXPECT_EQ(faces.mesh.face_offsets, expected.face_offsets);
    EXPECT_EQ(faces.mesh.face_vertices, expected.face_vertices);
    const SharpnessTags& got = faces.mesh.sharpness;
    const SharpnessTags& want = expected.sharpness;
    ASSERT_EQ(got.creases.size(), want.creases.size());
    for (std::size_t i = 0; i < want.creases.size(); ++i) {
        EXPECT_EQ(got.creases[i].v0, want.creases[i].v0) << "crease " << i;
        EXPECT_EQ(got.creases[i].v1, want.creases[i].v1) << "crease " << i;
        EXPECT_EQ(got.creases[i].sharpness, want.creases[i].sharpness) << "crease " << i;
    }
    ASSERT_EQ(got.corners.size(), want.corners.size());
    for (std::size_t i = 0; i < want.corners.size(); ++i) {
        EXPECT_EQ(got.corners[i].vertex, want.corners[i].vertex) << "corner " << i;
        EXPECT_EQ(got.corners[i].sharpness, want.corners[i].sharpness) << "corner " << i;
    }
    ASSERT_EQ(got.holes.size(), want.holes.size());
    for (std::size_t i = 0; i < want.holes.size(); ++i) {
        EXPECT_EQ(got.holes[i].face, want.holes[i].face) << "hole " << i;
    }
}

void expect_built_with_points_equals_plain(const Hierarchy& plain, const Topology& base, const Points& control_points,
                                           const RefineOptions& options);

void expect_finest_equals_hierarchy(const Topology& base, const Points& control_points, const RefineOptions& options,
                                    const std::string& name) {
    SCOPED_TRACE(name + " " + to_string(options.scheme) + " L = " + std::to_string(options.levels));
    const Hierarchy hierarchy(base, options);
    expect_built_with_points_equals_plain(hierarchy, base, control_points, options);
    const FinestLevel finest = refine_finest(base, control_points, options);
    const Topology& expected = hierarchy.topology(options.levels);
    ASSERT_EQ(finest.topology.num_faces(), expected.num_faces());
    EXPECT_TRUE(std::equal(expected.face_offsets().begin(), expected.face_offsets().end(),
                           finest.topology.face_offsets().begin()));
    EXPECT_TRUE(std::equal(expected.all_face_vertices().begin(), expected.all_face_vertices().end(),
                           finest.topology.all_face_vertices().begin()));
    EXPECT_EQ(finest.topology.sharpness_tags().creases.size(), expected.sharpness_tags().creases.size());
    const Points positions = hierarchy.positions(options.levels, control_points);
    ASSERT_EQ(finest.positions.rows(), positions.rows());
    EXPECT_TRUE((finest.positions.array() == positions.array()).all()) << "positions differ";
    ASSERT_EQ(finest.counts.size(), static_cast<std::size_t>(options.levels) + 1);
    for (int l = 0; l <= options.levels; ++l) {
        const Topology& t = hierarchy.topology(l);
        const std::array<Index, 3> counts{t.num_vertices(), t.num_edges(), t.num_faces()};
        EXPECT_EQ(finest.counts[static_cast<std::size_t>(l)], counts) << "level " << l;
    }
    expect_faces_equal_finest(refine_finest_faces(base, control_points, options), finest);
}

void expect_finest_equals_hierarchy(const test::BundledMesh& mesh, const RefineOptions& options) {
    const BuildResult built = read_mesh(mesh.path);
    expect_finest_equals_hierarchy(built.mesh.topology(), built.mesh.positions(), options, mesh.name);
}

TEST(RefineFinest, EqualsTheHierarchysFinestLevelBitForBit) {
    for (const auto& mesh : test::bundled_meshes()) {
        for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Bilinear}) {
            expect_finest_equals_hierarchy(mesh, options_for(scheme, 2));
        }
        if (const BuildResult built = read_mesh(mesh.path); !built.mesh.topology().has_sharpness()) {
            // Doo–Sabin has no crease rules. Without the boundary rule a boundary vertex has no face
            // of its own: the faces-only step counts the child's edges without a Topology, both ways.
            expect_finest_equals_hierarchy(mesh, options_for(SchemeKind::DooSabin, 2));
            if (!built.mesh.topology().is_closed()) {
                RefineOptions no_boundary = options_for(SchemeKind::DooSabin, 2);
                no_boundary.scheme_options.boundary = BoundaryInterpolation::None;
                expect_finest_equals_hierarchy(mesh, no_boundary);
            }
        }
        if (mesh.triangles_only) {
            expect_finest_equals_hierarchy(mesh, options_for(SchemeKind::Loop, 2));
            expect_finest_equals_hierarchy(mesh, options_for(SchemeKind::Linear, 2));
        }
    }
    for (const char* name : {"tetra_1", "tetra_2"}) {
        expect_finest_equals_hierarchy(test::find_bundled(name), options_for(SchemeKind::C2g0, 2));
    }
    RefineOptions tuned = options_for(SchemeKind::CatmullClark, 2);
    tuned.weights = TunedWeights::preset("cup");
    expect_finest_equals_hierarchy(test::find_bundled("quad_valence_5"), tuned);
    expect_finest_equals_hierarchy(test::find_bundled("cube"), options_for(SchemeKind::CatmullClark, 0));
    RefineOptions chaikin = options_for(SchemeKind::CatmullClark, 3);
    chaikin.scheme_options.creasing = CreasingMethod::Chaikin;
    expect_finest_equals_hierarchy(test::find_bundled("cube_creases"), chaikin);
}

/// Creases (semi-sharp and infinite, inside and on the boundary, under both creasing methods),
/// corners and holes: refine_finest_faces orders the child's tags as the child Topology does (creases
/// by edge number, which is not the order the step makes them in), for the quad and the triangle split.
TEST(RefineFinest, FacesOnlyKeepTheTagsInTheTopologysOrder) {
    const auto grid = [](Index n, bool triangles) {
        const auto id = [n](Index i, Index j) { return j * (n + 1) + i; };
        std::vector<std::vector<Index>> faces;
        for (Index j = 0; j < n; ++j) {
            for (Index i = 0; i < n; ++i) {
                const std::array<Index, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
                if (triangles) {
                    faces.push_back({q[0], q[1], q[2]});
                    faces.push_back({q[0], q[2], q[3]});
                } else {
                    faces.push_back({q.begin(), q.end()});
                }
            }
        }
        // Faces in a scrambled order, each from another corner: the parent's edge order (in which
        // the step makes the child's crease tags) is then far from the child's.
        std::vector<Index> offsets{0};
        std::vector<Index> corners;
        const std::size_t m = faces.size();
        for (std::size_t k = 0; k < m; ++k) {
            const std::vector<Index>& face = faces[(k * 7 + 3) % m];
            std::rotate_copy(face.begin(), face.begin() + static_cast<std::ptrdiff_t>(k % face.size()), face.end(),
                             std::back_inserter(corners));
            offsets.push_back(static_cast<Index>(corners.size()));
        }
        Points X((n + 1) * (n + 1), 3);
        for (Index j = 0; j <= n; ++j) {
            for (Index i = 0; i <= n; ++i) {
                X.row(id(i, j)) << i, j, std::sin(0.7 * i) * std::cos(0.4 * j);
            }
        }
        SharpnessTags tags;
        // A crease across the middle row of vertices (semi-sharp, rising), one from the boundary
        // inwards, a boundary edge tagged, a corner and a hole.
        for (Index i = 0; i < n; ++i) {
            tags.creases.push_back({id(i, n / 2), id(i + 1, n / 2), 0.5 + 0.75 * i, 0});
        }
        tags.creases.push_back({id(1, 0), id(1, 1), infinite_sharpness, 0});
        tags.creases.push_back({id(2, 0), id(3, 0), 2.0, 0});
        tags.corners.push_back({id(n - 1, n - 1), 1.5, 0});
        tags.holes.push_back({static_cast<Index>((offsets.size() - 1) / 2), 0});
        return std::pair{Topology(X.rows(), offsets, corners, tags), X};
    };
    for (const CreasingMethod creasing : {CreasingMethod::Uniform, CreasingMethod::Chaikin}) {
        for (const bool triangles : {false, true}) {
            const auto [topology, X] = grid(6, triangles);  // 36 or 72 faces: 7 is prime to both
            ASSERT_FALSE(topology.sharpness_tags().holes.empty());
            for (const SchemeKind scheme :
                 triangles ? std::vector{SchemeKind::Loop, SchemeKind::Linear, SchemeKind::CatmullClark}
                           : std::vector{SchemeKind::CatmullClark, SchemeKind::Bilinear}) {
                for (const int levels : {1, 3}) {  // a last step from the scrambled mesh, and from a split's
                    RefineOptions options = options_for(scheme, levels);
                    options.scheme_options.creasing = creasing;
                    const FinestLevel finest = refine_finest(topology, X, options);
                    ASSERT_FALSE(finest.topology.sharpness_tags().creases.empty());
                    ASSERT_FALSE(finest.topology.sharpness_tags().holes.empty());
                    SCOPED_TRACE(std::string(to_string(scheme)) + (triangles ? " triangles " : " quads ") +
                                 to_string(creasing) + " L = " + std::to_string(levels));
                    expect_faces_equal_finest(refine_finest_faces(topology, X, options), finest);
                }
            }
        }
    }
}

/// A 40-gon's face point and its corners' vertex points have rows of more than 32 entries, which
/// the row builder sorts and merges in one go instead of as they come: carried points must be
/// summed in the merged order there too. Coordinates spread over many binades, so that a different
/// order of the sums would show in the last bits.
TEST(RefineFinest, LongRowsAreSummedAsTheProductSumsThem) {
    constexpr Index n = 40;
    std::vector<Index> face(n);
    Points X(n, 3);
    for (Index i = 0; i < n; ++i) {
        face[static_cast<std::size_t>(i)] = i;
        const double angle = 2.0 * 3.141592653589793 * static_cast<double>(i) / n;
        X.row(i) << std::cos(angle) * (1.0 + 0.37 * i), std::sin(angle) / (1.0 + i),
            std::ldexp(1.0 + 0.1 * i, i % 9 - 4);
    }
    const Topology polygon = Topology::from_polygons(n, {face});
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Bilinear, SchemeKind::DooSabin}) {
        expect_finest_equals_hierarchy(polygon, X, options_for(scheme, 2), "40-gon");
    }
}

template <class Span>
std::vector<typename Span::value_type> list(const Span& s) {
    return {s.begin(), s.end()};
}

void expect_same_topology(const Topology& a, const Topology& b) {
    ASSERT_EQ(a.num_vertices(), b.num_vertices());
    ASSERT_EQ(a.num_edges(), b.num_edges());
    ASSERT_EQ(a.num_faces(), b.num_faces());
    EXPECT_EQ(list(a.face_offsets()), list(b.face_offsets()));
    EXPECT_EQ(list(a.all_face_vertices()), list(b.all_face_vertices()));
    for (Index e = 0; e < a.num_edges(); ++e) {
        ASSERT_EQ(a.edge_vertices(e), b.edge_vertices(e)) << "edge " << e;
        ASSERT_EQ(list(a.edge_faces(e)), list(b.edge_faces(e))) << "edge " << e;
        ASSERT_EQ(a.edge_sharpness(e), b.edge_sharpness(e)) << "edge " << e;
    }
    for (Index v = 0; v < a.num_vertices(); ++v) {
        ASSERT_EQ(list(a.vertex_faces(v)), list(b.vertex_faces(v))) << "vertex " << v;
        ASSERT_EQ(list(a.vertex_edges(v)), list(b.vertex_edges(v))) << "vertex " << v;
        ASSERT_EQ(a.vertex_sharpness(v), b.vertex_sharpness(v)) << "vertex " << v;
    }
    for (Index f = 0; f < a.num_faces(); ++f) {
        ASSERT_EQ(list(a.face_edges(f)), list(b.face_edges(f))) << "face " << f;
        ASSERT_EQ(a.is_hole(f), b.is_hole(f)) << "face " << f;
    }
}

void expect_same_matrix(const SparseMatrix& a, const SparseMatrix& b) {
    ASSERT_EQ(a.rows(), b.rows());
    ASSERT_EQ(a.cols(), b.cols());
    ASSERT_EQ(a.nonZeros(), b.nonZeros());
    const auto nnz = static_cast<std::size_t>(a.nonZeros());
    EXPECT_TRUE(std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()));
    EXPECT_TRUE(std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr()));
    EXPECT_TRUE(std::equal(a.valuePtr(), a.valuePtr() + nnz, b.valuePtr()));
}

void expect_same_provenance(const Provenance& got, const Provenance& want) {
    EXPECT_EQ(got.vertex_parent_kind, want.vertex_parent_kind);
    EXPECT_EQ(got.vertex_parent, want.vertex_parent);
    EXPECT_EQ(got.face_parent_kind, want.face_parent_kind);
    EXPECT_EQ(got.face_parent, want.face_parent);
    EXPECT_EQ(got.face_parent_corner, want.face_parent_corner);
}

/// A Hierarchy built with its control points carries them through each step's rows
/// (StepRun::keep_matrix): every level's topology, S0 and provenance must be the plain Hierarchy's,
/// and its positions those of positions(level, X), bit for bit.
void expect_built_with_points_equals_plain(const Hierarchy& plain, const Topology& base, const Points& control_points,
                                           const RefineOptions& options) {
    const Hierarchy carried(base, options, control_points);
    ASSERT_TRUE(carried.has_positions());
    EXPECT_FALSE(plain.has_positions());
    ASSERT_EQ(carried.num_steps(), plain.num_steps());
    EXPECT_TRUE((carried.positions(0).array() == control_points.array()).all());
    for (int l = 1; l <= plain.num_steps(); ++l) {
        SCOPED_TRACE("carried, level " + std::to_string(l));
        expect_same_topology(carried.topology(l), plain.topology(l));
        expect_same_matrix(carried.step(l).S0, plain.step(l).S0);
        expect_same_provenance(carried.step(l).provenance, plain.step(l).provenance);
        const Points expected = plain.positions(l, control_points);
        ASSERT_EQ(carried.positions(l).rows(), expected.rows());
        EXPECT_TRUE((carried.positions(l).array() == expected.array()).all()) << "positions differ";
    }
}

/// The steps with forms (refine_with_forms) build their S0 first: the positions are its products,
/// as positions(level, X) takes them. Asking a hierarchy built without points for them, or giving
/// points of the wrong size, is an InputError.
TEST(Hierarchy, BuiltWithPointsCarriesThemToEveryLevel) {
    for (const char* name : {"cube", "icosahedron"}) {
        SCOPED_TRACE(name);
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        RefineOptions options =
            options_for(std::string(name) == "cube" ? SchemeKind::CatmullClark : SchemeKind::Loop, 3);
        options.forms = true;
        const Hierarchy plain(built.mesh.topology(), options);
        expect_built_with_points_equals_plain(plain, built.mesh.topology(), built.mesh.positions(), options);
        EXPECT_THROW((void)plain.positions(1), InputError);
        const Points too_few = built.mesh.positions().topRows(built.mesh.positions().rows() - 1);
        EXPECT_THROW(Hierarchy(built.mesh.topology(), options, too_few), InputError);
        const Hierarchy carried(built.mesh.topology(), options, built.mesh.positions());
        EXPECT_THROW((void)carried.positions(4), InputError);
    }
}

/// With two threads each step builds the child topology on a second thread while the first builds
/// S0 or carries the points (RefineOptions::num_threads): every level, every S0 and the positions
/// must be those of one thread, bit for bit. The meshes are refined until a step's parent has at
/// least 1024 faces, from where a step takes the second thread (detail::step_threads).
TEST(RefineThreads, TwoThreadsGiveWhatOneGivesBitForBit) {
    struct Case {
        const char* mesh;
        SchemeKind scheme;
        int levels;
    };
    for (const Case& c : {Case{"cube_creases", SchemeKind::CatmullClark, 5},
                          Case{"annulus", SchemeKind::CatmullClark, 4}, Case{"icosahedron", SchemeKind::Loop, 5},
                          Case{"quad_torus", SchemeKind::Bilinear, 4}, Case{"tri_grid", SchemeKind::Linear, 4},
                          Case{"tetra_1", SchemeKind::C2g0, 5}, Case{"cube", SchemeKind::DooSabin, 5}}) {
        SCOPED_TRACE(std::string(c.mesh) + " " + to_string(c.scheme));
        const BuildResult built = read_mesh(test::find_bundled(c.mesh).path);
        RefineOptions one = options_for(c.scheme, c.levels);
        one.num_threads = 1;
        RefineOptions two = one;
        two.num_threads = 2;
        const Hierarchy serial(built.mesh.topology(), one);
        const Hierarchy parallel(built.mesh.topology(), two);
        ASSERT_GE(serial.topology(c.levels - 1).num_faces(), 1024) << "the last step would not take a second thread";
        for (int l = 1; l <= c.levels; ++l) {
            SCOPED_TRACE("level " + std::to_string(l));
            expect_same_topology(serial.topology(l), parallel.topology(l));
            expect_same_matrix(serial.step(l).S0, parallel.step(l).S0);
        }
        const Hierarchy carried(built.mesh.topology(), two, built.mesh.positions());
        for (int l = 1; l <= c.levels; ++l) {
            SCOPED_TRACE("carried, level " + std::to_string(l));
            expect_same_matrix(serial.step(l).S0, carried.step(l).S0);
            const Points expected = serial.positions(l, built.mesh.positions());
            EXPECT_TRUE((carried.positions(l).array() == expected.array()).all()) << "positions differ";
        }
        const FinestLevel finest_one = refine_finest(built.mesh.topology(), built.mesh.positions(), one);
        const FinestLevel finest_two = refine_finest(built.mesh.topology(), built.mesh.positions(), two);
        expect_same_topology(finest_one.topology, finest_two.topology);
        EXPECT_TRUE((finest_one.positions.array() == finest_two.positions.array()).all()) << "positions differ";
        expect_faces_equal_finest(refine_finest_faces(built.mesh.topology(), built.mesh.positions(), two), finest_one);
    }
    RefineOptions negative = options_for(SchemeKind::CatmullClark, 1);
    negative.num_threads = -1;
    EXPECT_THROW(Hierarchy(read_mesh(test::find_bundled("cube").path).mesh.topology(), negative), InputError);
}

/// KeptTopologies::FinestFaces drops each level's Topology once its child exists and writes only the
/// finest level's face list: every S0 (S1, S2), provenance, position and accumulated operator must be
/// those of a hierarchy keeping every level, bit for bit, and finest_faces() what a writer gets from
/// its finest level (to_polygon_soup), tag for tag. The levels it dropped are refused by name.
/// KeptTopologies::Finest likewise, with the finest level's Topology equal to Every's, table for table.
void expect_dropped_levels_keep_the_rest(const Topology& base, const Points& X, RefineOptions options,
                                         const std::string& name) {
    SCOPED_TRACE(name + " " + to_string(options.scheme) + " L = " + std::to_string(options.levels) +
                 (options.forms ? " with forms" : "") + ", " + std::to_string(options.num_threads) + " threads");
    const Hierarchy every(base, options, X);
    options.kept_topologies = KeptTopologies::FinestFaces;
    const Hierarchy plain(base, options);
    const Hierarchy carried(base, options, X);
    const int L = options.levels;
    for (const Hierarchy* lean : {&plain, &carried}) {
        ASSERT_EQ(lean->num_steps(), L);
        expect_same_topology(lean->topology(0), base);
        for (int l = 1; l <= L; ++l) {
            SCOPED_TRACE("level " + std::to_string(l));
            EXPECT_EQ(lean->step(l).topology.num_faces(), 0) << "a dropped level's topology is empty";
            try {
                (void)lean->topology(l);
                ADD_FAILURE() << "level " << l << "'s topology was dropped";
            } catch (const InputError& error) {
                EXPECT_NE(std::string(error.what()).find("finest_faces()"), std::string::npos) << error.what();
            }
            expect_same_matrix(lean->step(l).S0, every.step(l).S0);
            expect_same_matrix(lean->step(l).S1, every.step(l).S1);
            expect_same_matrix(lean->step(l).S2, every.step(l).S2);
            expect_same_provenance(lean->step(l).provenance, every.step(l).provenance);
        }
        expect_same_matrix(lean->accumulated(L), every.accumulated(L));
        if (options.forms) {
            expect_same_matrix(lean->accumulated_form(1, L), every.accumulated_form(1, L));
            expect_same_matrix(lean->accumulated_form(2, L), every.accumulated_form(2, L));
        }
        EXPECT_TRUE(lean->finest_faces().positions.size() == 0) << "positions(L) has them";
    }
    for (int l = 0; l <= L; ++l) {
        EXPECT_TRUE((carried.positions(l).array() == every.positions(l).array()).all()) << "level " << l;
    }
    EXPECT_TRUE((plain.positions(L, X).array() == every.positions(L).array()).all());
    FinestLevel expected{every.topology(L), every.positions(L), {}};
    FinestFaces got{plain.finest_faces(), {}};
    got.mesh.positions = carried.positions(L);
    expect_faces_equal_finest(got, expected);
    got.mesh = carried.finest_faces();
    got.mesh.positions = carried.positions(L);
    expect_faces_equal_finest(got, expected);
    EXPECT_THROW((void)every.finest_faces(), InputError);

    // KeptTopologies::Finest keeps the finest level's whole Topology, and drops only the levels between.
    options.kept_topologies = KeptTopologies::Finest;
    const Hierarchy finest(base, options, X);
    expect_same_topology(finest.topology(L), every.topology(L));
    expect_same_topology(finest.topology(0), base);
    for (int l = 1; l < L; ++l) {
        EXPECT_EQ(finest.step(l).topology.num_faces(), 0) << "level " << l;
        EXPECT_THROW((void)finest.topology(l), InputError) << "level " << l;
    }
    for (int l = 1; l <= L; ++l) {
        expect_same_matrix(finest.step(l).S0, every.step(l).S0);
        expect_same_matrix(finest.step(l).S1, every.step(l).S1);
        expect_same_provenance(finest.step(l).provenance, every.step(l).provenance);
        EXPECT_TRUE((finest.positions(l).array() == every.positions(l).array()).all()) << "level " << l;
    }
    expect_same_matrix(finest.accumulated(L), every.accumulated(L));
    EXPECT_THROW((void)finest.finest_faces(), InputError);
}

TEST(Hierarchy, KeepingOnlyTheFinestLevelChangesNothingElse) {
    const auto check = [](const char* name, SchemeKind scheme, int levels, bool forms = false, int threads = 1,
                          BoundaryInterpolation boundary = BoundaryInterpolation::EdgeAndCorner) {
        const BuildResult built = read_mesh(test::find_bundled(name).path);
        RefineOptions options = options_for(scheme, levels);
        options.forms = forms;
        options.num_threads = threads;
        options.scheme_options.boundary = boundary;
        expect_dropped_levels_keep_the_rest(built.mesh.topology(), built.mesh.positions(), options, name);
    };
    check("cube_creases", SchemeKind::CatmullClark, 3);
    check("cube_creases", SchemeKind::CatmullClark, 5, false, 2);  // the last steps on two threads
    check("cube", SchemeKind::CatmullClark, 0);                    // the finest is the base
    check("cube", SchemeKind::CatmullClark, 1);
    check("cube", SchemeKind::CatmullClark, 3, true);  // with forms the finest Topology is built and dropped
    check("icosahedron", SchemeKind::Loop, 3, true);
    check("annulus", SchemeKind::CatmullClark, 2, false, 1, BoundaryInterpolation::None);
    check("annulus", SchemeKind::Bilinear, 2);
    check("tri_grid", SchemeKind::Loop, 2);
    check("tri_grid", SchemeKind::Linear, 2);
    check("tetra_1", SchemeKind::C2g0, 2);
    check("cube", SchemeKind::DooSabin, 2);
    check("annulus", SchemeKind::DooSabin, 2, false, 1, BoundaryInterpolation::None);
    RefineOptions unknown = options_for(SchemeKind::CatmullClark, 1);
    unknown.kept_topologies = static_cast<KeptTopologies>(7);
    EXPECT_THROW(Hierarchy(read_mesh(test::find_bundled("cube").path).mesh.topology(), unknown), InputError);
}

/// refine_finest and refine_finest_faces keep two levels at a time, and the latter only the finest
/// level's face list: they are held to their own estimates, which lie below the Hierarchy's.
TEST(RefineFinest, IsHeldToItsOwnMemoryEstimate) {
    const BuildResult built = read_mesh(test::find_bundled("cube").path);
    const Topology& base = built.mesh.topology();
    RefineOptions options = options_for(SchemeKind::CatmullClark, 6);
    const auto sizes = predict_sizes(base, options.scheme, options.levels);
    const std::int64_t every_level = estimated_peak_bytes(sizes);
    const std::int64_t finest = estimated_finest_peak_bytes(sizes, false);
    const std::int64_t faces = estimated_finest_peak_bytes(sizes, true);
    EXPECT_LT(faces, finest);
    EXPECT_LT(finest, every_level);
    // At least what is returned: the finest positions and face list, or its topology.
    EXPECT_GE(faces, 24 * sizes.back().vertices + 4 * sizes.back().corners);
    EXPECT_GE(finest, estimated_bytes(sizes.back()));
    options.max_memory = faces - 1;
    try {
        (void)refine_finest_faces(base, built.mesh.positions(), options);
        FAIL() << "expected a refusal";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("needs about " + format_bytes(faces) + " at its peak"),
                  std::string::npos)
            << error.what();
    }
    options.max_memory = faces;
    EXPECT_NO_THROW((void)refine_finest_faces(base, built.mesh.positions(), options));
    EXPECT_THROW((void)refine_finest(base, built.mesh.positions(), options), InputError);
    options.max_memory = finest;
    EXPECT_NO_THROW((void)refine_finest(base, built.mesh.positions(), options));
    EXPECT_THROW(Hierarchy(base, options), InputError);
    // A Hierarchy that keeps only the finest faces holds every S0 (10 bytes and more per non-zero):
    // more than refine_finest, less than every level's topology too; keeping the finest Topology lies
    // between the two. Each is held to its own estimate: run at it, refused 1 byte under.
    const std::int64_t lean = estimated_peak_bytes(sizes, KeptTopologies::FinestFaces);
    const std::int64_t finest_topology = estimated_peak_bytes(sizes, KeptTopologies::Finest);
    EXPECT_EQ(estimated_peak_bytes(sizes, KeptTopologies::Every), every_level);
    EXPECT_GT(lean, faces);
    EXPECT_GT(finest_topology, lean);
    EXPECT_LT(finest_topology, every_level);
    for (const auto& [kept, estimate] :
         {std::pair{KeptTopologies::FinestFaces, lean}, std::pair{KeptTopologies::Finest, finest_topology}}) {
        options.kept_topologies = kept;
        options.max_memory = estimate;
        EXPECT_NO_THROW(Hierarchy(base, options));
        options.max_memory = estimate - 1;
        EXPECT_THROW(Hierarchy(base, options), InputError);
    }
}

TEST(RefineFinest, RefusesWhatTheHierarchyRefuses) {
    const BuildResult built = read_mesh(test::find_bundled("quad_torus").path);
    EXPECT_THROW(
        (void)refine_finest(built.mesh.topology(), built.mesh.positions(), options_for(SchemeKind::CatmullClark, 12)),
        InputError);  // 805 306 368 faces
    EXPECT_THROW((void)refine_finest(built.mesh.topology(), Points::Zero(3, 3), options_for(SchemeKind::Bilinear, 1)),
                 InputError);  // rows do not match the vertices
    EXPECT_THROW((void)refine_finest(built.mesh.topology(), built.mesh.positions(), options_for(SchemeKind::Loop, 1)),
                 UnsupportedError);  // quads under Loop
}

}  // namespace
}  // namespace limsurf
