// Doo–Sabin identities on every bundled mesh: S0 is a non-negative partition
// of unity, the counts follow from the F/E/V-face construction, Euler
// characteristic and genus are kept, planes and affine functions are
// reproduced, and the child boundary is Chaikin's corner cutting of the
// parent boundary (docs/doo_sabin.md).
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "limsurf/core/error.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/refine.h"
#include "support/mesh_zoo.h"

namespace limsurf {
namespace {

SchemeOptions with_boundary(BoundaryInterpolation boundary) {
    SchemeOptions options;
    options.boundary = boundary;
    return options;
}

/// The bundled meshes Doo–Sabin accepts (it refuses sharpness tags), optionally only the closed ones.
std::vector<test::BundledMesh> untagged_meshes(bool closed_only = false) {
    std::vector<test::BundledMesh> meshes;
    for (const test::BundledMesh& mesh : test::bundled_meshes()) {
        if (!read_mesh(mesh.path).mesh.topology().has_sharpness() && (mesh.closed || !closed_only)) {
            meshes.push_back(mesh);
        }
    }
    return meshes;
}

void expect_partition_of_unity(const SparseMatrix& S0, const std::string& what) {
    for (Index r = 0; r < S0.rows(); ++r) {
        double sum = 0.0;
        for (SparseMatrix::InnerIterator it(S0, r); it; ++it) {
            EXPECT_GE(it.value(), 0.0) << what << ": row " << r << " column " << it.col();
            sum += it.value();
        }
        EXPECT_NEAR(sum, 1.0, 1e-14) << what << ": row " << r;
    }
}

struct ExpectedCounts {
    Index num_vertices = 0;
    Index num_faces = 0;
};

/// V' = number of corners; F' = F + interior edges + interior vertices
/// (+ boundary vertices in >= 3 faces under the Chaikin boundary rule).
ExpectedCounts expected_counts(const Topology& t, bool boundary_rule) {
    ExpectedCounts counts{t.num_corners(), t.num_faces()};
    for (Index e = 0; e < t.num_edges(); ++e) {
        counts.num_faces += t.is_boundary_edge(e) ? 0 : 1;
    }
    for (Index v = 0; v < t.num_vertices(); ++v) {
        if (!t.is_boundary_vertex(v) || (boundary_rule && t.vertex_faces(v).size() >= 3)) {
            ++counts.num_faces;
        }
    }
    return counts;
}

class DooSabinIdentity : public ::testing::TestWithParam<test::BundledMesh> {};

TEST_P(DooSabinIdentity, CountsTopologyAndPartitionOfUnityOverThreeLevels) {
    const BuildResult r = read_mesh(GetParam().path);
    for (const BoundaryInterpolation boundary : {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::None}) {
        const bool boundary_rule = boundary != BoundaryInterpolation::None;
        Topology parent = r.mesh.topology();
        for (int level = 1; level <= 3; ++level) {
            const std::string what = GetParam().name + " level " + std::to_string(level) + " " + to_string(boundary);
            const Level child = refine_doo_sabin(parent, with_boundary(boundary));
            const Topology& t = child.topology;
            const ExpectedCounts counts = expected_counts(parent, boundary_rule);
            EXPECT_EQ(t.num_vertices(), counts.num_vertices) << what;
            EXPECT_EQ(t.num_faces(), counts.num_faces) << what;
            if (parent.is_closed()) {
                EXPECT_EQ(t.num_vertices(), 2 * parent.num_edges()) << what;
                EXPECT_EQ(t.num_faces(), parent.num_faces() + parent.num_edges() + parent.num_vertices()) << what;
                EXPECT_EQ(t.num_edges(), 4 * parent.num_edges()) << what;
                EXPECT_TRUE(t.is_closed()) << what;
            }
            EXPECT_EQ(t.euler_characteristic(), GetParam().euler_characteristic) << what;
            EXPECT_EQ(t.genus(), GetParam().genus) << what;
            EXPECT_EQ(t.num_components(), GetParam().num_components) << what;
            EXPECT_EQ(t.num_boundary_loops(), GetParam().num_boundary_loops) << what;
            EXPECT_EQ(child.S0.rows(), t.num_vertices()) << what;
            EXPECT_EQ(child.S0.cols(), parent.num_vertices()) << what;
            expect_partition_of_unity(child.S0, what);
            parent = t;
        }
    }
}

TEST_P(DooSabinIdentity, ProvenanceFollowsTheCornerOrder) {
    const BuildResult r = read_mesh(GetParam().path);
    const Topology& parent = r.mesh.topology();
    const Level child = refine_doo_sabin(parent);
    const Provenance& p = child.provenance;
    ASSERT_EQ(p.vertex_parent.size(), static_cast<std::size_t>(child.topology.num_vertices()));
    ASSERT_EQ(p.face_parent.size(), static_cast<std::size_t>(child.topology.num_faces()));
    ASSERT_EQ(p.face_parent_kind.size(), p.face_parent.size());
    ASSERT_EQ(p.face_parent_corner.size(), p.face_parent.size());
    for (Index f = 0; f < parent.num_faces(); ++f) {
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            const auto c = static_cast<std::size_t>(parent.face_offset(f) + i);
            EXPECT_EQ(p.vertex_parent_kind[c], ParentKind::Face);
            EXPECT_EQ(p.vertex_parent[c], f);
        }
        // F-face f is child face f, with the children of f's corners in order.
        const auto fv = child.topology.face_vertices(f);
        ASSERT_EQ(static_cast<Index>(fv.size()), parent.face_degree(f));
        for (Index i = 0; i < parent.face_degree(f); ++i) {
            EXPECT_EQ(fv[static_cast<std::size_t>(i)], parent.face_offset(f) + i);
        }
    }
    for (Index f = 0; f < child.topology.num_faces(); ++f) {
        const auto i = static_cast<std::size_t>(f);
        EXPECT_EQ(p.face_parent_corner[i], invalid_index);
        const auto fv = child.topology.face_vertices(f);
        switch (p.face_parent_kind[i]) {
        case ParentKind::Face:
            EXPECT_LT(f, parent.num_faces());
            EXPECT_EQ(p.face_parent[i], f);
            break;
        case ParentKind::Edge: {
            // The four corners sit at the two ends of the parent edge.
            ASSERT_EQ(fv.size(), 4U);
            const auto ends = parent.edge_vertices(p.face_parent[i]);
            for (const Index c : fv) {
                const Index v = parent.all_face_vertices()[static_cast<std::size_t>(c)];
                EXPECT_TRUE(v == ends[0] || v == ends[1]);
            }
            break;
        }
        case ParentKind::Vertex:
            EXPECT_EQ(fv.size(), parent.vertex_faces(p.face_parent[i]).size());
            for (const Index c : fv) {
                EXPECT_EQ(parent.all_face_vertices()[static_cast<std::size_t>(c)], p.face_parent[i]);
            }
            break;
        }
    }
}

TEST_P(DooSabinIdentity, TwoStepsAreTheProductOfTheirMatrices) {
    const BuildResult r = read_mesh(GetParam().path);
    const Level first = refine_doo_sabin(r.mesh.topology());
    const Level second = refine_doo_sabin(first.topology);
    const SparseMatrix product = second.S0 * first.S0;
    expect_partition_of_unity(product, GetParam().name + " product");
    const Points& x = r.mesh.positions();
    const Points stepwise = second.S0 * (first.S0 * x);
    const Points direct = product * x;
    EXPECT_LE((stepwise - direct).cwiseAbs().maxCoeff(), 1e-14 * (1.0 + x.cwiseAbs().maxCoeff()));
}

class DooSabinIdentityClosed : public ::testing::TestWithParam<test::BundledMesh> {};

TEST_P(DooSabinIdentityClosed, OrientationIsInherited) {
    // The signed volume of a closed mesh keeps its sign: child faces are outward.
    const BuildResult r = read_mesh(GetParam().path);
    const auto volume = [](const Topology& t, const Points& x) {
        double sum = 0.0;
        for (Index f = 0; f < t.num_faces(); ++f) {
            const auto fv = t.face_vertices(f);
            const Eigen::RowVector3d p0 = x.row(fv[0]);
            for (std::size_t k = 1; k + 1 < fv.size(); ++k) {
                sum += p0.dot(Eigen::RowVector3d(x.row(fv[k])).cross(Eigen::RowVector3d(x.row(fv[k + 1])))) / 6.0;
            }
        }
        return sum;
    };
    const double parent_volume = volume(r.mesh.topology(), r.mesh.positions());
    ASSERT_GT(std::abs(parent_volume), 1e-3);
    const Level child = refine_doo_sabin(r.mesh.topology());
    const double child_volume = volume(child.topology, child.S0 * r.mesh.positions());
    EXPECT_GT(child_volume * parent_volume, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Bundled, DooSabinIdentity, ::testing::ValuesIn(untagged_meshes()),
                         [](const auto& param_info) { return param_info.param.name; });
INSTANTIATE_TEST_SUITE_P(Closed, DooSabinIdentityClosed, ::testing::ValuesIn(untagged_meshes(true)),
                         [](const auto& param_info) { return param_info.param.name; });

TEST(DooSabinIdentityTags, SharpnessTagsAreRefused) {
    const BuildResult r = read_mesh(test::find_bundled("cube_creases").path);
    EXPECT_THROW((void)refine_doo_sabin(r.mesh.topology()), UnsupportedError);
}

TEST(DooSabinIdentityPlanar, PlanesAndAffineFunctionsAreReproduced) {
    for (const char* name : {"quad_grid", "tri_grid", "disk_ev5_quads", "disk_ev7_tris", "annulus", "pentagon"}) {
        const BuildResult r = read_mesh(test::find_bundled(name).path);
        ASSERT_TRUE((r.mesh.positions().col(2).array() == 0.0).all()) << name;
        for (const BoundaryInterpolation boundary :
             {BoundaryInterpolation::EdgeAndCorner, BoundaryInterpolation::None}) {
            Topology t = r.mesh.topology();
            Points x = r.mesh.positions();
            for (int level = 1; level <= 3; ++level) {
                const Level child = refine_doo_sabin(t, with_boundary(boundary));
                // Affine data a·x + b carried by S0 equals the affine function at the carried positions.
                const Eigen::Vector3d a(0.3, -1.7, 2.5);
                const double b = 0.25;
                const Eigen::VectorXd values = (x * a).array() + b;
                const Points child_x = child.S0 * x;
                const Eigen::VectorXd carried = child.S0 * values;
                const Eigen::VectorXd expected = (child_x * a).array() + b;
                EXPECT_LE((carried - expected).cwiseAbs().maxCoeff(), 1e-13) << name << " level " << level;
                EXPECT_EQ(child_x.col(2).cwiseAbs().maxCoeff(), 0.0) << name << " level " << level;
                t = child.topology;
                x = child_x;
            }
        }
    }
}

/// Chaikin's corner cutting of one closed boundary polygon, except that a
/// vertex in a single face (a one-face corner) is kept as one point.
std::vector<Eigen::RowVector3d> chaikin(const Topology& t, const Points& x, std::span<const Index> loop) {
    std::vector<Eigen::RowVector3d> out;
    const std::size_t m = loop.size();
    for (std::size_t j = 0; j < m; ++j) {
        const Index a = loop[j];
        const Index b = loop[(j + 1) % m];
        const Eigen::RowVector3d pa = x.row(a);
        const Eigen::RowVector3d pb = x.row(b);
        if (t.vertex_faces(a).size() == 1) {
            out.push_back(pa);
        } else {
            out.push_back(0.75 * pa + 0.25 * pb);
        }
        if (t.vertex_faces(b).size() != 1) {
            out.push_back(0.25 * pa + 0.75 * pb);
        }
    }
    return out;
}

TEST(DooSabinIdentityBoundary, ChildBoundaryIsChaikinOfTheParentBoundary) {
    for (const test::BundledMesh& mesh : test::meshes_with_boundary()) {
        const BuildResult r = read_mesh(mesh.path);
        if (r.mesh.topology().has_sharpness()) {
            continue;  // no crease rule (square_inclusion's interface)
        }
        Topology t = r.mesh.topology();
        Points x = r.mesh.positions();
        const double scale = 1.0 + x.cwiseAbs().maxCoeff();
        for (int level = 1; level <= 3; ++level) {
            const Level child = refine_doo_sabin(t);
            const Points child_x = child.S0 * x;
            ASSERT_EQ(child.topology.num_boundary_loops(), t.num_boundary_loops()) << mesh.name;
            std::vector<bool> used(static_cast<std::size_t>(child.topology.num_boundary_loops()), false);
            for (Index i = 0; i < t.num_boundary_loops(); ++i) {
                const std::vector<Eigen::RowVector3d> expected = chaikin(t, x, t.boundary_loop(i));
                // Find the child loop and the rotation that start at expected[0].
                bool found = false;
                for (Index j = 0; j < child.topology.num_boundary_loops() && !found; ++j) {
                    const auto loop = child.topology.boundary_loop(j);
                    if (used[static_cast<std::size_t>(j)] || loop.size() != expected.size()) {
                        continue;
                    }
                    for (std::size_t s = 0; s < loop.size() && !found; ++s) {
                        bool same = true;
                        for (std::size_t k = 0; k < loop.size() && same; ++k) {
                            const Eigen::RowVector3d p = child_x.row(loop[(s + k) % loop.size()]);
                            same = (p - expected[k]).cwiseAbs().maxCoeff() <= 1e-14 * scale;
                        }
                        if (same) {
                            found = true;
                            used[static_cast<std::size_t>(j)] = true;
                        }
                    }
                }
                EXPECT_TRUE(found) << mesh.name << " level " << level << ": boundary loop " << i
                                   << " is not refined by Chaikin's rule";
            }
            t = child.topology;
            x = child_x;
        }
    }
}

}  // namespace
}  // namespace limsurf
