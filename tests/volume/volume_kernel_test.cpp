// The evaluation kernels of the volume forms: the bicubic Gauss kernel of the regular
// Catmull–Clark facet is the same form as its coefficients (value and gradient), and the
// coefficient kernel's gradient is the derivative of its value.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "limsurf/volume/facet_ring.h"
#include "limsurf/volume/volume_forms.h"

namespace limsurf {
namespace {

std::vector<double> random_points(std::size_t m, std::mt19937& rng) {
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    std::vector<double> p(3 * m);
    for (double& x : p) {
        x = uniform(rng);
    }
    return p;
}

TEST(VolumeKernel, BicubicGaussRuleIsTheRegularCatmullClarkForm) {
    const detail::VolumeForm form = detail::load_volume_form(SchemeKind::CatmullClark, 4);
    ASSERT_TRUE(form.bicubic);
    std::mt19937 rng(7);
    for (int trial = 0; trial < 50; ++trial) {
        const std::vector<double> p = random_points(16, rng);
        std::vector<double> g_gauss(p.size(), 0.0);
        std::vector<double> g_table(p.size(), 0.0);
        const double v_gauss = form.evaluate(p.data(), g_gauss.data());
        const double v_table = form.evaluate_by_coefficients(p.data(), g_table.data());
        EXPECT_NEAR(v_gauss, v_table, 1e-15);
        for (std::size_t i = 0; i < p.size(); ++i) {
            EXPECT_NEAR(g_gauss[i], g_table[i], 1e-15) << i;
        }
    }
}

TEST(VolumeKernel, GradientIsTheDerivativeOfTheFormForEveryScheme) {
    std::mt19937 rng(11);
    for (const SchemeKind scheme : {SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin}) {
        for (const int type : {3, 4, 5, 6, 12}) {
            const detail::VolumeForm form = detail::load_volume_form(scheme, type);
            const auto m = static_cast<std::size_t>(detail::facet_ring_size(scheme, type));
            std::vector<double> p = random_points(m, rng);
            std::vector<double> g(p.size(), 0.0);
            form.evaluate(p.data(), g.data());
            // The form is cubic: the central difference is exact up to rounding (h² term vanishes
            // only for quadratics, so keep h small; the h² error is O(h² · |coefficients|)).
            const double h = 1e-5;
            for (std::size_t i = 0; i < p.size(); ++i) {
                const double x = p[i];
                p[i] = x + h;
                const double plus = form.evaluate(p.data(), nullptr);
                p[i] = x - h;
                const double minus = form.evaluate(p.data(), nullptr);
                p[i] = x;
                EXPECT_NEAR((plus - minus) / (2 * h), g[i], 1e-9) << to_string(scheme) << " type " << type << " " << i;
            }
        }
    }
}

}  // namespace
}  // namespace limsurf
