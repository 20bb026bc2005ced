# limsurf::warnings: the project's warning flags, linked PRIVATE into every
# target we compile (never set globally, never exported to users).
add_library(limsurf_warnings INTERFACE)
add_library(limsurf::warnings ALIAS limsurf_warnings)
target_compile_options(limsurf_warnings INTERFACE
    $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow>)
if(LIMSURF_WARNINGS_AS_ERRORS)
    target_compile_options(limsurf_warnings INTERFACE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
endif()
