// Building the control-mesh topology: limsurf's Topology (and full
// validation) against OpenSubdiv's Far::TopologyRefiner, on the same faces.
//
// Both build compressed incidence tables with ordered one-rings; limsurf also
// checks manifoldness, orientation and isolated vertices and computes boundary
// loops and components, which OpenSubdiv does not.
#include <vector>

#include <benchmark/benchmark.h>

#include "limsurf/mesh/topology.h"
#include "limsurf/mesh/validate.h"

#ifdef LIMSURF_HAVE_OPENSUBDIV
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>
#endif

namespace {

using limsurf::Index;

/// An n×n quad torus: n² vertices and faces, every vertex of valence 4.
struct Torus {
    Index num_vertices = 0;
    std::vector<Index> offsets{0};
    std::vector<Index> corners;
};

Torus make_torus(Index n) {
    Torus torus;
    torus.num_vertices = n * n;
    auto id = [n](Index i, Index j) { return (j % n) * n + (i % n); };
    for (Index j = 0; j < n; ++j) {
        for (Index i = 0; i < n; ++i) {
            torus.corners.insert(torus.corners.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
            torus.offsets.push_back(static_cast<Index>(torus.corners.size()));
        }
    }
    return torus;
}

void BM_limsurf_Topology(benchmark::State& state) {
    const Torus torus = make_torus(static_cast<Index>(state.range(0)));
    for (auto _ : state) {
        limsurf::Topology topology(torus.num_vertices, torus.offsets, torus.corners);
        benchmark::DoNotOptimize(topology.num_edges());
    }
    state.counters["faces"] = static_cast<double>(torus.offsets.size() - 1);
    state.counters["faces/s"] = benchmark::Counter(static_cast<double>(torus.offsets.size() - 1),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}

void BM_limsurf_validate(benchmark::State& state) {
    const Torus torus = make_torus(static_cast<Index>(state.range(0)));
    limsurf::PolygonSoup soup;
    soup.positions = limsurf::Points::Random(torus.num_vertices, 3);
    soup.face_offsets = torus.offsets;
    soup.face_vertices = torus.corners;
    for (auto _ : state) {
        const limsurf::ValidationReport report = limsurf::validate(soup);
        benchmark::DoNotOptimize(report.issues.size());
    }
    state.counters["faces"] = static_cast<double>(torus.offsets.size() - 1);
}

#ifdef LIMSURF_HAVE_OPENSUBDIV
void BM_OpenSubdiv_TopologyRefiner(benchmark::State& state) {
    using namespace OpenSubdiv;
    const Torus torus = make_torus(static_cast<Index>(state.range(0)));
    std::vector<int> vertices_per_face(torus.offsets.size() - 1, 4);
    Far::TopologyDescriptor descriptor;
    descriptor.numVertices = torus.num_vertices;
    descriptor.numFaces = static_cast<int>(vertices_per_face.size());
    descriptor.numVertsPerFace = vertices_per_face.data();
    descriptor.vertIndicesPerFace = torus.corners.data();
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
    const Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options options(Sdc::SCHEME_CATMARK, sdc);
    for (auto _ : state) {
        Far::TopologyRefiner* refiner =
            Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(descriptor, options);
        benchmark::DoNotOptimize(refiner->GetLevel(0).GetNumEdges());
        delete refiner;  // OpenSubdiv's API hands out an owning raw pointer
    }
    state.counters["faces"] = static_cast<double>(vertices_per_face.size());
    state.counters["faces/s"] = benchmark::Counter(static_cast<double>(vertices_per_face.size()),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_OpenSubdiv_TopologyRefiner)->Arg(128)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);
#endif

BENCHMARK(BM_limsurf_Topology)->Arg(128)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_limsurf_validate)->Arg(128)->Arg(512)->Arg(1024)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
