# Patch basis functions and the differential geometry of a surface point.
limsurf_add_test(patch_basis_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/patch_basis_test.cpp LABELS unit)
limsurf_add_test(surface_frame_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/surface_frame_test.cpp LABELS unit)
