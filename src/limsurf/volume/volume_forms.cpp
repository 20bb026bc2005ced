// Shipped and on-demand volume forms (volume_forms.h).
#include "limsurf/volume/volume_forms.h"

#include <utility>

#include "limsurf/core/error.h"
#include "limsurf/volume/facet_ring.h"
#include "limsurf/volume/form_generator.h"
#include "limsurf/volume/shipped_forms.h"

namespace limsurf::detail {
namespace {

const ShippedForm* find_shipped(SchemeKind scheme, int type) {
    for (const ShippedForm& form : shipped_forms()) {
        if (form.scheme == scheme && form.type == type) {
            return &form;
        }
    }
    return nullptr;
}

std::vector<double> shipped_coefficients(const ShippedForm& form) {
    const auto count = static_cast<std::size_t>(num_alternating(form.size));
    return {form.coefficients, form.coefficients + count};
}

}  // namespace

double VolumeForm::evaluate(const double* p, double* gradient) const {
    double volume = 0.0;
    for (const Pair& pair : pairs) {
        const double* pj = p + 3 * pair.j;
        const double* pk = p + 3 * pair.k;
        const double cross[3] = {pj[1] * pk[2] - pj[2] * pk[1], pj[2] * pk[0] - pj[0] * pk[2],
                                 pj[0] * pk[1] - pj[1] * pk[0]};
        double q[3] = {0.0, 0.0, 0.0};
        for (std::uint32_t t = pair.begin; t < pair.end; ++t) {
            const double* pi = p + 3 * term_i[t];
            const double c = term_c[t];
            q[0] += c * pi[0];
            q[1] += c * pi[1];
            q[2] += c * pi[2];
            if (gradient != nullptr) {
                double* gi = gradient + 3 * term_i[t];
                gi[0] += c * cross[0];
                gi[1] += c * cross[1];
                gi[2] += c * cross[2];
            }
        }
        volume += q[0] * cross[0] + q[1] * cross[1] + q[2] * cross[2];
        if (gradient != nullptr) {
            // ∂/∂p_j q·(p_j × p_k) = p_k × q;  ∂/∂p_k = q × p_j.
            double* gj = gradient + 3 * pair.j;
            double* gk = gradient + 3 * pair.k;
            gj[0] += pk[1] * q[2] - pk[2] * q[1];
            gj[1] += pk[2] * q[0] - pk[0] * q[2];
            gj[2] += pk[0] * q[1] - pk[1] * q[0];
            gk[0] += q[1] * pj[2] - q[2] * pj[1];
            gk[1] += q[2] * pj[0] - q[0] * pj[2];
            gk[2] += q[0] * pj[1] - q[1] * pj[0];
        }
    }
    return volume;
}

VolumeForm make_volume_form(SchemeKind scheme, int type, std::vector<double> coefficients) {
    VolumeForm form;
    form.scheme = scheme;
    form.type = type;
    form.size = facet_ring_size(scheme, type);
    const int m = form.size;
    // Lexicographic (i, j, k) -> grouped by (j, k): walk pairs, then i < j.
    for (int j = 1; j < m; ++j) {
        for (int k = j + 1; k < m; ++k) {
            VolumeForm::Pair pair{static_cast<std::uint16_t>(j), static_cast<std::uint16_t>(k),
                                  static_cast<std::uint32_t>(form.term_i.size()), 0};
            for (int i = 0; i < j; ++i) {
                const double c = coefficients[static_cast<std::size_t>(alternating_index(m, i, j, k))];
                if (c != 0.0) {
                    form.term_i.push_back(static_cast<std::uint16_t>(i));
                    form.term_c.push_back(c);
                }
            }
            pair.end = static_cast<std::uint32_t>(form.term_i.size());
            if (pair.end > pair.begin) {
                form.pairs.push_back(pair);
            }
        }
    }
    form.coefficients = std::move(coefficients);
    return form;
}

bool is_shipped(SchemeKind scheme, int type) {
    return find_shipped(scheme, type) != nullptr;
}

VolumeForm load_volume_form(SchemeKind scheme, int type) {
    if (const ShippedForm* shipped = find_shipped(scheme, type)) {
        return make_volume_form(scheme, type, shipped_coefficients(*shipped));
    }
    const ShippedForm* regular = find_shipped(scheme, regular_facet_type(scheme));
    LIMSURF_CHECK(regular != nullptr, UnsupportedError, "no volume forms for ", to_string(scheme));
    auto generated = solve_irregular_form<double>(scheme, type, shipped_coefficients(*regular), 1e-17);
    return make_volume_form(scheme, type, std::move(generated.coefficients));
}

}  // namespace limsurf::detail
