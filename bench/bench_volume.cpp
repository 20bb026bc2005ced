// Exact enclosed volume (trilinear forms) of ~1M-face control meshes, against reaching the
// same accuracy by subdividing: OpenSubdiv Far refining uniformly (Catmull–Clark, Loop) and
// the polyhedral volume of each level; limsurf's own refinement for Doo–Sabin (no peer).
//
//   setup      EnclosedVolume(topology, scheme): classify faces, subdivide irregular ones locally
//   volume     EnclosedVolume::volume(X), 1 and 2 threads
//   gradient   EnclosedVolume::gradient(X), 2 threads
//   subdivide  level l by OpenSubdiv (TopologyRefiner + PrimvarRefiner, from the control mesh)
//              and the polyhedral volume of level l; counters: its relative error against the exact
//              volume, and the levels plain subdivision (and one Richardson step) would need for 1e-9
//              at the measured rate
//
// Meshes (closed; built outside every timer):
//   cc_torus     1000 × 1000 quads, no extraordinary vertex: every face is a facet as it stands
//   cc_dense     a 410 × 410 × 2 triangle torus refined once by Catmull–Clark: 1 008 600 quads, each
//                with two extraordinary corners (valence 3 and 6), so every face is subdivided locally
//   loop_torus   700 × 700 × 2 triangles, regular
//   loop_ico     the icosahedron refined 8 times by Loop: 1 310 720 triangles, 12 valence-5 vertices
//   ds_torus     1000 × 1000 quads under Doo–Sabin
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opensubdiv/far/primvarRefiner.h>

#include "../tests/support/opensubdiv_refiner.h"
#include "bench_heap.h"
#include "limsurf/io/obj.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/refine/refine.h"
#include "limsurf/volume/enclosed_volume.h"

namespace {

using limsurf::Index;
using limsurf::SchemeKind;
namespace Far = OpenSubdiv::Far;

struct Mesh {
    limsurf::Topology topology;
    limsurf::Points X;
    SchemeKind scheme = SchemeKind::CatmullClark;
    double exact = 0.0;
};

/// An n × n torus of quads, or of triangles (each quad split along a diagonal).
Mesh torus(Index n, bool triangles, SchemeKind scheme) {
    Mesh mesh;
    mesh.scheme = scheme;
    mesh.X.resize(n * n, 3);
    std::vector<std::vector<Index>> faces;
    for (Index j = 0; j < n; ++j) {
        for (Index i = 0; i < n; ++i) {
            const double u = 2.0 * M_PI * i / n;
            const double v = 2.0 * M_PI * j / n;
            mesh.X.row(j * n + i) << (2.0 + 0.7 * std::cos(v)) * std::cos(u), (2.0 + 0.7 * std::cos(v)) * std::sin(u),
                0.7 * std::sin(v) + 0.05 * std::cos(3 * u);
            const Index a = j * n + i;
            const Index b = j * n + (i + 1) % n;
            const Index c = ((j + 1) % n) * n + (i + 1) % n;
            const Index d = ((j + 1) % n) * n + i;
            if (triangles) {
                faces.push_back({a, b, c});
                faces.push_back({a, c, d});
            } else {
                faces.push_back({a, b, c, d});
            }
        }
    }
    mesh.topology = limsurf::Topology::from_polygons(n * n, faces);
    return mesh;
}

Mesh icosahedron_refined(int levels) {
    const auto built = limsurf::build_control_mesh(limsurf::read_obj(LIMSURF_MESH_DIR "/icosahedron.obj"));
    limsurf::RefineOptions options;
    options.scheme = SchemeKind::Loop;
    options.levels = levels;
    const limsurf::Hierarchy hierarchy(built.mesh.topology(), options);
    return {hierarchy.topology(levels), hierarchy.positions(levels, built.mesh.positions()), SchemeKind::Loop, 0.0};
}

Mesh& with_exact(Mesh& mesh) {
    mesh.exact = limsurf::EnclosedVolume(mesh.topology, mesh.scheme).volume(mesh.X);
    return mesh;
}

const Mesh& mesh(int id) {
    static std::vector<std::unique_ptr<Mesh>> meshes(5);
    auto& m = meshes[static_cast<std::size_t>(id)];
    if (!m) {
        switch (id) {
        case 0:
            m = std::make_unique<Mesh>(torus(1000, false, SchemeKind::CatmullClark));
            break;
        case 1: {
            const Mesh triangles = torus(410, true, SchemeKind::CatmullClark);
            limsurf::Level level = limsurf::refine(triangles.topology, SchemeKind::CatmullClark);
            m = std::make_unique<Mesh>(
                Mesh{std::move(level.topology), level.S0 * triangles.X, SchemeKind::CatmullClark, 0.0});
            break;
        }
        case 2:
            m = std::make_unique<Mesh>(torus(700, true, SchemeKind::Loop));
            break;
        case 3:
            m = std::make_unique<Mesh>(icosahedron_refined(8));
            break;
        default:
            m = std::make_unique<Mesh>(torus(1000, false, SchemeKind::DooSabin));
        }
        with_exact(*m);
    }
    return *m;
}

const char* const mesh_names[] = {"cc_torus", "cc_dense", "loop_torus", "loop_ico", "ds_torus"};

void BM_Setup(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    for (auto _ : state) {
        const limsurf::EnclosedVolume forms(m.topology, m.scheme, {}, limsurf::VolumeOptions{2});
        benchmark::DoNotOptimize(&forms);
    }
    state.SetLabel(mesh_names[state.range(0)]);
    state.counters["faces"] = m.topology.num_faces();
}

void BM_Volume(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::EnclosedVolume forms(m.topology, m.scheme, {},
                                        limsurf::VolumeOptions{static_cast<int>(state.range(1))});
    double v = 0.0;
    for (auto _ : state) {
        v = forms.volume(m.X);
        benchmark::DoNotOptimize(v);
    }
    state.SetLabel(std::string(mesh_names[state.range(0)]) + ", threads " + std::to_string(state.range(1)));
    state.counters["faces"] = m.topology.num_faces();
    state.counters["subdivided"] = forms.statistics().subdivided_elements;
}

void BM_Gradient(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const limsurf::EnclosedVolume forms(m.topology, m.scheme, {}, limsurf::VolumeOptions{2});
    for (auto _ : state) {
        limsurf::Points g = forms.gradient(m.X);
        benchmark::DoNotOptimize(g.data());
    }
    state.SetLabel(mesh_names[state.range(0)]);
}

/// Polyhedral volumes of levels 0..levels: OpenSubdiv (Catmull–Clark, Loop) or limsurf (Doo–Sabin).
std::vector<double> subdivided_volumes(const Mesh& m, int levels) {
    std::vector<double> out;
    if (m.scheme == SchemeKind::DooSabin) {
        limsurf::Topology t = m.topology;
        limsurf::Points X = m.X;
        out.push_back(limsurf::polyhedral_volume(t, X));
        for (int l = 1; l <= levels; ++l) {
            limsurf::Level next = limsurf::refine(t, m.scheme);
            X = next.S0 * X;
            t = std::move(next.topology);
            out.push_back(limsurf::polyhedral_volume(t, X));
        }
        return out;
    }
    auto refiner = limsurf::test::make_opensubdiv_refiner(m.topology, m.scheme, limsurf::SchemeOptions{});
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
    std::vector<limsurf::test::OsdPoint> points(static_cast<std::size_t>(refiner->GetNumVerticesTotal()));
    for (Index v = 0; v < m.topology.num_vertices(); ++v) {
        for (int c = 0; c < 3; ++c) {
            points[static_cast<std::size_t>(v)].p[c] = m.X(v, c);
        }
    }
    Far::PrimvarRefiner primvar(*refiner);
    limsurf::test::OsdPoint* src = points.data();
    for (int l = 0; l <= levels; ++l) {
        out.push_back(limsurf::test::polyhedral_volume(refiner->GetLevel(l), src));
        if (l < levels) {
            limsurf::test::OsdPoint* dst = src + refiner->GetLevel(l).GetNumVertices();
            primvar.Interpolate(l + 1, src, dst);
            src = dst;
        }
    }
    return out;
}

void BM_Subdivide(benchmark::State& state) {
    const Mesh& m = mesh(static_cast<int>(state.range(0)));
    const int levels = static_cast<int>(state.range(1));
    std::vector<double> v;
    for (auto _ : state) {
        v = subdivided_volumes(m, levels);
        benchmark::DoNotOptimize(v.data());
    }
    const double e = std::abs(v.back() - m.exact) / m.exact;
    const double e_prev = std::abs(v[v.size() - 2] - m.exact) / m.exact;
    const double rate = e_prev / e;  // ~4 per level
    state.SetLabel(std::string(mesh_names[state.range(0)]) + ", level " + std::to_string(levels));
    state.counters["rel_error"] = e;
    state.counters["rate"] = rate;
    state.counters["levels_for_1e-9"] = levels + std::log(e / 1e-9) / std::log(rate);
    const double richardson = (4.0 * v.back() - v[v.size() - 2]) / 3.0;
    state.counters["richardson_rel_error"] = std::abs(richardson - m.exact) / m.exact;
}

}  // namespace

BENCHMARK(BM_Setup)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Volume)->ArgsProduct({{0, 1, 2, 3, 4}, {1, 2}})->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_Gradient)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Subdivide)->ArgsProduct({{0, 1, 2, 3, 4}, {1, 2}})->Unit(benchmark::kMillisecond)->Iterations(1);

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    limsurf::bench::prefault_heap(8.0);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
