// The Galerkin layer: assembly of the plate bending stiffness on a 10 000-face control mesh against
// the Laplace–Beltrami stiffness on the same mesh (the yardstick: first derivatives only) and
// against the SEC layer on the same mesh (inner products M0, M1, M2 at level 3 and the Laplacian
// d0ᵀ M1 d0 from them), the quadrature set-up, the solves (Laplace–Beltrami, plate, SEC Poisson:
// factorisation and solve only, matrices built outside the timer) and the whole plate solve. No
// Debian package assembles on subdivision limit surfaces; the figure to beat next time is the
// throughput per quadrature point. Every benchmark reports the resident memory before its loop
// (base_MiB: the mesh, and the sampler where it uses one) and the peak during it (peak_MiB, the
// process's VmHWM reset before the loop). One thread throughout.
// docs/BENCHMARKS.md "Galerkin assembly".
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "limsurf/fem/galerkin.h"
#include "limsurf/fem/plate.h"
#include "limsurf/fem/shell.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/sec/operators.h"

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

/// A field of /proc/self/status in MiB ("VmRSS:", "VmHWM:"), 0 where there is none (not Linux).
double status_mib(const std::string& field) {
    std::ifstream status("/proc/self/status");
    std::string key;
    while (status >> key) {
        if (key == field) {
            double kib = 0.0;
            status >> kib;
            return kib / 1024.0;
        }
        status.ignore(4096, '\n');
    }
    return 0.0;
}

/// Resident memory around a benchmark's loop: made after the inputs are built, it notes the
/// resident set (base_MiB) and resets the peak (Linux ≥ 4.0: "5" to /proc/self/clear_refs), so
/// that report() gives the peak during the loop (peak_MiB).
class MemoryWatch {
  public:
    MemoryWatch() : base_(status_mib("VmRSS:")) { std::ofstream("/proc/self/clear_refs") << "5"; }
    void report(benchmark::State& state) const {
        state.counters["base_MiB"] = base_;
        state.counters["peak_MiB"] = status_mib("VmHWM:");
    }

  private:
    double base_;
};

const limsurf::LimitSampler& sampler() {
    static const limsurf::LimitBasis basis(plate().topology, limsurf::SchemeKind::CatmullClark);
    static const limsurf::LimitSampler s(basis, limsurf::SamplerOptions{6, 0, 1});
    return s;
}

void BM_sampler_setup(benchmark::State& state) {
    const limsurf::LimitBasis basis(plate().topology, limsurf::SchemeKind::CatmullClark);
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::LimitSampler s(basis, limsurf::SamplerOptions{6, 0, 1});
        benchmark::DoNotOptimize(s.num_samples());
    }
    memory.report(state);
}

void BM_plate_bending_assembly(benchmark::State& state) {
    const auto& s = sampler();
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::SparseMatrix K = limsurf::assemble_plate_bending(s, plate().X, limsurf::PlateMaterial{});
        benchmark::DoNotOptimize(K.nonZeros());
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(s.num_samples()), benchmark::Counter::kIsIterationInvariantRate);
    memory.report(state);
}

/// The shell stiffness (membrane + bending, 3 unknowns per vertex) of the same grid rolled onto a
/// cylinder of radius 10 (a curved surface: every term of the strains is non-zero).
void BM_shell_stiffness_assembly(benchmark::State& state) {
    const auto& s = sampler();
    Points X = plate().X;
    for (Index v = 0; v < X.rows(); ++v) {
        const double angle = X(v, 0) / 10.0;
        X.row(v) << 10.0 * std::sin(angle), X(v, 1), 10.0 * std::cos(angle);
    }
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::SparseMatrix K = limsurf::assemble_shell_stiffness(s, X, limsurf::ShellMaterial{});
        benchmark::DoNotOptimize(K.nonZeros());
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(s.num_samples()), benchmark::Counter::kIsIterationInvariantRate);
    memory.report(state);
}

void BM_laplace_beltrami_assembly(benchmark::State& state) {
    const auto& s = sampler();
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::GalerkinMatrices m = limsurf::assemble_laplace_beltrami(s, plate().X);
        benchmark::DoNotOptimize(m.stiffness.nonZeros());
    }
    state.counters["points_per_s"] =
        benchmark::Counter(static_cast<double>(s.num_samples()), benchmark::Counter::kIsIterationInvariantRate);
    memory.report(state);
}

/// SEC at level 3 (the default patch assembly), one thread, as the FEM assembly.
limsurf::InnerProductOptions sec_options() {
    limsurf::InnerProductOptions options;
    options.method = limsurf::InnerProductMethod::Sec;
    options.level = 3;
    options.num_threads = 1;
    return options;
}

void BM_sec_inner_products(benchmark::State& state) {
    (void)plate();
    limsurf::InnerProducts ip;
    const MemoryWatch memory;
    for (auto _ : state) {
        ip = limsurf::control_inner_products(plate().topology, plate().X, limsurf::SchemeKind::CatmullClark,
                                             sec_options());
        benchmark::DoNotOptimize(ip.M1.nonZeros());
    }
    state.counters["M1_nonzeros"] = static_cast<double>(ip.M1.nonZeros());
    memory.report(state);
}

void BM_sec_laplacian(benchmark::State& state) {
    // The SEC Laplacian d0ᵀ M1 d0 (the Laplace–Beltrami stiffness's counterpart), inner products included.
    (void)plate();
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::Operators ops(plate().topology,
                                     limsurf::control_inner_products(plate().topology, plate().X,
                                                                     limsurf::SchemeKind::CatmullClark, sec_options()));
        const limsurf::SparseMatrix L = ops.laplacian();
        benchmark::DoNotOptimize(L.nonZeros());
    }
    memory.report(state);
}

/// The simply supported / Dirichlet-zero problem with matrices @p m: factorisation and solve only.
void galerkin_solve(benchmark::State& state, const limsurf::GalerkinMatrices& m) {
    const Eigen::VectorXd b = m.mass * Eigen::VectorXd::Constant(m.mass.rows(), 1e4);  // b = M p, p uniform
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.mass.rows());
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::GalerkinPoissonSolution u = limsurf::solve_galerkin_poisson(plate().topology, m, b, zero);
        benchmark::DoNotOptimize(u.u.data());
    }
    state.SetLabel(std::string(limsurf::sparse_cholesky_name()) + ", " + std::to_string(m.stiffness.nonZeros()) +
                   " non-zeros");
    memory.report(state);
}

void BM_laplace_beltrami_solve(benchmark::State& state) {
    galerkin_solve(state, limsurf::assemble_laplace_beltrami(sampler(), plate().X));
}

void BM_plate_system_solve(benchmark::State& state) {
    // The simply supported plate's system (boundary control values 0), through the same elimination
    // of fixed values and sparse Cholesky as solve_plate.
    limsurf::GalerkinMatrices m = limsurf::assemble_laplace_beltrami(sampler(), plate().X);
    m.stiffness = limsurf::assemble_plate_bending(sampler(), plate().X, limsurf::PlateMaterial{});
    galerkin_solve(state, m);
}

void BM_sec_poisson_solve(benchmark::State& state) {
    const limsurf::Operators ops(
        plate().topology,
        limsurf::control_inner_products(plate().topology, plate().X, limsurf::SchemeKind::CatmullClark, sec_options()));
    limsurf::PoissonProblem problem;
    problem.f = Eigen::VectorXd::Constant(plate().X.rows(), 1e4);
    problem.boundary_values = Eigen::VectorXd::Zero(plate().X.rows());
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::PoissonSolution u = limsurf::solve_poisson(plate().topology, ops, problem);
        benchmark::DoNotOptimize(u.u.data());
    }
    state.SetLabel(std::string(limsurf::sparse_cholesky_name()) + ", " + std::to_string(ops.laplacian().nonZeros()) +
                   " non-zeros");
    memory.report(state);
}

void BM_plate_solve(benchmark::State& state) {
    const auto& s = sampler();
    const auto load = [](const Points& P) { return Eigen::VectorXd::Constant(P.rows(), 1e4); };
    const MemoryWatch memory;
    for (auto _ : state) {
        const limsurf::PlateSolution w = limsurf::solve_plate(plate().topology, s, plate().X, limsurf::PlateMaterial{},
                                                              limsurf::PlateSupport::SimplySupported, load);
        benchmark::DoNotOptimize(w.w.data());
    }
    memory.report(state);
}

BENCHMARK(BM_sampler_setup)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_laplace_beltrami_assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_plate_bending_assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_shell_stiffness_assembly)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_sec_inner_products)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_sec_laplacian)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_laplace_beltrami_solve)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_plate_system_solve)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_sec_poisson_solve)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_plate_solve)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
