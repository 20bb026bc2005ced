// Wall-clock bounds in the tests: they hold for optimised builds (`make test`, CI). Debug and
// sanitizer builds (`make asan`) run 5–20× slower, so there the bounds are scaled; a path that is
// quadratic in the input still breaks them (it takes minutes, not seconds).
#pragma once

namespace limsurf::test {

#ifdef NDEBUG
inline constexpr double time_scale = 1.0;
#else
inline constexpr double time_scale = 25.0;
#endif

}  // namespace limsurf::test
