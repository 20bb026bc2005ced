// C2g0 refinement and limit evaluation next to Loop on the same triangle meshes (no peer
// implements C2g0: Loop, the same triangle split with a smaller stencil and quartic patches, is
// the yardstick). docs/BENCHMARKS.md "C2g0".
//
// Meshes: a 224 × 224 regular triangle torus (100 352 triangles, all valence 6) and the
// tetrahedron split 1-to-4 seven times (65 536 triangles, four valence-3 vertices), positions on
// the unit sphere.
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "limsurf/limit/limit_basis.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"

namespace {

using limsurf::Index;
using limsurf::Points;
using limsurf::SchemeKind;
using limsurf::Topology;

struct Mesh {
    Topology topology;
    Points positions;
};

Mesh torus() {
    constexpr Index n = 224;
    const auto id = [](Index i, Index j) { return ((i + n) % n) * n + (j + n) % n; };
    std::vector<std::vector<Index>> faces;
    Points X(n * n, 3);
    for (Index i = 0; i < n; ++i) {
        for (Index j = 0; j < n; ++j) {
            const double u = 2.0 * M_PI * static_cast<double>(i) / n;
            const double v = 2.0 * M_PI * static_cast<double>(j) / n;
            X.row(id(i, j)) << (2.0 + std::cos(v)) * std::cos(u), (2.0 + std::cos(v)) * std::sin(u), std::sin(v);
            faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    }
    return {Topology::from_polygons(n * n, faces), X};
}

Mesh sphere() {
    Topology t = Topology::from_polygons(4, {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
    Points X(4, 3);
    X << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
    for (int l = 0; l < 7; ++l) {
        limsurf::Level level = limsurf::refine_linear(t);
        X = level.S0 * X;
        t = std::move(level.topology);
    }
    X.rowwise().normalize();
    return {t, X};
}

const Mesh& mesh(int which) {
    static const Mesh meshes[2] = {torus(), sphere()};
    return meshes[which];
}

void refine_two_levels(benchmark::State& state, SchemeKind scheme) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::RefineOptions options;
    options.scheme = scheme;
    options.levels = 2;
    options.num_threads = 1;  // single-threaded, as every row of docs/BENCHMARKS.md unless it says
    for (auto _ : state) {
        const limsurf::Hierarchy hierarchy(m.topology, options);
        const Points x = hierarchy.positions(2, m.positions);
        benchmark::DoNotOptimize(x.data());
    }
    state.counters["input_faces"] = static_cast<double>(m.topology.num_faces());
}

/// Warm evaluation (second derivatives) of 200 000 random points, set-up outside the timer.
void evaluate(benchmark::State& state, SchemeKind scheme) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::LimitBasis basis(m.topology, scheme);
    std::mt19937_64 random(20261201);
    std::uniform_int_distribution<Index> face(0, m.topology.num_faces() - 1);
    std::uniform_real_distribution<double> uv(0.0, 1.0);
    std::vector<limsurf::SurfacePoint> points(200000);
    for (auto& p : points) {
        p = {face(random), uv(random), uv(random)};
        if (p.u + p.v > 1.0) {
            p.u = 1.0 - p.u;
            p.v = 1.0 - p.v;
        }
    }
    limsurf::LimitWeights w;
    for (const auto& p : points) {  // warm the caches of irregular patches
        basis.evaluate(p, w);
    }
    for (auto _ : state) {
        for (const auto& p : points) {
            basis.evaluate(p, w);
            benchmark::DoNotOptimize(w.w.data());
        }
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(points.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_refine_C2g0(benchmark::State& s) {
    refine_two_levels(s, SchemeKind::C2g0);
}
void BM_refine_Loop(benchmark::State& s) {
    refine_two_levels(s, SchemeKind::Loop);
}
void BM_evaluate_C2g0(benchmark::State& s) {
    evaluate(s, SchemeKind::C2g0);
}
void BM_evaluate_Loop(benchmark::State& s) {
    evaluate(s, SchemeKind::Loop);
}

// Argument: 0 = torus, 1 = sphere.
BENCHMARK(BM_refine_C2g0)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_refine_Loop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_evaluate_C2g0)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_evaluate_Loop)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
