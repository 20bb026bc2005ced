#include "limsurf/core/version.h"

namespace limsurf {

std::string version() {
    return "0.1.0";
}

}  // namespace limsurf
