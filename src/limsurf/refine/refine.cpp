#include "limsurf/refine/refine.h"

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

}  // namespace limsurf
