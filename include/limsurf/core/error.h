// The library's exception hierarchy (DESIGN.md §6, docs/coding_style.md).
//
// Everything the library throws derives from limsurf::Error. Messages name the
// element and, when the data came from a file, the file and line:
//     "mesh.obj:14: face 7 repeats vertex 3"
// The CLI prints "error: " + what() and exits 1.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace limsurf {

/// Root of every exception limsurf throws.
class Error : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
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
