// Limit-surface evaluation throughput: N random points (ptex face, u, v) on
// ~100k-face control meshes, position + first derivatives and position + all
// second derivatives, applied to the control positions.
//
//   limsurf:    LimitBasis::evaluate(X, point, out, order) (the positions path: a local
//               patch's points formed before its basis; X interleaved). "first" = a fresh LimitBasis
//               (its local patches are built lazily on first use: setup + evaluate);
//               "warm" = a second pass over the same points with the patches cached;
//               "weights" = the warm pass through LimitBasis::evaluate(point, weights,
//               order) + LimitWeights::apply (what a user who needs the weights pays);
//               "store" = the warm pass as a batch loop: points ahead prefetched
//               (prefetch_ahead), every point's rows kept in a reused array; "fresh" = the same
//               into arrays allocated in every pass, one per row (Python without out=).
//   OpenSubdiv: Far::TopologyRefiner + RefineAdaptive + PatchTableFactory
//               (Gregory-basis end caps, double precision) + PatchMap; refined
//               vertices by PrimvarRefiner, local (end-cap) points by the patch
//               table's local-point stencils ("setup", measured separately); then
//               per point PatchMap::FindPatch + PatchTable::EvaluateBasis + the
//               weighted sum of the patch's points.
//
// Meshes (all closed):
//   CC-dense:  a 129x129x2 triangle torus refined once by Catmull–Clark:
//              99 846 quads, every quad has two extraordinary corners
//              (valence 3 at the old face centres, valence 6 at the old vertices;
//              49 923 extraordinary vertices in all);
//   CC-sparse: data/meshes/quad_valence_8.obj refined 6 times by Catmull–Clark:
//              98 304 quads, 18 extraordinary vertices (2 of valence 8, 16 of
//              valence 3) — the mostly regular case;
//   Loop:      data/meshes/icosahedron.obj refined 6 times by Loop: 81 920
//              triangles, 12 extraordinary vertices (valence 5).
// Refinement is limsurf's own (Hierarchy), outside every timer.
//
// The number of points is 1 000 000, or LIMSURF_BENCH_POINTS when set.
//
// First-touch page faults are very expensive on the project's VM (3 GB of fresh
// heap cost ~10 s there) and would land on whichever setup happens to grow the
// heap first. So before any benchmark the heap is grown to
// LIMSURF_BENCH_PREFAULT_GIB GiB (default 6, enough for every contender here),
// touched, and kept: glibc malloc without mmap and without trimming (glibc only;
// 0 turns this off and measures "cold", each setup paying its own page faults).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opensubdiv/far/patchMap.h>
#include <opensubdiv/far/patchTable.h>
#include <opensubdiv/far/patchTableFactory.h>
#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include "bench_heap.h"
#include "limsurf/io/obj.h"
#include "limsurf/limit/batch_evaluation.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/refine/hierarchy.h"

namespace {

using limsurf::DerivativeOrder;
using limsurf::Index;
using limsurf::SchemeKind;
namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

std::size_t at(Index i) {
    return static_cast<std::size_t>(i);
}

std::size_t num_points() {
    if (const char* n = std::getenv("LIMSURF_BENCH_POINTS")) {
        return static_cast<std::size_t>(std::strtoull(n, nullptr, 10));
    }
    return 1'000'000;
}

struct Mesh {
    limsurf::Topology topology;
    limsurf::Points positions;
    limsurf::InterleavedPoints interleaved;  // the same, x y z side by side (the positions path)
    SchemeKind scheme = SchemeKind::CatmullClark;
    std::vector<limsurf::SurfacePoint> points;  // random; ptex face = control face on these meshes
    /// The basis the warm benchmarks share (built, and its patches cached, outside their timers).
    mutable std::unique_ptr<limsurf::LimitBasis> warm;
};

Mesh refined(const limsurf::Topology& base, const limsurf::Points& X, SchemeKind scheme, int levels) {
    limsurf::RefineOptions options;
    options.scheme = scheme;
    options.levels = levels;
    const limsurf::Hierarchy hierarchy(base, options);
    Mesh mesh;
    mesh.topology = hierarchy.topology(levels);
    mesh.positions = hierarchy.positions(levels, X);
    mesh.interleaved = mesh.positions;
    mesh.scheme = scheme;
    return mesh;
}

void add_points(Mesh& mesh) {
    const bool triangles = mesh.scheme == SchemeKind::Loop;
    std::mt19937_64 random(20261122);
    std::uniform_int_distribution<Index> face(0, mesh.topology.num_faces() - 1);
    std::uniform_real_distribution<double> uv(0.0, 1.0);
    mesh.points.resize(num_points());
    for (auto& p : mesh.points) {
        p.face = face(random);
        p.u = uv(random);
        p.v = uv(random);
        if (triangles && p.u + p.v > 1.0) {
            p.u = 1.0 - p.u;
            p.v = 1.0 - p.v;
        }
    }
}

Mesh from_obj(const char* name, SchemeKind scheme, int levels) {
    const auto built = limsurf::build_control_mesh(limsurf::read_obj(std::string(LIMSURF_MESH_DIR "/") + name));
    Mesh mesh = refined(built.mesh.topology(), built.mesh.positions(), scheme, levels);
    add_points(mesh);
    return mesh;
}

const Mesh& cc_dense() {
    static const Mesh mesh = [] {
        constexpr Index n = 129;
        limsurf::Points X(n * n, 3);
        for (Index j = 0; j < n; ++j) {
            for (Index i = 0; i < n; ++i) {
                const double u = 2.0 * M_PI * i / n;
                const double v = 2.0 * M_PI * j / n;
                X.row(j * n + i) << (2.0 + std::cos(v)) * std::cos(u), (2.0 + std::cos(v)) * std::sin(u), std::sin(v);
            }
        }
        const auto id = [](Index i, Index j) { return (j % n) * n + (i % n); };
        std::vector<Index> offsets{0};
        std::vector<Index> corners;
        for (Index j = 0; j < n; ++j) {
            for (Index i = 0; i < n; ++i) {
                for (const std::array<Index, 3>& t : {std::array<Index, 3>{id(i, j), id(i + 1, j), id(i + 1, j + 1)},
                                                      std::array<Index, 3>{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
                    corners.insert(corners.end(), t.begin(), t.end());
                    offsets.push_back(static_cast<Index>(corners.size()));
                }
            }
        }
        Mesh m = refined(limsurf::Topology(n * n, offsets, corners), X, SchemeKind::CatmullClark, 1);
        add_points(m);
        return m;
    }();
    return mesh;
}

const Mesh& cc_sparse() {
    static const Mesh mesh = from_obj("quad_valence_8.obj", SchemeKind::CatmullClark, 6);
    return mesh;
}

const Mesh& loop() {
    static const Mesh mesh = from_obj("icosahedron.obj", SchemeKind::Loop, 6);
    return mesh;
}

int rows_of(DerivativeOrder order) {
    return order == DerivativeOrder::First ? 3 : 6;
}

void report(benchmark::State& state, const Mesh& mesh, double checksum) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(mesh.points.size()));
    state.counters["faces"] = mesh.topology.num_faces();
    state.counters["points"] = static_cast<double>(mesh.points.size());
    state.counters["checksum"] = checksum;
}

// --- limsurf -----------------------------------------------------------------------

double limsurf_pass(const limsurf::LimitBasis& basis, const Mesh& mesh, DerivativeOrder order) {
    limsurf::LimitPoint point;
    double sum = 0.0;
    const int rows = rows_of(order);
    for (const auto& p : mesh.points) {
        basis.evaluate(mesh.interleaved, p, point, order);
        sum += point.d.topRows(rows).sum();
    }
    return sum;
}

double limsurf_weights_pass(const limsurf::LimitBasis& basis, const Mesh& mesh, DerivativeOrder order) {
    limsurf::LimitWeights weights;
    double sum = 0.0;
    const int rows = rows_of(order);
    for (const auto& p : mesh.points) {
        basis.evaluate(p, weights, order);
        const Eigen::Matrix<double, 6, 3> r = weights.apply(mesh.positions);
        sum += r.topRows(rows).sum();
    }
    return sum;
}

/// A fresh LimitBasis each iteration: construction + lazy patch building + evaluation.
void limsurf_first(benchmark::State& state, const Mesh& mesh, DerivativeOrder order) {
    double sum = 0.0;
    for (auto _ : state) {
        auto basis = std::make_unique<limsurf::LimitBasis>(mesh.topology, mesh.scheme);
        sum = limsurf_pass(*basis, mesh, order);
        benchmark::DoNotOptimize(sum);
        state.PauseTiming();
        basis.reset();
        state.ResumeTiming();
    }
    report(state, mesh, sum);
}

using Pass = double (*)(const limsurf::LimitBasis&, const Mesh&, DerivativeOrder);

/// The same points again on a basis whose patches are already built: one untimed pass of @p pass
/// first (the weights path builds per-face nodes on first use, which the positions path never
/// needs).
void limsurf_warm(benchmark::State& state, const Mesh& mesh, DerivativeOrder order, Pass pass = limsurf_pass) {
    if (!mesh.warm) {
        mesh.warm = std::make_unique<limsurf::LimitBasis>(mesh.topology, mesh.scheme);
    }
    (void)pass(*mesh.warm, mesh, order);
    double sum = 0.0;
    for (auto _ : state) {
        sum = pass(*mesh.warm, mesh, order);
        benchmark::DoNotOptimize(sum);
    }
    report(state, mesh, sum);
}

/// The warm pass of limsurf_warm, but as a batch loop that keeps every result: the points ahead
/// are prefetched (prefetch_ahead, as evaluate_points and the Python module do) and each point's
/// rows are written into a reused N × 3·rows array (faulted in before the timer), as Python's
/// evaluate(..., out=) does into its arrays — the C++ side of bench/python_eval.py.
void limsurf_store(benchmark::State& state, const Mesh& mesh, DerivativeOrder order) {
    if (!mesh.warm) {
        mesh.warm = std::make_unique<limsurf::LimitBasis>(mesh.topology, mesh.scheme);
    }
    const int rows = rows_of(order);
    limsurf::PointValues values(static_cast<Eigen::Index>(mesh.points.size()), 3 * rows);
    const auto pass = [&] {
        limsurf::LimitPoint point;
        const auto n = static_cast<limsurf::Index>(mesh.points.size());
        for (limsurf::Index i = 0; i < n; ++i) {
            limsurf::prefetch_ahead(*mesh.warm, mesh.interleaved, mesh.points, i, n);
            mesh.warm->evaluate(mesh.interleaved, mesh.points[static_cast<std::size_t>(i)], point, order);
            for (int r = 0; r < rows; ++r) {
                values.block<1, 3>(i, 3 * r) = point.d.row(r);
            }
        }
    };
    pass();  // warms the basis and faults the array in
    for (auto _ : state) {
        pass();
        benchmark::ClobberMemory();
    }
    report(state, mesh, values.sum());
}

/// limsurf_store, but into arrays allocated afresh in every pass, one N × 3 array per row (position,
/// first and second derivatives), freed at its end — what Python's evaluate(...) without out= does
/// with its new numpy arrays. Run cold (LIMSURF_BENCH_PREFAULT_GIB=0) it pays the fresh memory's
/// page faults as Python does.
void limsurf_fresh(benchmark::State& state, const Mesh& mesh, DerivativeOrder order) {
    if (!mesh.warm) {
        mesh.warm = std::make_unique<limsurf::LimitBasis>(mesh.topology, mesh.scheme);
    }
    using Array = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
    const int rows = rows_of(order);
    const auto n = static_cast<limsurf::Index>(mesh.points.size());
    double sum = 0.0;
    const auto pass = [&] {
        std::vector<Array> arrays(static_cast<std::size_t>(rows), Array(n, 3));
        limsurf::LimitPoint point;
        for (limsurf::Index i = 0; i < n; ++i) {
            limsurf::prefetch_ahead(*mesh.warm, mesh.interleaved, mesh.points, i, n);
            mesh.warm->evaluate(mesh.interleaved, mesh.points[static_cast<std::size_t>(i)], point, order);
            for (int r = 0; r < rows; ++r) {
                arrays[static_cast<std::size_t>(r)].row(i) = point.d.row(r);
            }
        }
        sum = arrays.back()(n - 1, 2);
    };
    pass();  // warms the basis
    for (auto _ : state) {
        pass();
        benchmark::DoNotOptimize(sum);
    }
    report(state, mesh, sum);
}

/// Warm evaluation as one batch (limit/batch_evaluation.h) on state.range(0) threads: the
/// multi-threaded form of limsurf_warm (same points, same basis, results independent of threads).
void limsurf_batch(benchmark::State& state, const Mesh& mesh, DerivativeOrder order) {
    if (!mesh.warm) {
        mesh.warm = std::make_unique<limsurf::LimitBasis>(mesh.topology, mesh.scheme);
    }
    const int threads = static_cast<int>(state.range(0));
    // One untimed batch first: it warms the basis, and the 72 MB result's first-touch page faults
    // (expensive on the project's VM) would otherwise land on whichever thread count runs first.
    (void)limsurf::evaluate_points(*mesh.warm, mesh.positions, mesh.points, order, threads);
    // The checksum is taken after the timed loop: a serial sum of the 9 M values inside it (~3 ms)
    // would count against the second thread.
    limsurf::PointValues values;
    for (auto _ : state) {
        values = limsurf::evaluate_points(*mesh.warm, mesh.positions, mesh.points, order, threads);
        benchmark::DoNotOptimize(values.data());
        benchmark::ClobberMemory();
    }
    report(state, mesh, values.sum());
}

// --- OpenSubdiv Far ---------------------------------------------------------------------

struct OsdPoint {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(const OsdPoint& src, double w) {
        p[0] += w * src.p[0];
        p[1] += w * src.p[1];
        p[2] += w * src.p[2];
    }
};

/// Everything OpenSubdiv needs before it can evaluate: adaptive refinement to
/// @p isolation, the patch table with Gregory-basis end caps, the patch map, and
/// the patch points (control + refined vertices, then local end-cap points).
struct OsdSetup {
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::unique_ptr<const Far::PatchTable> table;
    std::unique_ptr<const Far::PatchMap> map;
    std::vector<OsdPoint> points;

    OsdSetup(const Mesh& mesh, int isolation) {
        const limsurf::Topology& t = mesh.topology;
        std::vector<int> degrees(at(t.num_faces()));
        for (Index f = 0; f < t.num_faces(); ++f) {
            degrees[at(f)] = t.face_degree(f);
        }
        Far::TopologyDescriptor descriptor;
        descriptor.numVertices = t.num_vertices();
        descriptor.numFaces = t.num_faces();
        descriptor.numVertsPerFace = degrees.data();
        descriptor.vertIndicesPerFace = t.all_face_vertices().data();
        Sdc::Options sdc;
        sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
        using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
        const auto type = mesh.scheme == SchemeKind::Loop ? Sdc::SCHEME_LOOP : Sdc::SCHEME_CATMARK;
        refiner.reset(Factory::Create(descriptor, Factory::Options(type, sdc)));

        Far::PatchTableFactory::Options options(static_cast<unsigned>(isolation));
        options.SetEndCapType(Far::PatchTableFactory::Options::ENDCAP_GREGORY_BASIS);
        options.SetPatchPrecision<double>();
        refiner->RefineAdaptive(options.GetRefineAdaptiveOptions());
        table.reset(Far::PatchTableFactory::Create(*refiner, options));
        map = std::make_unique<Far::PatchMap>(*table);

        const int num_refined = refiner->GetNumVerticesTotal();
        const auto* local = table->GetLocalPointStencilTable<double>();
        const int num_local = local != nullptr ? local->GetNumStencils() : 0;
        points.resize(static_cast<std::size_t>(num_refined + num_local));
        for (Index v = 0; v < t.num_vertices(); ++v) {
            points[at(v)] = {{mesh.positions(v, 0), mesh.positions(v, 1), mesh.positions(v, 2)}};
        }
        const Far::PrimvarRefinerReal<double> primvar(*refiner);
        OsdPoint* src = points.data();
        for (int level = 1; level <= refiner->GetMaxLevel(); ++level) {
            OsdPoint* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
            primvar.Interpolate(level, src, dst);
            src = dst;
        }
        if (num_local > 0) {
            local->UpdateValues(points.data(), points.data() + num_refined);
        }
    }
};

double osd_pass(const OsdSetup& osd, const Mesh& mesh, DerivativeOrder order) {
    constexpr int max_points = 20;  // Gregory basis
    double w[6][max_points];
    const bool second = order == DerivativeOrder::Second;
    const int rows = rows_of(order);
    double sum = 0.0;
    for (const auto& p : mesh.points) {
        const Far::PatchTable::PatchHandle* handle = osd.map->FindPatch(p.face, p.u, p.v);
        osd.table->EvaluateBasis(*handle, p.u, p.v, w[0], w[1], w[2], second ? w[3] : nullptr, second ? w[4] : nullptr,
                                 second ? w[5] : nullptr);
        const Far::ConstIndexArray cvs = osd.table->GetPatchVertices(*handle);
        double r[6][3] = {};
        for (int i = 0; i < cvs.size(); ++i) {
            const double* x = osd.points[static_cast<std::size_t>(cvs[i])].p;
            for (int k = 0; k < rows; ++k) {
                r[k][0] += w[k][i] * x[0];
                r[k][1] += w[k][i] * x[1];
                r[k][2] += w[k][i] * x[2];
            }
        }
        for (int k = 0; k < rows; ++k) {
            sum += r[k][0] + r[k][1] + r[k][2];
        }
    }
    return sum;
}

/// The setup the evaluation benchmarks use: one at a time (a dense-EV setup takes gigabytes).
struct OsdCache {
    const Mesh* mesh = nullptr;
    int isolation = 0;
    std::unique_ptr<const OsdSetup> setup;
};
OsdCache& osd_cache() {
    static OsdCache cache;
    return cache;
}

const OsdSetup& cached_setup(const Mesh& mesh, int isolation) {
    OsdCache& cache = osd_cache();
    if (cache.mesh != &mesh || cache.isolation != isolation) {
        cache.setup.reset();
        cache.setup = std::make_unique<const OsdSetup>(mesh, isolation);
        cache.mesh = &mesh;
        cache.isolation = isolation;
    }
    return *cache.setup;
}

/// Setup alone: refiner, adaptive refinement, patch table, patch map, patch points.
void osd_setup(benchmark::State& state, const Mesh& mesh) {
    const int isolation = static_cast<int>(state.range(0));
    mesh.warm.reset();  // limsurf's cached patches are done with; keep the peak memory down
    osd_cache() = {};
    std::unique_ptr<const OsdSetup> osd;
    for (auto _ : state) {
        state.PauseTiming();
        osd.reset();
        state.ResumeTiming();
        osd = std::make_unique<const OsdSetup>(mesh, isolation);
        benchmark::DoNotOptimize(osd->points.data());
    }
    state.counters["faces"] = mesh.topology.num_faces();
    state.counters["patches"] = osd->table->GetNumPatchesTotal();
    state.counters["local_points"] = osd->table->GetNumLocalPoints();
    osd_cache() = {&mesh, isolation, std::move(osd)};
}

/// Evaluation alone, on a setup made outside the timer (the setup benchmark's, when it ran).
void osd_evaluate(benchmark::State& state, const Mesh& mesh, DerivativeOrder order) {
    mesh.warm.reset();
    const OsdSetup& osd = cached_setup(mesh, static_cast<int>(state.range(0)));
    if (Far::PtexIndices(*osd.refiner).GetNumFaces() != mesh.topology.num_faces()) {
        state.SkipWithError("ptex faces differ from control faces");
        return;
    }
    double sum = 0.0;
    for (auto _ : state) {
        sum = osd_pass(osd, mesh, order);
        benchmark::DoNotOptimize(sum);
    }
    report(state, mesh, sum);
}

// --- registration -----------------------------------------------------------------------

void BM_limsurf_batch_CCdense_d1(benchmark::State& s) {
    limsurf_batch(s, cc_dense(), DerivativeOrder::First);
}
void BM_limsurf_batch_CCsparse_d1(benchmark::State& s) {
    limsurf_batch(s, cc_sparse(), DerivativeOrder::First);
}
void BM_limsurf_batch_Loop_d1(benchmark::State& s) {
    limsurf_batch(s, loop(), DerivativeOrder::First);
}

void BM_limsurf_store_CCsparse_d1(benchmark::State& s) {
    limsurf_store(s, cc_sparse(), DerivativeOrder::First);
}
void BM_limsurf_store_CCsparse_d2(benchmark::State& s) {
    limsurf_store(s, cc_sparse(), DerivativeOrder::Second);
}
void BM_limsurf_fresh_CCsparse_d1(benchmark::State& s) {
    limsurf_fresh(s, cc_sparse(), DerivativeOrder::First);
}
void BM_limsurf_fresh_CCsparse_d2(benchmark::State& s) {
    limsurf_fresh(s, cc_sparse(), DerivativeOrder::Second);
}

void BM_limsurf_first_CCdense_d1(benchmark::State& s) {
    limsurf_first(s, cc_dense(), DerivativeOrder::First);
}
void BM_limsurf_first_CCdense_d2(benchmark::State& s) {
    limsurf_first(s, cc_dense(), DerivativeOrder::Second);
}
void BM_limsurf_warm_CCdense_d1(benchmark::State& s) {
    limsurf_warm(s, cc_dense(), DerivativeOrder::First);
}
void BM_limsurf_warm_CCdense_d2(benchmark::State& s) {
    limsurf_warm(s, cc_dense(), DerivativeOrder::Second);
}
void BM_limsurf_weights_CCdense_d1(benchmark::State& s) {
    limsurf_warm(s, cc_dense(), DerivativeOrder::First, limsurf_weights_pass);
}
void BM_limsurf_weights_CCdense_d2(benchmark::State& s) {
    limsurf_warm(s, cc_dense(), DerivativeOrder::Second, limsurf_weights_pass);
}
void BM_OpenSubdiv_setup_CCdense(benchmark::State& s) {
    osd_setup(s, cc_dense());
}
void BM_OpenSubdiv_eval_CCdense_d1(benchmark::State& s) {
    osd_evaluate(s, cc_dense(), DerivativeOrder::First);
}
void BM_OpenSubdiv_eval_CCdense_d2(benchmark::State& s) {
    osd_evaluate(s, cc_dense(), DerivativeOrder::Second);
}

void BM_limsurf_first_CCsparse_d1(benchmark::State& s) {
    limsurf_first(s, cc_sparse(), DerivativeOrder::First);
}
void BM_limsurf_first_CCsparse_d2(benchmark::State& s) {
    limsurf_first(s, cc_sparse(), DerivativeOrder::Second);
}
void BM_limsurf_warm_CCsparse_d1(benchmark::State& s) {
    limsurf_warm(s, cc_sparse(), DerivativeOrder::First);
}
void BM_limsurf_warm_CCsparse_d2(benchmark::State& s) {
    limsurf_warm(s, cc_sparse(), DerivativeOrder::Second);
}
void BM_limsurf_weights_CCsparse_d1(benchmark::State& s) {
    limsurf_warm(s, cc_sparse(), DerivativeOrder::First, limsurf_weights_pass);
}
void BM_limsurf_weights_CCsparse_d2(benchmark::State& s) {
    limsurf_warm(s, cc_sparse(), DerivativeOrder::Second, limsurf_weights_pass);
}
void BM_OpenSubdiv_setup_CCsparse(benchmark::State& s) {
    osd_setup(s, cc_sparse());
}
void BM_OpenSubdiv_eval_CCsparse_d1(benchmark::State& s) {
    osd_evaluate(s, cc_sparse(), DerivativeOrder::First);
}
void BM_OpenSubdiv_eval_CCsparse_d2(benchmark::State& s) {
    osd_evaluate(s, cc_sparse(), DerivativeOrder::Second);
}

void BM_limsurf_first_Loop_d1(benchmark::State& s) {
    limsurf_first(s, loop(), DerivativeOrder::First);
}
void BM_limsurf_first_Loop_d2(benchmark::State& s) {
    limsurf_first(s, loop(), DerivativeOrder::Second);
}
void BM_limsurf_warm_Loop_d1(benchmark::State& s) {
    limsurf_warm(s, loop(), DerivativeOrder::First);
}
void BM_limsurf_warm_Loop_d2(benchmark::State& s) {
    limsurf_warm(s, loop(), DerivativeOrder::Second);
}
void BM_limsurf_weights_Loop_d1(benchmark::State& s) {
    limsurf_warm(s, loop(), DerivativeOrder::First, limsurf_weights_pass);
}
void BM_limsurf_weights_Loop_d2(benchmark::State& s) {
    limsurf_warm(s, loop(), DerivativeOrder::Second, limsurf_weights_pass);
}
void BM_OpenSubdiv_setup_Loop(benchmark::State& s) {
    osd_setup(s, loop());
}
void BM_OpenSubdiv_eval_Loop_d1(benchmark::State& s) {
    osd_evaluate(s, loop(), DerivativeOrder::First);
}
void BM_OpenSubdiv_eval_Loop_d2(benchmark::State& s) {
    osd_evaluate(s, loop(), DerivativeOrder::Second);
}

}  // namespace

// One iteration each (a pass is 10^5–10^7 evaluations); repeat with --benchmark_repetitions.
// OpenSubdiv per isolation level: setup, then the evaluations on that setup.
#define LIMSURF_ONCE(name) BENCHMARK(name)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1)
#define LIMSURF_OSD(mesh, isolation)                                                                                   \
    LIMSURF_ONCE(BM_OpenSubdiv_setup_##mesh)->ArgName("isolation")->Arg(isolation);                                    \
    LIMSURF_ONCE(BM_OpenSubdiv_eval_##mesh##_d1)->ArgName("isolation")->Arg(isolation);                                \
    LIMSURF_ONCE(BM_OpenSubdiv_eval_##mesh##_d2)->ArgName("isolation")->Arg(isolation)
#define LIMSURF_MESH(mesh)                                                                                             \
    LIMSURF_ONCE(BM_limsurf_first_##mesh##_d1);                                                                        \
    LIMSURF_ONCE(BM_limsurf_first_##mesh##_d2);                                                                        \
    LIMSURF_ONCE(BM_limsurf_warm_##mesh##_d1);                                                                         \
    LIMSURF_ONCE(BM_limsurf_warm_##mesh##_d2);                                                                         \
    LIMSURF_ONCE(BM_limsurf_weights_##mesh##_d1);                                                                      \
    LIMSURF_ONCE(BM_limsurf_weights_##mesh##_d2);                                                                      \
    LIMSURF_OSD(mesh, 4);                                                                                              \
    LIMSURF_OSD(mesh, 6)

LIMSURF_MESH(CCdense);
LIMSURF_MESH(CCsparse);
LIMSURF_MESH(Loop);
// Warm batches on 1 and 2 threads (run with --benchmark_filter=batch).
LIMSURF_ONCE(BM_limsurf_batch_CCdense_d1)->ArgName("threads")->Arg(1)->Arg(2);
LIMSURF_ONCE(BM_limsurf_batch_CCsparse_d1)->ArgName("threads")->Arg(1)->Arg(2);
LIMSURF_ONCE(BM_limsurf_batch_Loop_d1)->ArgName("threads")->Arg(1)->Arg(2);
// Warm passes that keep their results (bench/python_eval.py's C++ side).
LIMSURF_ONCE(BM_limsurf_store_CCsparse_d1);
LIMSURF_ONCE(BM_limsurf_store_CCsparse_d2);
LIMSURF_ONCE(BM_limsurf_fresh_CCsparse_d1);
LIMSURF_ONCE(BM_limsurf_fresh_CCsparse_d2);

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
        return 1;
    }
    limsurf::bench::prefault_heap(6.0);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
