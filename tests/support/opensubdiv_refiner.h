// OpenSubdiv Far as a test peer: a TopologyRefiner for a limsurf Topology with the
// same options and tags (boundary rule, creasing, triangle rule, creases, corners,
// holes), and the point type Far's primvar interpolation wants. Header-only: only
// targets that link limsurf::peer_opensubdiv include it.
#pragma once

#include <memory>
#include <vector>

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "limsurf/mesh/topology.h"
#include "limsurf/scheme/scheme.h"

namespace limsurf::test {

/// A 3D point for Far::PrimvarRefiner and stencil tables.
struct OsdPoint {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(const OsdPoint& src, double w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

/// @brief Far's refiner for the faces of @p t with the tags @p tags as a file would list them (repeats
///   included: Far applies them in order) under Loop, bilinear or Catmull–Clark (any other kind), with
///   @p o mapped onto Sdc::Options; nullptr when Far refuses the topology.
inline std::unique_ptr<OpenSubdiv::Far::TopologyRefiner>
make_opensubdiv_refiner(const Topology& t, const SharpnessTags& tags, SchemeKind kind, const SchemeOptions& o) {
    namespace Far = OpenSubdiv::Far;
    namespace Sdc = OpenSubdiv::Sdc;
    Sdc::Options options;
    options.SetVtxBoundaryInterpolation(o.boundary == BoundaryInterpolation::None ? Sdc::Options::VTX_BOUNDARY_NONE
                                        : o.boundary == BoundaryInterpolation::EdgeOnly
                                            ? Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                            : Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    options.SetCreasingMethod(o.creasing == CreasingMethod::Uniform ? Sdc::Options::CREASE_UNIFORM
                                                                    : Sdc::Options::CREASE_CHAIKIN);
    options.SetTriangleSubdivision(o.triangles == TriangleSubdivision::Smooth ? Sdc::Options::TRI_SUB_SMOOTH
                                                                              : Sdc::Options::TRI_SUB_CATMARK);
    // The factory copies everything out of the descriptor during Create().
    std::vector<int> degrees;
    for (Index f = 0; f < t.num_faces(); ++f) {
        degrees.push_back(t.face_degree(f));
    }
    std::vector<Far::Index> crease_pairs, corners, holes;
    std::vector<float> crease_weights, corner_weights;
    for (const CreaseTag& c : tags.creases) {
        crease_pairs.insert(crease_pairs.end(), {c.v0, c.v1});
        crease_weights.push_back(static_cast<float>(c.sharpness));
    }
    for (const CornerTag& c : tags.corners) {
        corners.push_back(c.vertex);
        corner_weights.push_back(static_cast<float>(c.sharpness));
    }
    for (const HoleTag& h : tags.holes) {
        holes.push_back(h.face);
    }
    Far::TopologyDescriptor desc;
    desc.numVertices = t.num_vertices();
    desc.numFaces = t.num_faces();
    desc.numVertsPerFace = degrees.data();
    desc.vertIndicesPerFace = t.all_face_vertices().data();
    desc.numCreases = static_cast<int>(crease_weights.size());
    desc.creaseVertexIndexPairs = crease_pairs.data();
    desc.creaseWeights = crease_weights.data();
    desc.numCorners = static_cast<int>(corner_weights.size());
    desc.cornerVertexIndices = corners.data();
    desc.cornerWeights = corner_weights.data();
    desc.numHoles = static_cast<int>(holes.size());
    desc.holeIndices = holes.data();
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    const auto type = kind == SchemeKind::Loop       ? Sdc::SCHEME_LOOP
                      : kind == SchemeKind::Bilinear ? Sdc::SCHEME_BILINEAR
                                                     : Sdc::SCHEME_CATMARK;
    return std::unique_ptr<Far::TopologyRefiner>(Factory::Create(desc, Factory::Options(type, options)));
}

/// @brief Far's refiner for @p t with its own sharpness and holes (Topology::sharpness_tags(): each
///   sharp edge and vertex once, in index order).
inline std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> make_opensubdiv_refiner(const Topology& t, SchemeKind kind,
                                                                                 const SchemeOptions& o) {
    return make_opensubdiv_refiner(t, t.sharpness_tags(), kind, o);
}

/// The volume enclosed by the faces of a refined level (each face fanned from its first corner), about
/// the mean point: the polyhedral volume of Far's own refinement, for the volume tests and benchmark.
inline double polyhedral_volume(const OpenSubdiv::Far::TopologyLevel& level, const OsdPoint* points) {
    double o[3] = {0.0, 0.0, 0.0};
    const int nv = level.GetNumVertices();
    for (int v = 0; v < nv; ++v) {
        for (int c = 0; c < 3; ++c) {
            o[c] += points[v].p[c] / nv;
        }
    }
    const auto at = [&](int v, int c) { return points[v].p[c] - o[c]; };
    double sum = 0.0;
    for (int f = 0; f < level.GetNumFaces(); ++f) {
        const auto fv = level.GetFaceVertices(f);
        for (int k = 1; k + 1 < fv.size(); ++k) {
            const int a = fv[0];
            const int b = fv[k];
            const int c = fv[k + 1];
            sum += at(a, 0) * (at(b, 1) * at(c, 2) - at(b, 2) * at(c, 1)) -
                   at(a, 1) * (at(b, 0) * at(c, 2) - at(b, 2) * at(c, 0)) +
                   at(a, 2) * (at(b, 0) * at(c, 1) - at(b, 1) * at(c, 0));
        }
    }
    return sum / 6.0;
}

}  // namespace limsurf::test
