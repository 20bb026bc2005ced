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

namespace {

/// One step of @p kind run as @p run says.
Level run_step(const Topology& parent, SchemeKind kind, const SchemeOptions& options, const TunedWeights& weights,
               const detail::StepRun& run) {
    switch (kind) {
    case SchemeKind::CatmullClark:
        return detail::refine_catmull_clark_forced(parent, options, weights, {}, run);
    case SchemeKind::Loop:
        return detail::refine_loop_step(parent, options, run);
    case SchemeKind::Bilinear:
        return detail::refine_bilinear_step(parent, run);
    case SchemeKind::Linear:
        return detail::refine_linear_step(parent, run);
    case SchemeKind::C2g0:
        return detail::refine_c2g0_step(parent, run);
    case SchemeKind::DooSabin:
        return detail::refine_doo_sabin_step(parent, options, run);
    }
    return detail::refine_bilinear_step(parent, run);
}

}  // namespace

Level detail::refine_step(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                          const TunedWeights& weights, int threads, CarriedPoints* carried, PolygonSoup* faces,
                          std::function<void()> release_parent) {
    return run_step(parent, kind, options, weights,
                    StepRun{.carried = carried,
                            .keep_matrix = true,
                            .threads = threads,
                            .faces = faces,
                            .release_parent = std::move(release_parent)});
}

Topology detail::refine_carrying(const Topology& parent, SchemeKind kind, const SchemeOptions& options,
                                 const TunedWeights& weights, CarriedPoints& carried, int threads, PolygonSoup* faces) {
    return std::move(run_step(parent, kind, options, weights,
                              StepRun{.carried = &carried, .threads = threads, .faces = faces, .release_parent = {}})
                         .topology);
}

}  // namespace limsurf
