#include "osd_limit.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "support/opensubdiv_refiner.h"

namespace limsurf::test {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

namespace {

void check_scheme(const Topology& t, SchemeKind kind) {
    if (kind != SchemeKind::CatmullClark && kind != SchemeKind::Loop) {
        throw std::runtime_error(std::string("osd_limit: scheme ") + to_string(kind) +
                                 " is not supported (CatmullClark or Loop)");
    }
    if (kind == SchemeKind::Loop && !t.all_faces_have_degree(3)) {
        throw std::runtime_error("osd_limit: Loop needs a triangle mesh");
    }
}

std::unique_ptr<Far::TopologyRefiner> make_refiner(const Topology& t, SchemeKind kind, const SchemeOptions& o) {
    check_scheme(t, kind);
    auto refiner = make_opensubdiv_refiner(t, kind, o);
    if (!refiner) {
        throw std::runtime_error("osd_limit: Far::TopologyRefinerFactory refused the topology");
    }
    return refiner;
}

std::vector<OsdPoint> to_osd(const Points& X) {
    std::vector<OsdPoint> out(static_cast<std::size_t>(X.rows()));
    for (Index v = 0; v < X.rows(); ++v) {
        out[static_cast<std::size_t>(v)] = {{X(v, 0), X(v, 1), X(v, 2)}};
    }
    return out;
}

void check_points(const Topology& t, const Points& X) {
    if (X.rows() != t.num_vertices()) {
        throw std::runtime_error("osd_limit: " + std::to_string(X.rows()) + " positions for " +
                                 std::to_string(t.num_vertices()) + " vertices");
    }
}

/// Rows of a stencil table applied to control points, appended below row @p first of @p out.
void apply_stencils(const Far::StencilTableReal<double>& table, const Points& X, Index first, Points& out) {
    const auto& sizes = table.GetSizes();
    const auto& offsets = table.GetOffsets();
    const auto& indices = table.GetControlIndices();
    const auto& weights = table.GetWeights();
    for (int s = 0; s < table.GetNumStencils(); ++s) {
        Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
        const auto begin = static_cast<std::size_t>(offsets[static_cast<std::size_t>(s)]);
        for (std::size_t k = begin; k < begin + static_cast<std::size_t>(sizes[static_cast<std::size_t>(s)]); ++k) {
            p += weights[k] * X.row(indices[k]);
        }
        out.row(first + s) = p;
    }
}

}  // namespace

OsdVertexLimits osd_vertex_limits(const Topology& topology, const Points& X, SchemeKind scheme,
                                  const SchemeOptions& options) {
    check_points(topology, X);
    auto refiner = make_refiner(topology, scheme, options);
    // Limit() needs a full last level (and one refinement for non-quad faces).
    Far::TopologyRefiner::UniformOptions uniform(1);
    uniform.fullTopologyInLastLevel = true;
    refiner->RefineUniform(uniform);
    const std::vector<OsdPoint> level0 = to_osd(X);
    std::vector<OsdPoint> level1(static_cast<std::size_t>(refiner->GetLevel(1).GetNumVertices()));
    std::vector<OsdPoint> pos(level1.size()), tan1(level1.size()), tan2(level1.size());
    Far::PrimvarRefinerReal<double> primvar(*refiner);
    const OsdPoint* src0 = level0.data();
    OsdPoint* dst1 = level1.data();
    primvar.Interpolate(1, src0, dst1);
    const OsdPoint* src1 = level1.data();
    OsdPoint* dst_pos = pos.data();
    OsdPoint* dst_tan1 = tan1.data();
    OsdPoint* dst_tan2 = tan2.data();
    primvar.Limit(src1, dst_pos, dst_tan1, dst_tan2);
    OsdVertexLimits out{Points(X.rows(), 3), Points(X.rows(), 3), Points(X.rows(), 3)};
    for (Index v = 0; v < X.rows(); ++v) {  // child v of a refinement is parent v
        const auto i = static_cast<std::size_t>(v);
        out.position.row(v) << pos[i].p[0], pos[i].p[1], pos[i].p[2];
        out.tangent1.row(v) << tan1[i].p[0], tan1[i].p[1], tan1[i].p[2];
        out.tangent2.row(v) << tan2[i].p[0], tan2[i].p[1], tan2[i].p[2];
    }
    return out;
}

struct OsdLimitEvaluator::Impl {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<const Far::PatchTable> table;
    std::unique_ptr<const Far::PatchMap> map;
    Points points;  // every patch point: control vertices, refined vertices of all levels, local points
    Index num_ptex = 0;
};

OsdLimitEvaluator::OsdLimitEvaluator(const Topology& topology, const Points& X, SchemeKind scheme,
                                     const SchemeOptions& options, int isolation_level, OsdEndCaps end_caps)
    : impl_(std::make_unique<Impl>()) {
    check_points(topology, X);
    if (isolation_level < 1 || isolation_level > 10) {
        throw std::runtime_error("osd_limit: isolation level " + std::to_string(isolation_level) +
                                 " out of range [1, 10]");
    }
    Impl& m = *impl_;
    m.refiner = make_refiner(topology, scheme, options);
    m.num_ptex = Far::PtexIndices(*m.refiner).GetNumFaces();

    Far::PatchTableFactory::Options patch_options(static_cast<unsigned>(isolation_level));
    patch_options.SetEndCapType(end_caps == OsdEndCaps::GregoryBasis
                                    ? Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS
                                    : Far::PatchTableFactory::Options::ENDCAP_BSPLINE_BASIS);
    patch_options.SetPatchPrecision<double>();
    patch_options.useInfSharpPatch = false;
    patch_options.useSingleCreasePatch = false;
    m.refiner->RefineAdaptive(patch_options.GetRefineAdaptiveOptions());
    m.table.reset(Far::PatchTableFactory::Create(*m.refiner, patch_options));
    if (!m.table) {
        throw std::runtime_error("osd_limit: Far::PatchTableFactory failed");
    }
    m.map = std::make_unique<Far::PatchMap>(*m.table);

    // Patch point indices run over the control vertices, the refined vertices of
    // every level, then the local (end-cap) points; stencils factorised down to
    // the control vertices give all of them.
    using StencilFactory = Far::StencilTableFactoryReal<double>;
    std::unique_ptr<const Far::StencilTableReal<double>> refined;
    if (m.refiner->GetMaxLevel() > 0) {
        StencilFactory::Options stencil_options;
        stencil_options.generateOffsets = true;
        stencil_options.generateIntermediateLevels = true;
        stencil_options.factorizeIntermediateLevels = true;
        stencil_options.generateControlVerts = false;
        refined.reset(StencilFactory::Create(*m.refiner, stencil_options));
    }
    const Far::StencilTableReal<double>* local = m.table->GetLocalPointStencilTable<double>();
    const int num_local = local ? local->GetNumStencils() : 0;
    if (num_local > 0) {
        if (!refined) {
            throw std::runtime_error("osd_limit: local points without refinement");
        }
        std::unique_ptr<const Far::StencilTableReal<double>> combined(
            StencilFactory::AppendLocalPointStencilTable(*m.refiner, refined.get(), local));
        if (combined) {
            refined = std::move(combined);
        }
    }
    const int num_refined = refined ? refined->GetNumStencils() : 0;
    const int expected = m.refiner->GetNumVerticesTotal() - topology.num_vertices() + num_local;
    if (num_refined != expected) {
        throw std::runtime_error("osd_limit: " + std::to_string(num_refined) + " stencils, expected " +
                                 std::to_string(expected));
    }
    m.points.resize(X.rows() + num_refined, 3);
    m.points.topRows(X.rows()) = X;
    if (refined) {
        apply_stencils(*refined, X, X.rows(), m.points);
    }
}

OsdLimitEvaluator::~OsdLimitEvaluator() = default;
OsdLimitEvaluator::OsdLimitEvaluator(OsdLimitEvaluator&&) noexcept = default;
OsdLimitEvaluator& OsdLimitEvaluator::operator=(OsdLimitEvaluator&&) noexcept = default;

Index OsdLimitEvaluator::num_ptex_faces() const {
    return impl_->num_ptex;
}

OsdPointEval OsdLimitEvaluator::evaluate(const SurfacePoint& point) const {
    const Impl& m = *impl_;
    if (point.face < 0 || point.face >= m.num_ptex) {
        throw std::runtime_error("osd_limit: ptex face " + std::to_string(point.face) + " out of range [0, " +
                                 std::to_string(m.num_ptex) + ")");
    }
    OsdPointEval out;
    const Far::PatchTable::PatchHandle* handle = m.map->FindPatch(point.face, point.u, point.v);
    if (handle == nullptr) {
        out.value.setConstant(std::numeric_limits<double>::quiet_NaN());
        return out;
    }
    out.has_patch = true;
    const Far::PatchParam param = m.table->GetPatchParam(*handle);
    const Far::PatchDescriptor::Type type = m.table->GetPatchArrayDescriptor(handle->arrayIndex).GetType();
    const Far::ConstIndexArray cvs = m.table->GetPatchVertices(*handle);
    constexpr int max_points = 20;  // Gregory basis
    if (cvs.size() > max_points) {
        throw std::runtime_error("osd_limit: patch with " + std::to_string(cvs.size()) + " points");
    }
    double w[6][max_points] = {};
    m.table->EvaluateBasis(*handle, point.u, point.v, w[0], w[1], w[2], w[3], w[4], w[5]);
    for (int i = 0; i < cvs.size(); ++i) {
        for (int r = 0; r < 6; ++r) {
            out.value.row(r) += w[r][i] * m.points.row(cvs[i]);
        }
    }
    const bool triangle = type == Far::PatchDescriptor::LOOP || type == Far::PatchDescriptor::GREGORY_TRIANGLE;
    out.regular = (type == Far::PatchDescriptor::REGULAR || type == Far::PatchDescriptor::LOOP) && param.IsRegular();
    out.end_cap = !out.regular;
    out.non_quad_root = param.NonQuadRoot();
    out.triangle_rotated = triangle && param.IsTriangleRotated();
    out.depth = param.GetDepth();
    out.patch = handle->patchIndex;
    // Far 3.5 defects (header comment): EvaluateBasis scales by 2^depth where the
    // parametric size of a patch under an n-gon's sub-face is 2^-(depth-1), and
    // multiplies the second derivatives of rotated triangles by sign^3 = -1.
    const double first = out.non_quad_root ? 0.5 : 1.0;
    const double second = first * first * (out.triangle_rotated ? -1.0 : 1.0);
    out.value.middleRows(1, 2) *= first;
    out.value.bottomRows(3) *= second;
    return out;
}

std::vector<OsdPointEval> osd_evaluate(const Topology& topology, const Points& X, SchemeKind scheme,
                                       const SchemeOptions& options, const std::vector<SurfacePoint>& points,
                                       int isolation_level, OsdEndCaps end_caps) {
    const OsdLimitEvaluator evaluator(topology, X, scheme, options, isolation_level, end_caps);
    std::vector<OsdPointEval> out;
    out.reserve(points.size());
    for (const SurfacePoint& p : points) {
        out.push_back(evaluator.evaluate(p));
    }
    return out;
}

}  // namespace limsurf::test
