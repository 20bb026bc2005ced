#include "common.h"

#include <array>

#include "arrays.h"
#include "limsurf/sec/inner_products.h"

namespace limsurf::python {
namespace {

/// The value of @p E whose to_string() is @p name. @throws InputError listing the names
template <class E, std::size_t N>
E parse_name(const std::string& what, const std::string& name, const std::array<E, N>& values) {
    std::string accepted;
    for (const E value : values) {
        if (name == to_string(value)) {
            return value;
        }
        accepted += std::string(accepted.empty() ? "" : ", ") + to_string(value);
    }
    throw InputError(detail::concat("unknown ", what, " '", name, "' (expected ", accepted, ")"));
}

}  // namespace

SchemeKind scheme_from(const std::string& name) {
    return parse_name("scheme", name,
                      std::array{SchemeKind::CatmullClark, SchemeKind::Loop, SchemeKind::DooSabin, SchemeKind::C2g0,
                                 SchemeKind::Bilinear, SchemeKind::Linear});
}

SchemeHints hints_from(const RuleNames& names) {
    SchemeHints hints;
    if (names.boundary) {
        hints.boundary = parse_name("boundary rule", *names.boundary,
                                    std::array{BoundaryInterpolation::None, BoundaryInterpolation::EdgeOnly,
                                               BoundaryInterpolation::EdgeAndCorner});
    }
    if (names.creasing) {
        hints.creasing = parse_name("creasing method", *names.creasing,
                                    std::array{CreasingMethod::Uniform, CreasingMethod::Chaikin});
    }
    if (names.triangles) {
        hints.triangles = parse_name("triangle rule", *names.triangles,
                                     std::array{TriangleSubdivision::CatmullClark, TriangleSubdivision::Smooth});
    }
    return hints;
}

SchemeOptions rules_for(const ControlMesh& mesh, const RuleNames& names) {
    const SchemeHints chosen = hints_from(names);
    const SchemeHints& hints = mesh.hints();
    const SchemeOptions defaults;
    SchemeOptions rules;
    rules.boundary = chosen.boundary.value_or(hints.boundary.value_or(defaults.boundary));
    rules.creasing = chosen.creasing.value_or(hints.creasing.value_or(defaults.creasing));
    rules.triangles = chosen.triangles.value_or(hints.triangles.value_or(defaults.triangles));
    return rules;
}

SurfaceFunction surface_function(const py::function& f, const std::string& name) {
    return [f, name](const Points& P) {
        const py::gil_scoped_acquire acquire;
        return vector_from(f(to_numpy(P)), name + "(P) result", static_cast<Index>(P.rows()));
    };
}

void check_threads(int threads) {
    LIMSURF_CHECK(threads >= 0, InputError, "threads: expected 0 (all cores) or a positive count, got ", threads);
}

int level_for(const std::string& method, const std::optional<int>& level) {
    if (!level) {
        return InnerProductOptions{}.level;  // the library's default, as every application's options use
    }
    LIMSURF_CHECK(has_level(parse_laplacian_method(method)), InputError,
                  "level applies to method 'sec' and 'secsnap', not to '", method, "'");
    return *level;
}

void require_iga_for_quadrature(LaplacianMethod method, const std::string& method_name,
                                const std::optional<int>& degree, const std::optional<int>& tiles) {
    if (method == LaplacianMethod::Iga) {
        return;
    }
    LIMSURF_CHECK(!degree, InputError, "degree applies to method 'iga', not to '", method_name, "'");
    LIMSURF_CHECK(!tiles, InputError, "tiles applies to method 'iga', not to '", method_name, "'");
}

std::string located_message(const Error& error, const SourceMap& source) {
    const std::string message = error.what();
    if (source.file.empty() || message.compare(0, source.file.size() + 1, source.file + ":") == 0) {
        return message;
    }
    // Only errors about one of the mesh's elements are located: an error about an argument (an
    // array, an option) is not about the file, unlike in the CLI where the mesh is the input.
    const auto& element = error.element();
    if (!element) {
        return message;
    }
    const std::string where = element->kind == ErrorElement::Kind::Face ? source.face_location(element->index)
                                                                        : source.vertex_location(element->index);
    return where + ": " + message;
}

void bind_errors(py::module_& m) {
    // Translators run newest first, so the subclasses are registered after their base.
    auto& error = py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
    error.attr("__doc__") = "Base of every error limsurf raises (a RuntimeError).";
    const auto subclass = [&](auto tag, const char* name, PyObject* also, const char* doc) {
        using E = typename decltype(tag)::type;
        auto& type = py::register_exception<E>(m, name, py::make_tuple(error, py::handle(also)));
        type.attr("__doc__") = doc;
    };
    subclass(std::type_identity<InputError>{}, "InputError", PyExc_ValueError,
             "Bad file, bad array or bad argument; the message names the file and line or the array, row and problem "
             "(also a ValueError).");
    subclass(std::type_identity<TopologyError>{}, "TopologyError", PyExc_ValueError,
             "Non-manifold, inconsistently oriented or otherwise unusable connectivity (also a ValueError).");
    subclass(std::type_identity<NumericalError>{}, "NumericalError", PyExc_ArithmeticError,
             "A factorisation failed or a result is not finite (also an ArithmeticError).");
    subclass(std::type_identity<UnsupportedError>{}, "UnsupportedError", PyExc_NotImplementedError,
             "A valid request this scheme or case does not implement (also a NotImplementedError).");
}

py::dict reference_dict(const ReferenceComparison& reference) {
    using namespace pybind11::literals;
    return py::dict("level"_a = reference.level, "method"_a = "dec", "vertices"_a = reference.vertices,
                    "l2_relative"_a = reference.l2, "linf_relative"_a = reference.linf);
}

}  // namespace limsurf::python
