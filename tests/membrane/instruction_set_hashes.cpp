// Prints the CPU features that pick a LIMSURF_TARGET_CLONES copy (detail/target_clones.h: SSE2,
// AVX2, AVX-512), then one hash per mesh of every shape functional's value and gradient and of the
// exact volume's value and gradient (its pair-weight kernel). same_bits_on_every_cpu.cmake runs it
// natively and under qemu-user's emulated CPUs without AVX (qemu64) and without AVX-512 (Haswell)
// and compares the hashes: every copy must give the same bits.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "limsurf/io/mesh_io.h"
#include "limsurf/limit/limit_basis.h"
#include "limsurf/membrane/shape_functionals.h"
#include "limsurf/refine/hierarchy.h"
#include "limsurf/volume/enclosed_volume.h"
#include "support/mesh_zoo.h"

namespace {

using namespace limsurf;

/// FNV-1a over the bytes of the doubles.
struct Hash {
    std::uint64_t state = 14695981039346656037ull;
    void add(const double* values, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) {
            unsigned char bytes[sizeof(double)];
            std::memcpy(bytes, &values[i], sizeof(double));
            for (const unsigned char b : bytes) {
                state = (state ^ b) * 1099511628211ull;
            }
        }
    }
};

/// The mesh's control points scaled per coordinate by factors in [0.995, 1.005) from integer
/// arithmetic (no library function whose last bits could depend on the CPU).
Points perturbed(const Points& X) {
    Points out = X;
    for (Index i = 0; i < X.rows(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const auto k = static_cast<double>((i * 7919 + c * 104729) % 101);
            out(i, c) *= 1.0 + 0.01 * (k / 101.0 - 0.5);
        }
    }
    return out;
}

void print_hashes(const char* name, SchemeKind scheme, int levels) {
    const ControlMesh mesh = read_mesh(test::find_bundled(name).path).mesh;
    RefineOptions refine_options;
    refine_options.scheme = scheme;
    refine_options.levels = levels;
    const FinestLevel finest = refine_finest(mesh.topology(), mesh.positions(), refine_options);
    const Topology& topology = finest.topology;
    const Points X = perturbed(finest.positions);
    const LimitBasis basis(topology, scheme);
    const ShapeFunctionals functionals(basis, ShapeOptions{.num_threads = 2});
    const ShapeValues values = functionals.evaluate_all(X);
    Hash hash;
    for (int f = 0; f < num_shape_functionals; ++f) {
        const double value = values.value(static_cast<ShapeFunctional>(f));
        hash.add(&value, 1);
        const Points& g = values.gradient[static_cast<std::size_t>(f)];
        hash.add(g.data(), static_cast<std::size_t>(g.size()));
    }
    std::printf("%s %s (%d levels, %lld vertices): shape functionals %016llx", name, to_string(scheme), levels,
                static_cast<long long>(X.rows()), static_cast<unsigned long long>(hash.state));
    if (scheme != SchemeKind::C2g0) {
        const EnclosedVolume volume(topology, scheme);
        Points gradient;
        const double v = volume.volume_and_gradient(X, gradient);
        Hash h;
        h.add(&v, 1);
        h.add(gradient.data(), static_cast<std::size_t>(gradient.size()));
        std::printf(", exact volume %016llx", static_cast<unsigned long long>(h.state));
    }
    std::printf("\n");
}

}  // namespace

int main() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    std::printf("cpu: avx2 %d avx512f %d\n", __builtin_cpu_supports("avx2") ? 1 : 0,
                __builtin_cpu_supports("avx512f") ? 1 : 0);
#else
    std::printf("cpu: not x86-64\n");
#endif
    try {
        print_hashes("tetra_2", SchemeKind::C2g0, 0);
        print_hashes("icosahedron", SchemeKind::Loop, 2);
        print_hashes("cube", SchemeKind::CatmullClark, 2);
        print_hashes("dodecahedron", SchemeKind::CatmullClark, 1);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
