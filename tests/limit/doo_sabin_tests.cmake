# Doo–Sabin limit evaluation (src/limsurf/limit/doo_sabin_limit.h, a private header).
limsurf_add_test(doo_sabin_limit_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/doo_sabin_limit_test.cpp LABELS identity)
target_include_directories(doo_sabin_limit_test PRIVATE ${PROJECT_SOURCE_DIR}/src)
# Published: the Doo–Sabin cube volume 6241/9920, face-centroid invariance, planar meshes.
limsurf_add_test(doo_sabin_limit_published_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/doo_sabin_limit_published_test.cpp
                 LABELS published)
target_include_directories(doo_sabin_limit_published_test PRIVATE ${PROJECT_SOURCE_DIR}/src)
