// Subdivision Exterior Calculus: assembling the inner products M0, M1, M2 of a ~10k-face control
// mesh with SEC at level 3 (Eq. 12), against polygonal DEC on the same control mesh and DEC
// assembled directly on the level-3 mesh; the sparse factorisation and solve of the Poisson
// problem. No peer library has SEC inner products; the DEC assemblies are the yardsticks the
// issue names.
//
//   DecControl         polygonal_inner_products(control mesh)
//   DecLevel3          polygonal_inner_products(level-3 mesh), positions precomputed
//   SecLevel3          control_inner_products(Sec, L = 3), the default patch assembly, everything
//                      included; second argument: threads
//   SecLevel3Hierarchy the same by SecAssembly::Hierarchy (refine with forms, pull back level by level)
//   PoissonSec         solve_poisson with the SEC operators (factorisation + solve)
//   counters: nonzeros of the assembled M1, peak resident memory (VmHWM, MiB) after the run
//
// Meshes: genus2 refined 4 times by Catmull–Clark (12 800 quads, valences 3 and 5);
//         tri_valence_7 refined 4 times by Loop (10 752 triangles, valences 5 and 7).
#include <fstream>
#include <string>

#include <benchmark/benchmark.h>

#include "bench_heap.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/sec/operators.h"

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

/// Peak resident set size of the process in MiB (Linux /proc/self/status VmHWM).
double peak_mib() {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == "VmHWM:") {
            double kib = 0.0;
            status >> kib;
            return kib / 1024.0;
        }
        status.ignore(4096, '\n');
    }
    return 0.0;
}

void label(benchmark::State& state, const Mesh& m) {
    state.SetLabel(std::string(m.scheme == SchemeKind::Loop ? "loop " : "catmull-clark ") +
                   std::to_string(m.topology.num_faces()) + " faces");
}

void BM_DecControl(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::InnerProducts ip;
    for (auto _ : state) {
        ip = limsurf::polygonal_inner_products(m.topology, m.X);
        benchmark::DoNotOptimize(ip.M1.nonZeros());
    }
    state.counters["M1_nonzeros"] = static_cast<double>(ip.M1.nonZeros());
    label(state, m);
}

void BM_DecLevel3(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::RefineOptions options;
    options.scheme = m.scheme;
    options.levels = 3;
    const limsurf::Hierarchy h(m.topology, options);
    const limsurf::Points X3 = h.positions(3, m.X);
    limsurf::InnerProducts ip;
    for (auto _ : state) {
        ip = limsurf::polygonal_inner_products(h.topology(3), X3);
        benchmark::DoNotOptimize(ip.M1.nonZeros());
    }
    state.counters["M1_nonzeros"] = static_cast<double>(ip.M1.nonZeros());
    label(state, m);
}

void sec_level3(benchmark::State& state, limsurf::SecAssembly assembly, int threads) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::InnerProductOptions options;
    options.method = limsurf::InnerProductMethod::Sec;
    options.level = 3;
    options.assembly = assembly;
    options.num_threads = threads;
    limsurf::InnerProducts ip;
    for (auto _ : state) {
        ip = limsurf::control_inner_products(m.topology, m.X, m.scheme, options);
        benchmark::DoNotOptimize(ip.M1.nonZeros());
    }
    state.counters["M1_nonzeros"] = static_cast<double>(ip.M1.nonZeros());
    state.counters["peak_MiB"] = peak_mib();
    label(state, m);
}

void BM_SecLevel3(benchmark::State& state) {
    sec_level3(state, limsurf::SecAssembly::Patches, static_cast<int>(state.range(1)));
}

void BM_SecLevel3Hierarchy(benchmark::State& state) {
    sec_level3(state, limsurf::SecAssembly::Hierarchy, 0);
}

/// load_vector at L = 3 of f = sin x + yz (what `limsurf poisson --rhs` integrates), by the ring
/// stencils (range 1 = 0) or through the whole hierarchy (1).
void BM_LoadVector(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::InnerProductOptions options;
    options.level = 3;
    options.assembly = state.range(1) == 0 ? limsurf::SecAssembly::Patches : limsurf::SecAssembly::Hierarchy;
    const auto f = [](const limsurf::Points& P) {
        return (P.col(0).array().sin() + P.col(1).array() * P.col(2).array()).matrix().eval();
    };
    Eigen::VectorXd b;
    for (auto _ : state) {
        b = limsurf::load_vector(m.topology, m.X, m.scheme, options, f);
        benchmark::DoNotOptimize(b.data());
    }
    state.counters["peak_MiB"] = peak_mib();
    label(state, m);
}

void BM_PoissonSec(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    limsurf::InnerProductOptions options;
    options.level = 3;
    const limsurf::Operators ops(m.topology, limsurf::control_inner_products(m.topology, m.X, m.scheme, options));
    limsurf::PoissonProblem problem;
    problem.f = m.X.col(2);
    for (auto _ : state) {
        const auto solution = limsurf::solve_poisson(m.topology, ops, problem);
        benchmark::DoNotOptimize(solution.u.data());
    }
    state.SetLabel(std::string(limsurf::sparse_cholesky_name()));
}

BENCHMARK(BM_DecControl)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DecLevel3)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SecLevel3)
    ->Args({0, 1})
    ->Args({0, 2})
    ->Args({1, 1})
    ->Args({1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SecLevel3Hierarchy)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LoadVector)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_PoissonSec)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    limsurf::bench::prefault_heap(3.5);  // the hierarchy route of SEC at level 3 peaks near 3 GiB
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
