// sample_integrands.h. One loop over the samples with no branch and no call in its body (the
// functionals' terms are all computed; a degenerate sample is noted, not jumped over), so that the
// compiler runs it across 2, 4 or 8 samples at a time. Built with -fno-math-errno (a square root
// that may not set errno becomes one instruction) and vectorisation beyond -O2's very-cheap model
// (src/limsurf/membrane/CMakeLists.txt).
#include "limsurf/membrane/sample_integrands.h"

#include <algorithm>
#include <cmath>

#include "limsurf/detail/target_clones.h"
#include "limsurf/membrane/shape_functionals.h"

namespace limsurf::detail {
namespace {

// The functionals' indices, from the public enum (the outputs are laid out in its order).
constexpr int functional_index(ShapeFunctional f) {
    return static_cast<int>(f);
}
constexpr int Area = functional_index(ShapeFunctional::Area), Volume = functional_index(ShapeFunctional::Volume),
              MeanCurvature = functional_index(ShapeFunctional::MeanCurvature),
              Willmore = functional_index(ShapeFunctional::Willmore),
              Gaussian = functional_index(ShapeFunctional::Gaussian),
              Harmonic = functional_index(ShapeFunctional::Harmonic);

/// |v| ≤ the largest double: false for ±∞ and NaN, without a call.
inline bool finite(double v) {
    return std::fabs(v) <= 1.7976931348623157e308;
}

}  // namespace

LIMSURF_TARGET_CLONES
std::ptrdiff_t sample_integrands(const SampleBatch& batch, double* __restrict values, double* __restrict normal_area,
                                 double* __restrict local, double* __restrict degenerate) noexcept {
    const std::ptrdiff_t n = batch.n;
    const std::ptrdiff_t ld = 6 * n;
    const double* __restrict D = batch.rows;
    const double* __restrict weight = batch.weights;
    const double cx = batch.centroid[0], cy = batch.centroid[1], cz = batch.centroid[2];
    // The harmonic energy's metric: an equilateral triangle (τ of (3.9)) or a unit square.
    const double hs = batch.triangle ? 2.0 / std::sqrt(3.0) : 1.0;
    const double hm = batch.triangle ? -1.0 : 0.0;
    // Row r, coordinate c of the derivatives, and column 3 f + c of the local gradients at row r.
    const auto in = [&](int r, int c) { return D + c * ld + r * n; };
    const auto out = [&](int f, int r, int c) { return local + (3 * f + c) * ld + r * n; };
    const double *x0 = in(RowValue, 0), *x1 = in(RowValue, 1), *x2 = in(RowValue, 2);
    const double *a0 = in(RowDu, 0), *a1 = in(RowDu, 1), *a2 = in(RowDu, 2);
    const double *b0 = in(RowDv, 0), *b1 = in(RowDv, 1), *b2 = in(RowDv, 2);
    const double *uu0 = in(RowDuu, 0), *uu1 = in(RowDuu, 1), *uu2 = in(RowDuu, 2);
    const double *uv0 = in(RowDuv, 0), *uv1 = in(RowDuv, 1), *uv2 = in(RowDuv, 2);
    const double *vv0 = in(RowDvv, 0), *vv1 = in(RowDvv, 1), *vv2 = in(RowDvv, 2);

    std::ptrdiff_t bad = 0;  // a count, not the first index: a running minimum keeps the loop scalar
    // Each sample reads its own rows and writes its own: nothing carries from one to the next,
    // which the compiler cannot prove through the offsets in n.
#pragma GCC ivdep
    for (std::ptrdiff_t i = 0; i < n; ++i) {
        const double w = weight[i];
        const double x[3] = {x0[i] - cx, x1[i] - cy, x2[i] - cz};
        const double a[3] = {a0[i], a1[i], a2[i]};
        const double b[3] = {b0[i], b1[i], b2[i]};
        const double uu[3] = {uu0[i], uu1[i], uu2[i]};
        const double uv[3] = {uv0[i], uv1[i], uv2[i]};
        const double vv[3] = {vv0[i], vv1[i], vv2[i]};
        const double N[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        const double S = N[0] * N[0] + N[1] * N[1] + N[2] * N[2];
        const double E = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
        const double F = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        const double G = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
        const double J = std::sqrt(S);
        const double L = N[0] * uu[0] + N[1] * uu[1] + N[2] * uu[2];
        const double Mn = N[0] * uv[0] + N[1] * uv[1] + N[2] * uv[2];
        const double Nn = N[0] * vv[0] + N[1] * vv[1] + N[2] * vv[2];
        double Q[3];
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) {
            Q[c] = G * uu[c] - 2.0 * F * uv[c] + E * vv[c];
        }
        const double P = N[0] * Q[0] + N[1] * Q[1] + N[2] * Q[2];
        const double T = L * Nn - Mn * Mn;
        const double SJ = S * J;
        const double S2 = S * S;

        double value[6];
        value[Area] = J * w;
        value[Volume] = (x[0] * N[0] + x[1] * N[1] + x[2] * N[2]) / 3.0 * w;
        value[MeanCurvature] = -P / (2.0 * S) * w;
        value[Willmore] = P * P / (4.0 * S2 * J) * w;
        value[Gaussian] = T / SJ * w;
        value[Harmonic] = hs * (E + hm * F + G) * w;
        bool good = (S > 1e-28 * E * G) & finite(S);
#pragma GCC unroll 6
        for (int f = 0; f < 6; ++f) {
            values[f * n + i] = value[f];
            good = good & finite(value[f]);
        }
        degenerate[i] = good ? 0.0 : 1.0;
        bad += good ? 0 : 1;
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) {
            normal_area[c * n + i] = w * N[c];
        }

        // dS = 2 N·dN with dN = da × b + a × db; dP = dN·Q + N·dQ, dQ = dG ∂uu − 2 dF ∂uv + dE ∂vv
        // with dE = 2 a·da, dF = b·da + a·db, dG = 2 b·db; dT = Nn dL + L dNn − 2 Mn dMn.
        const double R[3] = {Nn * uu[0] + L * vv[0] - 2.0 * Mn * uv[0], Nn * uu[1] + L * vv[1] - 2.0 * Mn * uv[1],
                             Nn * uu[2] + L * vv[2] - 2.0 * Mn * uv[2]};
        // Coefficients of dP and dS in M = −P/(2S), W = P²/(4 S^(5/2)); of dT and dS in K = T/S^(3/2).
        const double m_p = -1.0 / (2.0 * S), m_s = P / (2.0 * S2);
        const double S52 = S2 * J;
        const double w_p = P / (2.0 * S52), w_s = -5.0 * P * P / (8.0 * S52 * S);
        const double k_t = 1.0 / SJ, k_s = -1.5 * T / (S2 * J);
        const double area_s = 1.0 / (2.0 * J);
#pragma GCC unroll 3
        for (int c = 0; c < 3; ++c) {
            const int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            const double dS_da = 2.0 * (b[c1] * N[c2] - b[c2] * N[c1]);  // 2 b × N
            const double dS_db = 2.0 * (N[c1] * a[c2] - N[c2] * a[c1]);  // 2 N × a
            const double dP_da = (b[c1] * Q[c2] - b[c2] * Q[c1]) - 2.0 * Mn * b[c] + 2.0 * Nn * a[c];
            const double dP_db = (Q[c1] * a[c2] - Q[c2] * a[c1]) + 2.0 * L * b[c] - 2.0 * Mn * a[c];
            const double dP_duu = G * N[c], dP_duv = -2.0 * F * N[c], dP_dvv = E * N[c];
            const double dT_da = b[c1] * R[c2] - b[c2] * R[c1];  // b × R
            const double dT_db = R[c1] * a[c2] - R[c2] * a[c1];  // R × a

            out(Area, RowDu, c)[i] = w * (dS_da * area_s);
            out(Area, RowDv, c)[i] = w * (dS_db * area_s);

            out(Volume, RowValue, c)[i] = w * (N[c] / 3.0);
            out(Volume, RowDu, c)[i] = w * ((b[c1] * x[c2] - b[c2] * x[c1]) / 3.0);  // b × x
            out(Volume, RowDv, c)[i] = w * ((x[c1] * a[c2] - x[c2] * a[c1]) / 3.0);  // x × a

            out(MeanCurvature, RowDu, c)[i] = w * (m_p * dP_da + m_s * dS_da);
            out(MeanCurvature, RowDv, c)[i] = w * (m_p * dP_db + m_s * dS_db);
            out(MeanCurvature, RowDuu, c)[i] = w * (m_p * dP_duu);
            out(MeanCurvature, RowDuv, c)[i] = w * (m_p * dP_duv);
            out(MeanCurvature, RowDvv, c)[i] = w * (m_p * dP_dvv);

            out(Willmore, RowDu, c)[i] = w * (w_p * dP_da + w_s * dS_da);
            out(Willmore, RowDv, c)[i] = w * (w_p * dP_db + w_s * dS_db);
            out(Willmore, RowDuu, c)[i] = w * (w_p * dP_duu);
            out(Willmore, RowDuv, c)[i] = w * (w_p * dP_duv);
            out(Willmore, RowDvv, c)[i] = w * (w_p * dP_dvv);

            out(Gaussian, RowDu, c)[i] = w * (k_t * dT_da + k_s * dS_da);
            out(Gaussian, RowDv, c)[i] = w * (k_t * dT_db + k_s * dS_db);
            out(Gaussian, RowDuu, c)[i] = w * (k_t * Nn * N[c]);
            out(Gaussian, RowDuv, c)[i] = w * (k_t * (-2.0 * Mn) * N[c]);
            out(Gaussian, RowDvv, c)[i] = w * (k_t * L * N[c]);

            out(Harmonic, RowDu, c)[i] = w * (hs * (2.0 * a[c] + hm * b[c]));
            out(Harmonic, RowDv, c)[i] = w * (hs * (2.0 * b[c] + hm * a[c]));
        }
    }
    if (bad == 0) {
        return -1;
    }
    return std::find(degenerate, degenerate + n, 1.0) - degenerate;
}

}  // namespace limsurf::detail
