// The face-split peer comparison with OpenSubdiv Far, shared by the bundled-mesh peer test and
// OpenSubdiv's regression shapes: Far (TopologyRefiner + PrimvarRefinerReal<double>) refines the same
// topology with the same options; positions agree vertex by vertex to 1e-12 of the bounding-box
// diagonal, child faces agree exactly (vertex and face orders mapped through provenance) and so does
// the child edge sharpness. Header-only: only targets that link limsurf::peer_opensubdiv include it.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyRefiner.h>

#include "limsurf/refine/refine.h"
#include "support/opensubdiv_refiner.h"

namespace limsurf::test {

/// @brief Refines @p t0 / @p p0 by @p num_levels levels of @p kind (Catmull–Clark, Loop or bilinear)
///   with limsurf and with Far and checks positions, faces and edge sharpness level by level.
inline void compare_with_opensubdiv(const Topology& t0, const Points& p0, SchemeKind kind, const SchemeOptions& options,
                                    const std::string& what, int num_levels = 3) {
    namespace Far = OpenSubdiv::Far;
    SCOPED_TRACE(what);
    auto refiner = make_opensubdiv_refiner(t0, kind, options);
    ASSERT_TRUE(refiner);
    Far::TopologyRefiner::UniformOptions uniform(num_levels);
    uniform.fullTopologyInLastLevel = true;  // edges of the last level, to compare sharpness
    refiner->RefineUniform(uniform);

    std::vector<std::vector<OsdPoint>> far(static_cast<std::size_t>(num_levels) + 1);
    far[0].resize(static_cast<std::size_t>(t0.num_vertices()));
    for (Index v = 0; v < t0.num_vertices(); ++v) {
        far[0][static_cast<std::size_t>(v)] = {{p0(v, 0), p0(v, 1), p0(v, 2)}};
    }
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    for (int l = 1; l <= num_levels; ++l) {
        far[static_cast<std::size_t>(l)].resize(static_cast<std::size_t>(refiner->GetLevel(l).GetNumVertices()));
        OsdPoint* dst = far[static_cast<std::size_t>(l)].data();
        primvar.Interpolate(l, far[static_cast<std::size_t>(l - 1)].data(), dst);
    }

    const double scale = (p0.colwise().maxCoeff() - p0.colwise().minCoeff()).norm();
    Topology parent = t0;
    Points positions = p0;
    std::vector<Index> to_far(static_cast<std::size_t>(t0.num_vertices()));
    for (Index v = 0; v < t0.num_vertices(); ++v) {
        to_far[static_cast<std::size_t>(v)] = v;
    }
    // Faces: Far puts a quad's child j at corner j with the parent vertex in position j, so
    // from level 2 on face numbers differ; map them through provenance too.
    std::vector<Index> face_to_far(static_cast<std::size_t>(t0.num_faces()));
    for (Index f = 0; f < t0.num_faces(); ++f) {
        face_to_far[static_cast<std::size_t>(f)] = f;
    }
    for (int l = 1; l <= num_levels; ++l) {
        const Far::TopologyLevel& far_parent = refiner->GetLevel(l - 1);
        const Far::TopologyLevel& far_child = refiner->GetLevel(l);
        Level level = refine(parent, kind, options);
        positions = level.S0 * positions;
        const Topology& child = level.topology;
        ASSERT_EQ(child.num_vertices(), far_child.GetNumVertices());
        ASSERT_EQ(child.num_faces(), far_child.GetNumFaces());
        std::vector<Index> child_to_far(static_cast<std::size_t>(child.num_vertices()));
        for (Index i = 0; i < child.num_vertices(); ++i) {
            const auto kind_i = level.provenance.vertex_parent_kind[static_cast<std::size_t>(i)];
            const Index p = level.provenance.vertex_parent[static_cast<std::size_t>(i)];
            Index mapped = invalid_index;
            if (kind_i == ParentKind::Vertex) {
                mapped = far_parent.GetVertexChildVertex(to_far[static_cast<std::size_t>(p)]);
            } else if (kind_i == ParentKind::Face) {
                mapped = far_parent.GetFaceChildVertex(face_to_far[static_cast<std::size_t>(p)]);
            } else {
                const auto ends = parent.edge_vertices(p);
                const Index far_edge = far_parent.FindEdge(to_far[static_cast<std::size_t>(ends[0])],
                                                           to_far[static_cast<std::size_t>(ends[1])]);
                ASSERT_GE(far_edge, 0);
                mapped = far_parent.GetEdgeChildVertex(far_edge);
            }
            child_to_far[static_cast<std::size_t>(i)] = mapped;
            const OsdPoint& q = far[static_cast<std::size_t>(l)][static_cast<std::size_t>(mapped)];
            const double d = (positions.row(i) - Eigen::RowVector3d(q.p[0], q.p[1], q.p[2])).norm();
            EXPECT_LE(d, 1e-12 * scale) << "level " << l << " child vertex " << i;
        }
        std::vector<Index> child_face_to_far(static_cast<std::size_t>(child.num_faces()));
        for (Index f = 0; f < child.num_faces(); ++f) {
            const Index g = level.provenance.face_parent[static_cast<std::size_t>(f)];
            const Index corner_k = level.provenance.face_parent_corner[static_cast<std::size_t>(f)];
            const Index far_g = face_to_far[static_cast<std::size_t>(g)];
            int child_j = 3;  // the middle triangle of a triangle split
            if (corner_k != invalid_index) {
                const Index corner =
                    to_far[static_cast<std::size_t>(parent.face_vertices(g)[static_cast<std::size_t>(corner_k)])];
                const auto far_corners = far_parent.GetFaceVertices(far_g);
                child_j = 0;
                while (child_j < far_corners.size() && far_corners[child_j] != corner) {
                    ++child_j;
                }
                ASSERT_LT(child_j, far_corners.size());
            }
            const Index far_f = far_parent.GetFaceChildFaces(far_g)[child_j];
            child_face_to_far[static_cast<std::size_t>(f)] = far_f;
            const auto ours = child.face_vertices(f);
            const auto theirs = far_child.GetFaceVertices(far_f);
            ASSERT_EQ(static_cast<int>(ours.size()), theirs.size());
            // Same cycle of vertices (Far's Loop children start at another corner: [e0, v1, e1], ...).
            int shift = 0;
            while (shift < theirs.size() && theirs[shift] != child_to_far[static_cast<std::size_t>(ours[0])]) {
                ++shift;
            }
            for (std::size_t k = 0; k < ours.size(); ++k) {
                const int j = (shift + static_cast<int>(k)) % theirs.size();
                EXPECT_EQ(child_to_far[static_cast<std::size_t>(ours[k])], theirs[j]) << "level " << l << " face " << f;
            }
        }
        for (Index e = 0; e < child.num_edges(); ++e) {
            if (child.is_boundary_edge(e)) {
                continue;  // OpenSubdiv stores the boundary's implicit infinite sharpness
            }
            const auto ends = child.edge_vertices(e);
            const Index far_edge = far_child.FindEdge(child_to_far[static_cast<std::size_t>(ends[0])],
                                                      child_to_far[static_cast<std::size_t>(ends[1])]);
            EXPECT_EQ(static_cast<float>(child.edge_sharpness(e)), far_child.GetEdgeSharpness(far_edge))
                << "level " << l << " edge " << e;
        }
        to_far = std::move(child_to_far);
        face_to_far = std::move(child_face_to_far);
        parent = std::move(level.topology);
    }
}

}  // namespace limsurf::test
