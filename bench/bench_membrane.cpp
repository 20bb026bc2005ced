// Shape functionals of the membrane layer (c2g0-sphere-scheme-biomembranes §3): one evaluation of
// W, A, V and M with their gradients, the work of every Ipopt iterate, on control meshes of about
// 10k vertices (the target: <= 10 ms wall on 2 cores). No peer library evaluates these
// functionals of a subdivision limit surface; Surface Evolver's solve time is compared by
// tests/membrane/evolver_canham.py (docs/BENCHMARKS.md).
//
//   ShapeEval/scheme/threads   evaluate(X, {W, A, V, M}) (counters: vertices, samples, elements
//                              evaluated by sum factorisation)
//   ShapeEvalDense/scheme/threads  the same for Catmull–Clark with every element dense
//   ShapeSetup/scheme          ShapeFunctionals construction (sampler with second derivatives)
//   ShapeHessian/mesh/threads  hessian(X, W + A + V + M), the work of a Newton iterate
//                              (MembraneHessian::Exact); ShapeEval of the same mesh beside it
//   mesh 4: C2g0 tetra_3 as it is (130 vertices: F_tetra,3 of Figs. 11–13)
//   scheme: 0 C2g0 (tetra_4 refined twice: 8194 vertices), 1 Loop (icosahedron refined 5 times:
//           10242 vertices), 2 Catmull–Clark (sphere_quads refined 3 times: 6146 vertices),
//           3 Catmull–Clark at more than 10k vertices (genus2 refined 4 times: 12798 vertices; its
//           own shape, not projected onto the sphere)
#include <array>
#include <string>
#include <utility>

#include <benchmark/benchmark.h>

#include "limsurf/io/mesh_io.h"
#include "limsurf/membrane/shape_functionals.h"
#include "limsurf/refine/hierarchy.h"

namespace {

using limsurf::SchemeKind;

struct Mesh {
    limsurf::Topology topology;
    limsurf::Points X;
    SchemeKind scheme;
};

Mesh refined(const char* name, SchemeKind scheme, int levels, bool onto_sphere = true) {
    const auto built = limsurf::read_mesh(std::string(LIMSURF_MESH_DIR) + "/" + name);
    limsurf::RefineOptions options;
    options.scheme = scheme;
    options.levels = levels;
    const limsurf::Hierarchy h(built.mesh.topology(), options);
    limsurf::Points X = h.positions(levels, built.mesh.positions());
    if (onto_sphere) {
        X.rowwise().normalize();
    }
    return {h.topology(levels), std::move(X), scheme};
}

const Mesh& mesh(int which) {
    static const Mesh c2g0 = refined("tetra_4.obj", SchemeKind::C2g0, 2);
    static const Mesh loop = refined("icosahedron.obj", SchemeKind::Loop, 5);
    static const Mesh cc = refined("sphere_quads.obj", SchemeKind::CatmullClark, 3);
    static const Mesh cc_genus2 = refined("genus2.obj", SchemeKind::CatmullClark, 4, false);
    static const Mesh tetra_3 = refined("tetra_3.obj", SchemeKind::C2g0, 0);
    return which == 0 ? c2g0 : which == 1 ? loop : which == 2 ? cc : which == 3 ? cc_genus2 : tetra_3;
}

const char* scheme_label(int which) {
    return which == 0   ? "c2g0"
           : which == 1 ? "loop"
           : which == 2 ? "catmull-clark"
           : which == 3 ? "catmull-clark genus2"
                        : "c2g0 tetra_3";
}

void evaluate(benchmark::State& state, bool sum_factorisation) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::LimitBasis basis(m.topology, m.scheme);
    limsurf::ShapeOptions options;
    options.num_threads = static_cast<int>(state.range(1));
    options.sum_factorisation = sum_factorisation;
    const limsurf::ShapeFunctionals functionals(basis, options);
    constexpr std::array<limsurf::ShapeFunctional, 4> terms{
        limsurf::ShapeFunctional::Willmore, limsurf::ShapeFunctional::Area, limsurf::ShapeFunctional::Volume,
        limsurf::ShapeFunctional::MeanCurvature};
    for (auto _ : state) {
        benchmark::DoNotOptimize(functionals.evaluate(m.X, terms));
    }
    state.counters["vertices"] = static_cast<double>(m.X.rows());
    state.counters["samples"] = static_cast<double>(functionals.num_samples());
    state.counters["factorised"] = static_cast<double>(functionals.num_sum_factorised_elements());
    state.SetLabel(scheme_label(static_cast<int>(state.range(0))));
}

void ShapeEval(benchmark::State& state) {
    evaluate(state, true);
}
BENCHMARK(ShapeEval)->ArgsProduct({{0, 1, 2, 3, 4}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

// Catmull–Clark with every element through its dense kernel (ShapeOptions::sum_factorisation off).
void ShapeEvalDense(benchmark::State& state) {
    evaluate(state, false);
}
BENCHMARK(ShapeEvalDense)->ArgsProduct({{2, 3}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void ShapeHessian(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::LimitBasis basis(m.topology, m.scheme);
    limsurf::ShapeOptions options;
    options.num_threads = static_cast<int>(state.range(1));
    const limsurf::ShapeFunctionals functionals(basis, options);
    const limsurf::ShapeCoefficients weights{1.0, 1.0, 1.0, 1.0, 0.0, 0.0};  // A, V, M, W
    limsurf::Index entries = 0;
    for (auto _ : state) {
        const limsurf::SparseMatrix H = functionals.hessian(m.X, weights);
        entries = static_cast<limsurf::Index>(H.nonZeros());
        benchmark::DoNotOptimize(H.valuePtr());
    }
    state.counters["vertices"] = static_cast<double>(m.X.rows());
    state.counters["entries"] = static_cast<double>(entries);
    state.SetLabel(scheme_label(static_cast<int>(state.range(0))));
}
BENCHMARK(ShapeHessian)->ArgsProduct({{4, 0}, {1, 2}})->Unit(benchmark::kMillisecond)->UseRealTime();

void ShapeSetup(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::LimitBasis basis(m.topology, m.scheme);
    for (auto _ : state) {
        benchmark::DoNotOptimize(limsurf::ShapeFunctionals(basis));
    }
    state.SetLabel(scheme_label(static_cast<int>(state.range(0))));
}
BENCHMARK(ShapeSetup)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
