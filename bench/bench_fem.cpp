// The Galerkin layer: assembly of the plate bending stiffness on a 10 000-face control mesh against
// the Laplace–Beltrami stiffness on the same mesh (the yardstick: first derivatives only), the
// quadrature set-up, and the plate solve. No Debian package assembles on subdivision limit
// surfaces; the figure to beat next time is the throughput per quadrature point.
// docs/BENCHMARKS.md "Galerkin assembly".
#include <vector>

#include <benchmark/benchmark.h>

#include "limsurf/fem/galerkin.h"
#include "limsurf/fem/plate.h"
#include "limsurf/limit/limit_basis.h"

namespace {

using limsurf::Index;
using limsurf::Points;

struct Plate {
    limsurf::Topology topology;
    Points X;
};

/// 100 × 100 quads on [0, 10]².
const Plate& plate() {
    static const Plate p = [] {
        constexpr Index n = 100;
        Plate out;
        out.X.resize((n + 1) * (n + 1), 3);
        std::vector<std::vector<Index>> faces;
        for (Index j = 0; j <= n; ++j) {
            for (Index i = 0; i <= n; ++i) {
                out.X.row(j * (n + 1) + i) << 0.1 * static_cast<double>(i), 0.1 * static_cast<double>(j), 0.0;
                if (i < n && j < n) {
                    const Index a = j * (n + 1) + i;
                    faces.push_back({a, a + 1, a + n + 2, a + n + 1});
                }
            }
        }
        out.topology = limsurf::Topology::from_polygons((n + 1) * (n + 1), faces);
        return out;
    }();
    return p;
}

const limsurf::LimitSampler& sampler() {
    static const limsurf::LimitBasis basis(plate().topology, limsurf::SchemeKind::CatmullClark);
    static const limsurf::LimitSampler s(basis, limsurf::SamplerOptions{6, 0, 1});
    return s;
}

void BM_sampler_setup(benchmark::State& state) {
    const limsurf::LimitBasis basis(plate().topology, limsurf::SchemeKind::CatmullClark);
    for (auto _ : state) {
        const limsurf::LimitSampler s(basis, limsurf::SamplerOptions{6, 0, 1});
        benchmark::DoNotOptimize(s.num_samples());
    }
}

void BM_plate_bending_assembly(benchmark::State& state) {
    const auto& s = sampler();
    for (auto _ : state) {
        const limsurf::SparseMatrix K = limsurf::assemble_plate_bending(s, plate().X, limsurf::PlateMaterial{});
        benchmark::DoNotOptimize(K.nonZeros());
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(s.num_samples()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_laplace_beltrami_assembly(benchmark::State& state) {
    const auto& s = sampler();
    for (auto _ : state) {
        const limsurf::GalerkinMatrices m = limsurf::assemble_laplace_beltrami(s, plate().X);
        benchmark::DoNotOptimize(m.stiffness.nonZeros());
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(s.num_samples()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_plate_solve(benchmark::State& state) {
    const auto& s = sampler();
    const auto load = [](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), 1e4); };
    for (auto _ : state) {
        const limsurf::PlateSolution w = limsurf::solve_plate(plate().topology, s, plate().X, limsurf::PlateMaterial{},
                                                              limsurf::PlateSupport::SimplySupported, load);
        benchmark::DoNotOptimize(w.w.data());
    }
}

BENCHMARK(BM_sampler_setup)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_laplace_beltrami_assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_plate_bending_assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_plate_solve)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
