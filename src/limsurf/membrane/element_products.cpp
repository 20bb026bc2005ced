// element_products.h. The loops are written so that the compiler vectorises them without
// reassociating anything: the forward pass across rows (independent sums), the backward pass across
// the eight partial sums of each dot product. Both keep a few independent sums in flight, because
// a sum of products is limited by the latency of the addition, not by the multiplications.
#include "limsurf/membrane/element_products.h"

#include <array>

#include "limsurf/detail/target_clones.h"

namespace limsurf::detail {

namespace {

/// Eight doubles as one value (GCC/Clang vector types): lowered to the widest registers of the
/// instruction set the function is compiled for (one AVX-512 register, two AVX2, four SSE2), each
/// operation lane by lane, so that the sums are those of the scalar loop in every copy.
typedef double Lanes __attribute__((vector_size(8 * sizeof(double))));

/// Eight doubles from @p p, aligned or not (through a reference: a vector returned by value would
/// depend on the instruction set's calling convention).
[[gnu::always_inline]] inline void load(Lanes& v, const double* p) {
    __builtin_memcpy(&v, p, sizeof v);
}

[[gnu::always_inline]] inline void store(double* p, const Lanes& v) {
    __builtin_memcpy(p, &v, sizeof v);
}

}  // namespace

LIMSURF_TARGET_CLONES
void element_forward(const double* __restrict K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols,
                     const double* __restrict P, double* __restrict out) noexcept {
    // 16 rows per pass, times three columns: six vector sums in flight.
    constexpr std::ptrdiff_t block = 16;
    const double* P0 = P;
    const double* P1 = P + cols;
    const double* P2 = P + 2 * cols;
    std::ptrdiff_t r = 0;
    for (; r + block <= rows; r += block) {
        Lanes a0 = {}, a1 = {}, b0 = {}, b1 = {}, c0 = {}, c1 = {};
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            Lanes k0, k1;
            load(k0, K + j * ld_k + r);
            load(k1, K + j * ld_k + r + 8);
            const double p0 = P0[j], p1 = P1[j], p2 = P2[j];
            a0 += k0 * p0;
            a1 += k1 * p0;
            b0 += k0 * p1;
            b1 += k1 * p1;
            c0 += k0 * p2;
            c1 += k1 * p2;
        }
        store(out + r, a0);
        store(out + r + 8, a1);
        store(out + rows + r, b0);
        store(out + rows + r + 8, b1);
        store(out + 2 * rows + r, c0);
        store(out + 2 * rows + r + 8, c1);
    }
    for (; r < rows; ++r) {  // the last rows % 16, summed in the same order
        double s0 = 0.0, s1 = 0.0, s2 = 0.0;
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            const double k = K[j * ld_k + r];
            s0 += k * P0[j];
            s1 += k * P1[j];
            s2 += k * P2[j];
        }
        out[r] = s0;
        out[rows + r] = s1;
        out[2 * rows + r] = s2;
    }
}

namespace {

constexpr std::ptrdiff_t lanes = 8;

/// The documented reduction of eight partial sums.
inline double reduce(const std::array<double, lanes>& s) {
    return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

}  // namespace

LIMSURF_TARGET_CLONES
void element_backward(const double* __restrict K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols,
                      const double* __restrict L, std::ptrdiff_t ld_l, std::ptrdiff_t width, double* __restrict out,
                      std::ptrdiff_t ld_out) noexcept {
    const std::ptrdiff_t full = rows - rows % lanes;
    for (std::ptrdiff_t j = 0; j < cols; ++j) {
        const double* k = K + j * ld_k;
        double* o = out + j * ld_out;
        std::ptrdiff_t w = 0;
        for (; w + 3 <= width; w += 3) {  // three dot products sharing the loads of K's column
            const double* a = L + w * ld_l;
            const double* b = a + ld_l;
            const double* c = b + ld_l;
            std::array<double, lanes> sa{}, sb{}, sc{};
            for (std::ptrdiff_t r = 0; r < full; r += lanes) {
                for (std::ptrdiff_t l = 0; l < lanes; ++l) {
                    sa[l] += k[r + l] * a[r + l];
                    sb[l] += k[r + l] * b[r + l];
                    sc[l] += k[r + l] * c[r + l];
                }
            }
            double ta = reduce(sa), tb = reduce(sb), tc = reduce(sc);
            for (std::ptrdiff_t r = full; r < rows; ++r) {
                ta += k[r] * a[r];
                tb += k[r] * b[r];
                tc += k[r] * c[r];
            }
            o[w] = ta;
            o[w + 1] = tb;
            o[w + 2] = tc;
        }
        for (; w < width; ++w) {
            const double* a = L + w * ld_l;
            std::array<double, lanes> sa{};
            for (std::ptrdiff_t r = 0; r < full; r += lanes) {
                for (std::ptrdiff_t l = 0; l < lanes; ++l) {
                    sa[l] += k[r + l] * a[r + l];
                }
            }
            double ta = reduce(sa);
            for (std::ptrdiff_t r = full; r < rows; ++r) {
                ta += k[r] * a[r];
            }
            o[w] = ta;
        }
    }
}

}  // namespace limsurf::detail
