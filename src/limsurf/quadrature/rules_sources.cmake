# Quadrature rules on the interval, the square and the triangle.
target_sources(limsurf_subdiv PRIVATE ${CMAKE_CURRENT_LIST_DIR}/rules.cpp)
# No fused multiply-add where the compiler would choose it (AArch64, or x86-64 built with -mfma):
# the double-double arithmetic of the Gauss–Legendre nodes takes its product errors from std::fma
# and must round the rest as written, for the same bits on every platform.
set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/rules.cpp TARGET_DIRECTORY limsurf_subdiv PROPERTIES
    COMPILE_OPTIONS "$<$<CXX_COMPILER_ID:GNU,Clang>:-ffp-contract=off>")
