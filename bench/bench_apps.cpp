// The SEC applications (SEC §4.2): heat-method geodesics on a ~10k-face control mesh, SEC (L = 3)
// and IGA against DEC on the same control mesh, and the heat method with DEC on the control mesh subdivided
// 1, 2 and 3 times (the paper's reference is level 3). No peer library has SEC operators (and
// geometry-central / libigl are not in Debian): the DEC computations are the yardsticks the issue
// names.
//
//   GeodesicSetup/method/mesh      HeatGeodesics construction: inner products, operators, gradient
//                                  mesh and the Cholesky factorisations (counters: setup_s, factor_s)
//   GeodesicSolve/method/mesh      one distance() from a prefactorised HeatGeodesics (a new source
//                                  each iteration)
//   GeodesicBatch/method/mesh      distances() of 16 single-source sets per call (counter per_source:
//                                  seconds per set)
//   GeodesicSubdivided/level/mesh  DEC heat method on the control mesh subdivided `level` times:
//                                  refinement, set-up, factorisation and one solve (level 3: the
//                                  reference of `--reference-level 3`)
//   method: 0 dec, 1 sec (L = 3, limit gradient: the default), 2 sec (L = 3, gradient on level 3),
//           3 sec (L = 3, gradient on level 1), 4 iga (degree 8, 6 tile levels; limit gradient)
//
// Meshes: genus2 refined 4 times by Catmull–Clark (12 800 quads);
//         tri_valence_7 refined 4 times by Loop (10 752 triangles).
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "limsurf/apps/geodesics.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"

namespace {

using limsurf::SchemeKind;

struct Mesh {
    limsurf::Topology topology;
    limsurf::Points X;
    SchemeKind scheme;
};

Mesh control_mesh(const char* name, SchemeKind scheme) {
    const auto built = limsurf::read_mesh(std::string(LIMSURF_MESH_DIR) + "/" + name);
    limsurf::RefineOptions options;
    options.scheme = scheme;
    options.levels = 4;
    const limsurf::Hierarchy h(built.mesh.topology(), options);
    return {h.topology(4), h.positions(4, built.mesh.positions()), scheme};
}

const Mesh& mesh(int which) {
    static const Mesh cc = control_mesh("genus2.obj", SchemeKind::CatmullClark);
    static const Mesh loop = control_mesh("tri_valence_7.obj", SchemeKind::Loop);
    return which == 0 ? cc : loop;
}

limsurf::HeatGeodesicsOptions options_for(int method) {
    limsurf::HeatGeodesicsOptions options;
    options.method = method == 0   ? limsurf::LaplacianMethod::Dec
                     : method == 4 ? limsurf::LaplacianMethod::Iga
                                   : limsurf::LaplacianMethod::Sec;
    options.level = 3;
    if (method == 2 || method == 3) {
        options.gradient = limsurf::HeatGradient::Subdivided;
        options.gradient_level = method == 2 ? 3 : 1;
    }
    return options;
}

const char* method_name(int method) {
    return method == 0   ? "dec"
           : method == 1 ? "sec, limit gradient"
           : method == 2 ? "sec, gradient level 3"
           : method == 3 ? "sec, gradient level 1"
                         : "iga";
}

void label(benchmark::State& state, const Mesh& m, const std::string& what) {
    state.SetLabel(what + (m.scheme == SchemeKind::Loop ? ", loop " : ", catmull-clark ") +
                   std::to_string(m.topology.num_faces()) + " faces");
}

void BM_GeodesicSetup(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(1)));
    const limsurf::HeatGeodesicsOptions options = options_for(static_cast<int>(state.range(0)));
    double setup = 0.0, factor = 0.0;
    for (auto _ : state) {
        const limsurf::HeatGeodesics heat(m.topology, m.X, m.scheme, options);
        setup = heat.setup_seconds();
        factor = heat.factorisation_seconds();
        benchmark::DoNotOptimize(heat.time_step());
    }
    state.counters["setup_s"] = setup;
    state.counters["factor_s"] = factor;
    label(state, m, method_name(static_cast<int>(state.range(0))));
}

void BM_GeodesicSolve(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(1)));
    const limsurf::HeatGeodesics heat(m.topology, m.X, m.scheme, options_for(static_cast<int>(state.range(0))));
    limsurf::Index source = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(heat.distance({source}).data());
        source = (source + 997) % m.topology.num_vertices();
    }
    state.counters["gradient_elements"] = static_cast<double>(heat.gradient_elements());
    label(state, m, method_name(static_cast<int>(state.range(0))));
}

void BM_GeodesicBatch(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(1)));
    const limsurf::HeatGeodesics heat(m.topology, m.X, m.scheme, options_for(static_cast<int>(state.range(0))));
    constexpr int batch = 16;
    limsurf::Index source = 0;
    for (auto _ : state) {
        std::vector<std::vector<limsurf::Index>> sets(batch);
        for (auto& set : sets) {
            set = {source};
            source = (source + 997) % m.topology.num_vertices();
        }
        benchmark::DoNotOptimize(heat.distances(sets).data());
    }
    // Seconds per source set (the time per iteration divided by the batch).
    state.counters["per_source"] =
        benchmark::Counter(batch, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
    label(state, m, std::string(method_name(static_cast<int>(state.range(0)))) + ", 16 sources per call");
}

void BM_GeodesicSubdivided(benchmark::State& state) {
    const int level = static_cast<int>(state.range(0));
    const Mesh& m = mesh(static_cast<int>(state.range(1)));
    limsurf::Index vertices = 0;
    for (auto _ : state) {
        limsurf::RefineOptions refine;
        refine.scheme = m.scheme;
        refine.levels = level;
        const limsurf::Hierarchy h(m.topology, refine);
        limsurf::HeatGeodesicsOptions options = options_for(0);
        const limsurf::HeatGeodesics heat(h.topology(level), h.positions(level, m.X), m.scheme, options);
        benchmark::DoNotOptimize(heat.distance({0}).data());
        vertices = h.topology(level).num_vertices();
    }
    state.counters["vertices"] = static_cast<double>(vertices);
    label(state, m, "dec on level " + std::to_string(level));
}

}  // namespace

BENCHMARK(BM_GeodesicSetup)->ArgsProduct({{0, 1, 2, 4}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GeodesicSolve)->ArgsProduct({{0, 1, 2, 3, 4}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GeodesicBatch)->ArgsProduct({{0, 1, 4}, {0, 1}})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GeodesicSubdivided)
    ->ArgsProduct({{1, 2, 3}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

BENCHMARK_MAIN();
