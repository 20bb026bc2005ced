// Placeholder until the face-split schemes land: refuses clearly.
#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_catmull_clark(const Topology&, const SchemeOptions&, const TunedWeights&) {
    throw UnsupportedError("Catmull-Clark refinement is not implemented yet");
}
Level refine_loop(const Topology&, const SchemeOptions&) {
    throw UnsupportedError("Loop refinement is not implemented yet");
}
Level refine_bilinear(const Topology&) {
    throw UnsupportedError("bilinear refinement is not implemented yet");
}
Level refine_linear(const Topology&) {
    throw UnsupportedError("linear refinement is not implemented yet");
}

}  // namespace limsurf
