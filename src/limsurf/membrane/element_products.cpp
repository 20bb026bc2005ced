// element_products.h. The loops are written so that the compiler vectorises them without
// reassociating anything: the forward pass across rows (independent sums), the backward pass across
// the eight partial sums of each dot product. Both keep a few independent sums in flight, because
// a sum of products is limited by the latency of the addition, not by the multiplications.
#include "limsurf/membrane/element_products.h"

#include <array>

// One copy of each function per instruction set, chosen at load time (GCC/Clang function
// multi-versioning through an ifunc: x86-64 Linux only). Elsewhere the baseline copy alone.
#if defined(__x86_64__) && defined(__linux__) && defined(__has_attribute)
#if __has_attribute(target_clones)
#define LIMSURF_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#endif
#endif
#ifndef LIMSURF_CLONES
#define LIMSURF_CLONES
#endif

namespace limsurf::detail {

LIMSURF_CLONES
void element_forward(const double* __restrict K, std::ptrdiff_t ld_k, std::ptrdiff_t rows, std::ptrdiff_t cols,
                     const double* __restrict P, double* __restrict out) noexcept {
    constexpr std::ptrdiff_t block = 8;  // rows per pass, times three columns: 24 sums in flight
    const double* P0 = P;
    const double* P1 = P + cols;
    const double* P2 = P + 2 * cols;
    std::ptrdiff_t r = 0;
    for (; r + block <= rows; r += block) {
        std::array<double, block> s0{}, s1{}, s2{};
        for (std::ptrdiff_t j = 0; j < cols; ++j) {
            const double* k = K + j * ld_k + r;
            const double p0 = P0[j], p1 = P1[j], p2 = P2[j];
            for (std::ptrdiff_t l = 0; l < block; ++l) {
                s0[l] += k[l] * p0;
                s1[l] += k[l] * p1;
                s2[l] += k[l] * p2;
            }
        }
        for (std::ptrdiff_t l = 0; l < block; ++l) {
            out[r + l] = s0[l];
            out[rows + r + l] = s1[l];
            out[2 * rows + r + l] = s2[l];
        }
    }
    for (; r < rows; ++r) {  // the last rows % 8, summed in the same order
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

LIMSURF_CLONES
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
