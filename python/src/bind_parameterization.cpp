// Placeholder: filled in by the SEC-applications work (issue 16).
#include "common.h"

namespace limsurf::python {

void bind_parameterization(py::module_& m) {
    (void)m;
}

}  // namespace limsurf::python
