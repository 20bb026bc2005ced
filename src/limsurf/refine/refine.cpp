#include "limsurf/refine/refine.h"

#include <utility>

#include "limsurf/detail/refine_face_split.h"
#include "limsurf/detail/tuned_copy.h"

namespace limsurf {

const char* to_string(SchemeKind kind) noexcept {
    switch (kind) {
    case SchemeKind::CatmullClark:
        return "catmull-clark";
    case SchemeKind::Loop:
        return "loop";
    case SchemeKind::DooSabin:
        return "doo-sabin";
    case SchemeKind::Bilinear:
        return "bilinear";
    case SchemeKind::Linear:
        return "linear";
    case SchemeKind::C2g0:
        return "c2g0";
    }
    return "?";
}

Level refine(const Topology& parent, SchemeKind kind, const SchemeOptions& options, const TunedWeights& weights) {
    switch (kind) {
    case SchemeKind::CatmullClark:
        return refine_catmull_clark(parent, options, weights);
    case SchemeKind::Loop:
        return refine_loop(parent, options);
    case SchemeKind::DooSabin:
        return refine_doo_sabin(parent, options);
    case SchemeKind::Bilinear:
        return refine_bilinear(parent);
    case SchemeKind::Linear:
        return refine_linear(parent);
    case SchemeKind::C2g0:
        return refine_c2g0(parent);
    }
    return refine_bilinear(parent);
}

Topology detail::refine_carrying(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                                 const TunedWeights& weights, CarriedPoints& carried) {
    switch (kind) {
    case SchemeKind::CatmullClark:
        return std::move(refine_catmull_clark_forced(parent, options, weights, {}, &carried).topology);
    case SchemeKind::Loop:
        return std::move(refine_loop_step(parent, options, &carried).topology);
    case SchemeKind::Bilinear:
        return std::move(refine_bilinear_step(parent, &carried).topology);
    case SchemeKind::Linear:
        return std::move(refine_linear_step(parent, &carried).topology);
    case SchemeKind::C2g0:
        return std::move(refine_c2g0_step(parent, &carried).topology);
    case SchemeKind::DooSabin:
        break;
    }
    // Doo–Sabin collects its S0 as triplets: it is built and applied as Hierarchy::apply does.
    Level step = refine(parent, kind, options, weights);
    carried.child = step.S0 * Points(carried.parent);
    return std::move(step.topology);
}

}  // namespace limsurf
