// Placeholder until Doo–Sabin lands: refuses clearly.
#include "limsurf/core/error.h"
#include "limsurf/refine/refine.h"

namespace limsurf {

Level refine_doo_sabin(const Topology&, const SchemeOptions&) {
    throw UnsupportedError("Doo-Sabin refinement is not implemented yet");
}

}  // namespace limsurf
