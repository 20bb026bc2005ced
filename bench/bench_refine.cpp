// Uniform refinement, 2 levels, topology + positions, on ~100k-face meshes:
// limsurf (Hierarchy: every level's child topology, S0, provenance, then S0
// products, or carried as the rows are built (Hierarchy with its control points, "points"; "operators": the same
// keeping of the level topologies only the finest level's face list, KeptTopologies::FinestFaces); refine_finest: the
// same, keeping only the finest level; refine_finest_faces: of the finest level only its face list, as `limsurf
// subdivide` and Far's default rows) against OpenSubdiv Far (TopologyRefiner::RefineUniform +
// PrimvarRefiner::Interpolate), CGAL Subdivision_method_3 and OpenMesh's uniform subdividers, each in the same binary
// and run. CGAL and OpenMesh refine in place, so each iteration starts from a copy made outside the timer. limsurf's
// rows take the thread count as argument
// (/1: single-threaded, as the peers; /2: two threads).
#include <vector>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "limsurf/refine/hierarchy.h"

namespace {

using limsurf::Index;

constexpr int levels = 2;

/// A torus of n×m quads (triangles: each quad split in two), positions on a ring.
struct Mesh {
    limsurf::Points positions;
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
    [[nodiscard]] int num_faces() const { return static_cast<int>(offsets.size()) - 1; }
};

Mesh make_torus(Index n, Index m, bool triangles) {
    Mesh mesh;
    mesh.positions.resize(n * m, 3);
    for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < n; ++i) {
            const double u = 2.0 * M_PI * i / n;
            const double v = 2.0 * M_PI * j / m;
            mesh.positions.row(j * n + i) << (2.0 + std::cos(v)) * std::cos(u), (2.0 + std::cos(v)) * std::sin(u),
                std::sin(v);
        }
    }
    auto id = [n, m](Index i, Index j) { return (j % m) * n + (i % n); };
    auto add = [&mesh](std::initializer_list<Index> face) {
        mesh.corners.insert(mesh.corners.end(), face);
        mesh.offsets.push_back(static_cast<Index>(mesh.corners.size()));
    };
    for (Index j = 0; j < m; ++j) {
        for (Index i = 0; i < n; ++i) {
            if (triangles) {
                add({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
                add({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
            } else {
                add({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            }
        }
    }
    return mesh;
}

const Mesh& quads() {
    static const Mesh mesh = make_torus(316, 316, false);  // 99 856 quads
    return mesh;
}

const Mesh& triangles() {
    static const Mesh mesh = make_torus(224, 224, true);  // 100 352 triangles
    return mesh;
}

void report(benchmark::State& state, const Mesh& mesh, double output_faces) {
    state.counters["input_faces"] = mesh.num_faces();
    state.counters["output_faces"] = output_faces;
}

// --- limsurf -----------------------------------------------------------------

/// @p scheme by `levels` steps; the benchmark's argument is the thread count
/// (RefineOptions::num_threads; 1 is the single-threaded row).
limsurf::RefineOptions limsurf_options(const benchmark::State& state, limsurf::SchemeKind scheme) {
    limsurf::RefineOptions options;
    options.scheme = scheme;
    options.levels = levels;
    options.num_threads = static_cast<int>(state.range(0));
    return options;
}

/// Times @p refine(base, options), which returns the number of faces of the finest level.
template <class Refine>
void limsurf_run(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme, const Refine& refine) {
    const limsurf::Topology base(static_cast<Index>(mesh.positions.rows()), mesh.offsets, mesh.corners);
    const limsurf::RefineOptions options = limsurf_options(state, scheme);
    double faces = 0;
    for (auto _ : state) {
        faces = refine(base, options);
    }
    report(state, mesh, faces);
}

/// The Hierarchy: every level's topology, S0 and provenance, then the positions as S0 products.
void limsurf_refine(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme) {
    limsurf_run(state, mesh, scheme, [&](const limsurf::Topology& base, const limsurf::RefineOptions& options) {
        const limsurf::Hierarchy hierarchy(base, options);
        const limsurf::Points x = hierarchy.positions(levels, mesh.positions);
        benchmark::DoNotOptimize(x.data());
        return hierarchy.topology(levels).num_faces();
    });
}

/// The Hierarchy built with the control points: every level's topology, S0, provenance and positions,
/// the positions carried as each step builds its rows (the same bits as the S0 products above).
void limsurf_refine_points(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme) {
    limsurf_run(state, mesh, scheme, [&](const limsurf::Topology& base, const limsurf::RefineOptions& options) {
        const limsurf::Hierarchy hierarchy(base, options, mesh.positions);
        benchmark::DoNotOptimize(hierarchy.positions(levels).data());
        return hierarchy.topology(levels).num_faces();
    });
}

/// The Hierarchy built with the control points, keeping of the level topologies only the finest level's
/// face list (KeptTopologies::FinestFaces): every S0, provenance and positions, as above; the finest
/// level as Far's default rows have it (its faces, no edges or one-rings).
void limsurf_refine_operators(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme) {
    limsurf_run(state, mesh, scheme, [&](const limsurf::Topology& base, limsurf::RefineOptions options) {
        options.kept_topologies = limsurf::KeptTopologies::FinestFaces;
        const limsurf::Hierarchy hierarchy(base, options, mesh.positions);
        benchmark::DoNotOptimize(hierarchy.positions(levels).data());
        return hierarchy.finest_faces().num_faces();
    });
}

/// refine_finest: the same topology and positions, only the finest level kept.
void limsurf_refine_finest(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme) {
    limsurf_run(state, mesh, scheme, [&](const limsurf::Topology& base, const limsurf::RefineOptions& options) {
        const limsurf::FinestLevel finest = limsurf::refine_finest(base, mesh.positions, options);
        benchmark::DoNotOptimize(finest.positions.data());
        return finest.topology.num_faces();
    });
}

/// refine_finest_faces: the same positions, the finest level's face list without its Topology (what
/// `limsurf subdivide` runs and writes; Far's default rows, without fullTopologyInLastLevel, likewise).
void limsurf_refine_faces(benchmark::State& state, const Mesh& mesh, limsurf::SchemeKind scheme) {
    limsurf_run(state, mesh, scheme, [&](const limsurf::Topology& base, const limsurf::RefineOptions& options) {
        const limsurf::FinestFaces finest = limsurf::refine_finest_faces(base, mesh.positions, options);
        benchmark::DoNotOptimize(finest.mesh.positions.data());
        return finest.mesh.num_faces();
    });
}

void BM_limsurf_CatmullClark(benchmark::State& state) {
    limsurf_refine(state, quads(), limsurf::SchemeKind::CatmullClark);
}
void BM_limsurf_Loop(benchmark::State& state) {
    limsurf_refine(state, triangles(), limsurf::SchemeKind::Loop);
}
void BM_limsurf_points_CatmullClark(benchmark::State& state) {
    limsurf_refine_points(state, quads(), limsurf::SchemeKind::CatmullClark);
}
void BM_limsurf_points_Loop(benchmark::State& state) {
    limsurf_refine_points(state, triangles(), limsurf::SchemeKind::Loop);
}
void BM_limsurf_points_DooSabin(benchmark::State& state) {
    limsurf_refine_points(state, quads(), limsurf::SchemeKind::DooSabin);
}
void BM_limsurf_operators_CatmullClark(benchmark::State& state) {
    limsurf_refine_operators(state, quads(), limsurf::SchemeKind::CatmullClark);
}
void BM_limsurf_operators_Loop(benchmark::State& state) {
    limsurf_refine_operators(state, triangles(), limsurf::SchemeKind::Loop);
}
void BM_limsurf_operators_DooSabin(benchmark::State& state) {
    limsurf_refine_operators(state, quads(), limsurf::SchemeKind::DooSabin);
}
void BM_limsurf_finest_CatmullClark(benchmark::State& state) {
    limsurf_refine_finest(state, quads(), limsurf::SchemeKind::CatmullClark);
}
void BM_limsurf_finest_Loop(benchmark::State& state) {
    limsurf_refine_finest(state, triangles(), limsurf::SchemeKind::Loop);
}
void BM_limsurf_faces_CatmullClark(benchmark::State& state) {
    limsurf_refine_faces(state, quads(), limsurf::SchemeKind::CatmullClark);
}
void BM_limsurf_faces_Loop(benchmark::State& state) {
    limsurf_refine_faces(state, triangles(), limsurf::SchemeKind::Loop);
}
void BM_limsurf_DooSabin(benchmark::State& state) {
    limsurf_refine(state, quads(), limsurf::SchemeKind::DooSabin);
}
void BM_limsurf_finest_DooSabin(benchmark::State& state) {
    limsurf_refine_finest(state, quads(), limsurf::SchemeKind::DooSabin);
}
void BM_limsurf_faces_DooSabin(benchmark::State& state) {
    limsurf_refine_faces(state, quads(), limsurf::SchemeKind::DooSabin);
}

// --- OpenSubdiv Far ----------------------------------------------------------------

struct OsdPoint {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(const OsdPoint& src, float w) {
        for (int k = 0; k < 3; ++k) {
            p[k] += static_cast<double>(w) * src.p[k];
        }
    }
};

/// @param full_topology the finest level with edges and one-rings too (UniformOptions::fullTopologyInLastLevel),
///   as limsurf's finest Topology has them; by default Far keeps only its face list.
void opensubdiv_refine(benchmark::State& state, const Mesh& mesh, OpenSubdiv::Sdc::SchemeType scheme,
                       bool full_topology = false) {
    using namespace OpenSubdiv;
    std::vector<int> degrees(static_cast<std::size_t>(mesh.num_faces()));
    for (int f = 0; f < mesh.num_faces(); ++f) {
        degrees[static_cast<std::size_t>(f)] =
            mesh.offsets[static_cast<std::size_t>(f) + 1] - mesh.offsets[static_cast<std::size_t>(f)];
    }
    Far::TopologyDescriptor descriptor;
    descriptor.numVertices = static_cast<int>(mesh.positions.rows());
    descriptor.numFaces = mesh.num_faces();
    descriptor.numVertsPerFace = degrees.data();
    descriptor.vertIndicesPerFace = mesh.corners.data();
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    double faces = 0;
    for (auto _ : state) {
        Far::TopologyRefiner* refiner = Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
            descriptor, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(scheme, sdc));
        Far::TopologyRefiner::UniformOptions uniform(levels);
        uniform.fullTopologyInLastLevel = full_topology;
        refiner->RefineUniform(uniform);
        std::vector<OsdPoint> points(static_cast<std::size_t>(refiner->GetNumVerticesTotal()));
        for (int v = 0; v < descriptor.numVertices; ++v) {
            points[static_cast<std::size_t>(v)] = {{mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)}};
        }
        Far::PrimvarRefiner primvar(*refiner);
        OsdPoint* src = points.data();
        for (int l = 1; l <= levels; ++l) {
            OsdPoint* dst = src + refiner->GetLevel(l - 1).GetNumVertices();
            primvar.Interpolate(l, src, dst);
            src = dst;
        }
        benchmark::DoNotOptimize(points.data());
        faces = refiner->GetLevel(levels).GetNumFaces();
        delete refiner;  // Far hands out an owning raw pointer
    }
    report(state, mesh, faces);
}

void BM_OpenSubdiv_CatmullClark(benchmark::State& state) {
    opensubdiv_refine(state, quads(), OpenSubdiv::Sdc::SCHEME_CATMARK);
}
void BM_OpenSubdiv_Loop(benchmark::State& state) {
    opensubdiv_refine(state, triangles(), OpenSubdiv::Sdc::SCHEME_LOOP);
}
void BM_OpenSubdiv_full_CatmullClark(benchmark::State& state) {
    opensubdiv_refine(state, quads(), OpenSubdiv::Sdc::SCHEME_CATMARK, true);
}
void BM_OpenSubdiv_full_Loop(benchmark::State& state) {
    opensubdiv_refine(state, triangles(), OpenSubdiv::Sdc::SCHEME_LOOP, true);
}

// --- CGAL ------------------------------------------------------------------------

using CgalMesh = CGAL::Surface_mesh<CGAL::Simple_cartesian<double>::Point_3>;

CgalMesh to_cgal(const Mesh& mesh) {
    CgalMesh out;
    std::vector<CgalMesh::Vertex_index> vertices;
    for (Eigen::Index v = 0; v < mesh.positions.rows(); ++v) {
        vertices.push_back(out.add_vertex({mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)}));
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
        std::vector<CgalMesh::Vertex_index> face;
        for (Index c = mesh.offsets[static_cast<std::size_t>(f)]; c < mesh.offsets[static_cast<std::size_t>(f) + 1];
             ++c) {
            face.push_back(vertices[static_cast<std::size_t>(mesh.corners[static_cast<std::size_t>(c)])]);
        }
        out.add_face(face);
    }
    return out;
}

template <class Subdivide>
void cgal_refine(benchmark::State& state, const Mesh& mesh, Subdivide subdivide) {
    const CgalMesh original = to_cgal(mesh);
    double faces = 0;
    for (auto _ : state) {
        state.PauseTiming();
        CgalMesh copy = original;
        state.ResumeTiming();
        subdivide(copy);
        benchmark::DoNotOptimize(copy.number_of_faces());
        faces = static_cast<double>(copy.number_of_faces());
    }
    report(state, mesh, faces);
}

void BM_CGAL_CatmullClark(benchmark::State& state) {
    cgal_refine(state, quads(), [](CgalMesh& m) {
        CGAL::Subdivision_method_3::CatmullClark_subdivision(m, CGAL::parameters::number_of_iterations(levels));
    });
}
void BM_CGAL_Loop(benchmark::State& state) {
    cgal_refine(state, triangles(), [](CgalMesh& m) {
        CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(levels));
    });
}
void BM_CGAL_DooSabin(benchmark::State& state) {
    cgal_refine(state, quads(), [](CgalMesh& m) {
        CGAL::Subdivision_method_3::DooSabin_subdivision(m, CGAL::parameters::number_of_iterations(levels));
    });
}

// --- OpenMesh --------------------------------------------------------------------------

template <class OmMesh, class Subdivider>
void openmesh_refine(benchmark::State& state, const Mesh& mesh) {
    OmMesh original;
    std::vector<typename OmMesh::VertexHandle> vertices;
    for (Eigen::Index v = 0; v < mesh.positions.rows(); ++v) {
        vertices.push_back(original.add_vertex(
            typename OmMesh::Point(mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2))));
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
        std::vector<typename OmMesh::VertexHandle> face;
        for (Index c = mesh.offsets[static_cast<std::size_t>(f)]; c < mesh.offsets[static_cast<std::size_t>(f) + 1];
             ++c) {
            face.push_back(vertices[static_cast<std::size_t>(mesh.corners[static_cast<std::size_t>(c)])]);
        }
        original.add_face(face);
    }
    double faces = 0;
    for (auto _ : state) {
        state.PauseTiming();
        OmMesh copy = original;
        Subdivider subdivider;
        state.ResumeTiming();
        subdivider.attach(copy);
        subdivider(levels);
        subdivider.detach();
        benchmark::DoNotOptimize(copy.n_faces());
        faces = static_cast<double>(copy.n_faces());
    }
    report(state, mesh, faces);
}

struct OmTraits : OpenMesh::DefaultTraits {
    using Point = OpenMesh::Vec3d;
};
using OmPoly = OpenMesh::PolyMesh_ArrayKernelT<OmTraits>;
using OmTri = OpenMesh::TriMesh_ArrayKernelT<OmTraits>;

void BM_OpenMesh_CatmullClark(benchmark::State& state) {
    openmesh_refine<OmPoly, OpenMesh::Subdivider::Uniform::CatmullClarkT<OmPoly, double>>(state, quads());
}
void BM_OpenMesh_Loop(benchmark::State& state) {
    openmesh_refine<OmTri, OpenMesh::Subdivider::Uniform::LoopT<OmTri, double>>(state, triangles());
}

}  // namespace

BENCHMARK(BM_limsurf_CatmullClark)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_points_CatmullClark)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_operators_CatmullClark)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_finest_CatmullClark)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_faces_CatmullClark)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenSubdiv_CatmullClark)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenSubdiv_full_CatmullClark)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CGAL_CatmullClark)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenMesh_CatmullClark)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_Loop)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_points_Loop)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_operators_Loop)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_finest_Loop)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_faces_Loop)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenSubdiv_Loop)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenSubdiv_full_Loop)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CGAL_Loop)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenMesh_Loop)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_DooSabin)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_points_DooSabin)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_operators_DooSabin)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_finest_DooSabin)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_limsurf_faces_DooSabin)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CGAL_DooSabin)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
