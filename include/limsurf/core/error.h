// The library's exception hierarchy (DESIGN.md §6, docs/coding_style.md).
//
// Everything the library throws derives from limsurf::Error. Messages name the
// element and, when the data came from a file, the file and line:
//     "mesh.obj:14: face 7 repeats vertex 3"
// The CLI prints "error: " + what() and exits 1.
#pragma once

#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "limsurf/core/types.h"

namespace limsurf {

/// The mesh element an error is about, numbered as in the mesh the failing call was given,
/// so that a caller who knows where that mesh came from can name the file and line.
struct ErrorElement {
    enum class Kind { Vertex, Face };
    Kind kind = Kind::Face;
    Index index = invalid_index;
};

[[nodiscard]] inline ErrorElement face_element(Index f) noexcept {
    return {ErrorElement::Kind::Face, f};
}
[[nodiscard]] inline ErrorElement vertex_element(Index v) noexcept {
    return {ErrorElement::Kind::Vertex, v};
}

/// Root of every exception limsurf throws.
class Error : public std::runtime_error {
  public:
    explicit Error(const std::string& what) : std::runtime_error(what) {}
    explicit Error(const char* what) : std::runtime_error(what) {}
    /// An error about one element of the input mesh (see ErrorElement).
    Error(const std::string& what, ErrorElement element) : std::runtime_error(what), element_(element) {}

    /// The element the error is about, when it is about one.
    [[nodiscard]] const std::optional<ErrorElement>& element() const noexcept { return element_; }

  private:
    std::optional<ErrorElement> element_;
};

/// Bad file, bad argument, out-of-range option.
class InputError : public Error {
  public:
    using Error::Error;
};

/// Non-manifold, inconsistently oriented or otherwise unusable connectivity.
class TopologyError : public Error {
  public:
    using Error::Error;
};

/// Factorisation failure, no convergence, non-finite result.
class NumericalError : public Error {
  public:
    using Error::Error;
};

/// A valid request that this scheme or case does not implement.
class UnsupportedError : public Error {
  public:
    using Error::Error;
};

namespace detail {

/// Concatenates any streamable values into a string (GCC 12 has no <format>).
template <class... Args>
[[nodiscard]] std::string concat(Args&&... args) {
    std::ostringstream out;
    out.precision(17);
    (out << ... << std::forward<Args>(args));
    return out.str();
}

}  // namespace detail
}  // namespace limsurf

/// Always-on precondition check at public entry points: throws ErrorType with
/// the concatenated message when @p cond is false.
#define LIMSURF_CHECK(cond, ErrorType, ...)                                                                            \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            throw ErrorType(::limsurf::detail::concat(__VA_ARGS__));                                                   \
        }                                                                                                              \
    } while (0)

/// As LIMSURF_CHECK for an error about one mesh element (an ErrorElement: face_element(f),
/// vertex_element(v)), so that callers can name the file and line it came from.
#define LIMSURF_CHECK_AT(cond, ErrorType, element, ...)                                                                \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            throw ErrorType(::limsurf::detail::concat(__VA_ARGS__), element);                                          \
        }                                                                                                              \
    } while (0)

/// Internal invariant: active in Debug and sanitizer builds, compiled out in
/// Release (NDEBUG). A failure is a limsurf bug, reported as std::logic_error.
#ifdef NDEBUG
#define LIMSURF_ASSERT(cond, ...)                                                                                      \
    do {                                                                                                               \
    } while (0)
#else
#define LIMSURF_ASSERT(cond, ...)                                                                                      \
    do {                                                                                                               \
        if (!(cond)) {                                                                                                 \
            throw std::logic_error(::limsurf::detail::concat(                                                          \
                __FILE__, ":", __LINE__, ": internal invariant failed: ", #cond, " ", __VA_ARGS__));                   \
        }                                                                                                              \
    } while (0)
#endif
