// Gauss points along the limit boundary (boundary_samples.h).
#include "boundary_samples.h"

#include <cmath>

#include "limsurf/core/error.h"
#include "limsurf/quadrature/rules.h"

namespace limsurf::detail {
namespace {

/// Segments [t0, t1] of [0, 1]: the whole side, or dyadic rings towards both ends, `levels` deep.
std::vector<std::pair<double, double>> side_segments(int levels) {
    if (levels == 0) {
        return {{0.0, 1.0}};
    }
    std::vector<std::pair<double, double>> out;
    double size = std::ldexp(1.0, -levels);
    out.emplace_back(0.0, size);  // the innermost cell at each end
    for (double t = size; t < 0.5; t *= 2.0) {
        out.emplace_back(t, 2.0 * t);
    }
    const std::size_t half = out.size();
    for (std::size_t i = half; i-- > 0;) {
        out.emplace_back(1.0 - out[i].second, 1.0 - out[i].first);
    }
    return out;
}

/// The side of a quad ptex face on its edge from corner k to corner k + 1 (k = 0..3).
BoundarySample quad_side(Index p, int k) {
    BoundarySample s;
    s.point.face = p;
    s.along_u = k % 2 == 0;
    s.inward = (k == 0 || k == 3) ? 1.0 : -1.0;
    if (k == 1) {
        s.point.u = 1.0;
    } else if (k == 2) {
        s.point.v = 1.0;
    }
    return s;
}

void add_side(const BoundarySample& side, const QuadratureRule& gauss,
              const std::vector<std::pair<double, double>>& segments, std::vector<BoundarySample>& out) {
    for (const auto& [t0, t1] : segments) {
        for (int i = 0; i < gauss.num_points(); ++i) {
            BoundarySample s = side;
            const double t = t0 + (t1 - t0) * gauss.u[static_cast<std::size_t>(i)];
            (s.along_u ? s.point.u : s.point.v) = t;
            s.weight = (t1 - t0) * gauss.weight[static_cast<std::size_t>(i)];
            out.push_back(s);
        }
    }
}

}  // namespace

std::vector<BoundarySample> boundary_samples(const LimitBasis& basis, const SamplerOptions& rule) {
    LIMSURF_CHECK(basis.domain() == ParameterDomain::Quad, UnsupportedError,
                  "boundary quadrature: quad ptex faces (Catmull–Clark) only");
    LIMSURF_CHECK(rule.degree >= 1 && rule.degree <= 127, InputError, "boundary quadrature: degree ", rule.degree,
                  " out of range 1..127");
    LIMSURF_CHECK(rule.subdivide_near_extraordinary >= 0 && rule.subdivide_near_extraordinary <= 30, InputError,
                  "boundary quadrature: tile level ", rule.subdivide_near_extraordinary, " out of range 0..30");
    const QuadratureRule gauss = gauss_legendre_1d((rule.degree + 2) / 2);
    const auto segments = side_segments(rule.subdivide_near_extraordinary);
    const Topology& t = basis.topology();
    std::vector<BoundarySample> out;
    for (Index f = 0; f < t.num_faces(); ++f) {
        if (t.is_hole(f)) {
            continue;
        }
        const Index first = basis.first_ptex_face(f);
        const bool split = basis.ptex_face(first).corner >= 0;
        const Index n = t.face_degree(f);
        const auto edges = t.face_edges(f);
        for (Index k = 0; k < n; ++k) {
            if (!t.is_boundary_edge(edges[static_cast<std::size_t>(k)])) {
                continue;
            }
            if (!split) {
                if (basis.has_limit_surface(first)) {
                    add_side(quad_side(first, static_cast<int>(k)), gauss, segments, out);
                }
                continue;
            }
            // Sub-face k holds the first half (its side v = 0), sub-face k + 1 the second (its side u = 0).
            const Index here = first + k;
            const Index next = first + (k + 1) % n;
            if (basis.has_limit_surface(here)) {
                add_side(quad_side(here, 0), gauss, segments, out);
            }
            if (basis.has_limit_surface(next)) {
                add_side(quad_side(next, 3), gauss, segments, out);
            }
        }
    }
    return out;
}

}  // namespace limsurf::detail
