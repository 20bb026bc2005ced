// The compiled half of the Python module `limsurf` (python/limsurf/__init__.py re-exports it).
// Conventions: arrays in are checked and copied (any real dtype, any strides); arrays out are
// C-ordered float64 owned by Python, except Mesh.V, a read-only view of the mesh's positions that
// keeps the mesh alive. Sparse matrices come out as scipy.sparse.csr_matrix. Long C++ work runs
// with the GIL released. limsurf errors become limsurf.Error and its subclasses.
#include <pybind11/pybind11.h>

#include "common.h"
#include "limsurf/core/version.h"

PYBIND11_MODULE(_limsurf, m) {
    namespace py = pybind11;
    m.doc() = "limsurf: exact computation on subdivision surfaces (compiled core).";
    m.attr("__version__") = limsurf::version();
    limsurf::python::bind_errors(m);
    limsurf::python::bind_mesh(m);
    limsurf::python::bind_refine(m);
    limsurf::python::bind_limit(m);
    limsurf::python::bind_measure(m);
    limsurf::python::bind_sec(m);
    limsurf::python::bind_fem(m);
    limsurf::python::bind_render(m);
    limsurf::python::bind_parameterization(m);
    limsurf::python::bind_geodesics(m);
    limsurf::python::bind_vector_field(m);
    limsurf::python::bind_hodge(m);
    limsurf::python::bind_membrane(m);
    limsurf::python::bind_tuning(m);
    limsurf::python::bind_eigen(m);
    limsurf::python::bind_reverse(m);
    limsurf::python::bind_elasticity(m);
}
