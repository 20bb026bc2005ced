// What every binding shares: the Python-side mesh (a ControlMesh that remembers where it came
// from, so that errors name the file and line), scheme names, and error location.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include <pybind11/pybind11.h>

#include "limsurf/apps/laplacian_method.h"
#include "limsurf/core/error.h"
#include "limsurf/fem/galerkin.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/scheme/scheme.h"
#include "limsurf/sec/reference_solution.h"

namespace limsurf {
struct ShapeDecomposition;
struct VertexRuleWeights;
}  // namespace limsurf

namespace limsurf::python {

namespace py = pybind11;

/// limsurf.Mesh: a validated control mesh and the provenance of its elements (file and lines when
/// read from a file, empty for arrays).
struct Mesh {
    ControlMesh mesh;
    SourceMap source;
    ValidationReport report;  ///< the warnings validation had (errors throw)
};

/// The scheme named as the CLI names it ("catmull-clark", "loop", "doo-sabin", "c2g0", "bilinear",
/// "linear"). @throws InputError naming the accepted names
[[nodiscard]] SchemeKind scheme_from(const std::string& name);

/// Rule overrides as keyword arguments give them: None keeps the mesh's hint, else the default.
struct RuleNames {
    std::optional<std::string> boundary;
    std::optional<std::string> creasing;
    std::optional<std::string> triangles;
};

/// Scheme hints of a mesh from names (None: no hint). @throws InputError for an unknown name
[[nodiscard]] SchemeHints hints_from(const RuleNames& names);

/// The rules: each override, else the mesh file's hint, else limsurf's default (as the CLI).
/// @throws InputError for an unknown rule name
[[nodiscard]] SchemeOptions rules_for(const ControlMesh& mesh, const RuleNames& names);

/// A Python callable f(P) -> values as a SurfaceFunction (the library calls it from C++ with the GIL
/// released around its own work): f is called with the GIL re-acquired, its result checked to be #P
/// finite values (InputError naming "<name>(P) result"). A Python exception in f propagates as itself.
[[nodiscard]] SurfaceFunction surface_function(const py::function& f, const std::string& name);

/// @brief @p value as T, for values a binding converts itself (elements of a list, a tuple's
///   parts): pybind11's own refusal (cast_error, a RuntimeError) named only the C++ type.
/// @throws InputError "<name>: expected <expected>, got <the value's repr>"
template <class T>
[[nodiscard]] T cast_as(const py::handle& value, const std::string& name, const char* expected) {
    try {
        return value.cast<T>();
    } catch (const py::cast_error&) {
        std::string got = py::repr(value).cast<std::string>();
        if (got.size() > 60) {
            got = got.substr(0, 57) + "...";
        }
        throw InputError(name + ": expected " + expected + ", got " +
                         py::str(py::type::of(value).attr("__name__")).cast<std::string>() + " " + got);
    }
}

/// @brief Refuses a negative thread count (0 means all cores), as every binding with `threads` does.
/// @throws InputError "threads: …"
void check_threads(int threads);

/// @brief The SEC level L of @p method: @p level when given, else InnerProductOptions' default (3).
/// @throws InputError when a level is given to a method that has none (dec, decsnap, iga): it would be
///   ignored without a word (the CLI refuses --level alike); as parse_laplacian_method for a bad name
[[nodiscard]] int level_for(const std::string& method, const std::optional<int>& level);

/// @brief Refuses `degree` or `tiles` (iga's quadrature) given with another method, which would
///   ignore them without a word (the CLI refuses --degree and --tiles alike).
/// @throws InputError naming the argument and the method
void require_iga_for_quadrature(LaplacianMethod method, const std::string& method_name,
                                const std::optional<int>& degree, const std::optional<int>& tiles);

/// The message of @p error prefixed with the file and line of the mesh element it is about (when
/// the mesh came from a file and the error is about one of its elements), as the CLI does.
/// The comparison with the DEC reference on the K-times subdivided mesh as the CLI prints it in
/// --json: level, method ("dec"), vertices, l2_relative, linf_relative.
[[nodiscard]] py::dict reference_dict(const ReferenceComparison& reference);

[[nodiscard]] std::string located_message(const Error& error, const SourceMap& source);

/// @brief Runs @p work; a limsurf error from it is rethrown with the same type, naming the file and
///   line of @p mesh's element it is about (located_message).
template <class Work>
auto naming_source(const Mesh& mesh, Work&& work) -> decltype(work()) {
    try {
        return work();
    } catch (const InputError& e) {
        throw InputError(located_message(e, mesh.source));
    } catch (const TopologyError& e) {
        throw TopologyError(located_message(e, mesh.source));
    } catch (const NumericalError& e) {
        throw NumericalError(located_message(e, mesh.source));
    } catch (const UnsupportedError& e) {
        throw UnsupportedError(located_message(e, mesh.source));
    } catch (const Error& e) {
        throw Error(located_message(e, mesh.source));
    }
}

// One registration function per layer of the library (module.cpp calls them in order).
void bind_errors(py::module_& m);
void bind_mesh(py::module_& m);
void bind_refine(py::module_& m);
void bind_limit(py::module_& m);
void bind_measure(py::module_& m);
void bind_sec(py::module_& m);
void bind_fem(py::module_& m);
void bind_render(py::module_& m);
void bind_parameterization(py::module_& m);
void bind_geodesics(py::module_& m);
void bind_vector_field(py::module_& m);
void bind_hodge(py::module_& m);
void bind_membrane(py::module_& m);
void bind_tuning(py::module_& m);
void bind_eigen(py::module_& m);
void bind_reverse(py::module_& m);
void bind_elasticity(py::module_& m);

/// The cup–saddle decomposition at one vertex as limsurf.decompose_shapes and limsurf.plate return
/// it: vertex, valence, k3, k4, k5, ratio, cup_dominates, and the 3-arrays normal and position and
/// the 2 × 3 array tangents (∂P/∂ξ₁, ∂P/∂ξ₂). Defined in bind_tuning.cpp.
[[nodiscard]] py::dict shape_decomposition_dict(const ShapeDecomposition& d);

/// @brief The weights (alpha, beta, gamma) of a tuned Catmull–Clark vertex from a 3-sequence or a
///   dict with 'alpha', 'beta', 'gamma' (a W of the tuning functions). Defined in bind_tuning.cpp.
/// @throws InputError naming @p what for another shape, a value that is not a number or a non-finite
///   weight (the library checks the signs)
[[nodiscard]] VertexRuleWeights vertex_weights_from(const py::handle& value, const std::string& what);

}  // namespace limsurf::python
