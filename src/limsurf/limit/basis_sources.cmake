# Patch basis functions (regular B-spline and box-spline patches) and the
# differential geometry of a surface point.
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/patch_basis.cpp
    ${CMAKE_CURRENT_LIST_DIR}/surface_frame.cpp)
