# The limit basis (Catmull–Clark, Loop): identities on every bundled mesh.
limsurf_add_test(limit_identity_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_identity_test.cpp LABELS identity)
# Batches of points on several threads: bit for bit the point-by-point evaluation.
limsurf_add_test(limit_batch_evaluation_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/batch_evaluation_test.cpp LABELS identity)
# Peers: OpenSubdiv Far (regular patches, vertex limits, Gregory deviation) and deep subdivision.
if(TARGET limsurf::peer_opensubdiv)
    limsurf_add_test(limit_peer_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_peer_test.cpp LABELS peer
                     LIBRARIES limsurf_osd_limit limsurf_limit_reference)
    # OpenSubdiv's regression shapes (tests/data/opensubdiv_shapes): patches, holes and vertex limits.
    limsurf_add_test(limit_opensubdiv_shapes_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/opensubdiv_shapes_limit_test.cpp
                     LABELS peer LIBRARIES limsurf_osd_limit)
endif()
# Published limit masks (regular and extraordinary Catmull–Clark, Loop, boundary curve).
limsurf_add_test(limit_published_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_published_test.cpp LABELS published)
# C2g0 (c2g0-sphere-scheme-biomembranes §3.1): identities, the refined-control-point limit through
# refine_c2g0, C² at valence-3 vertices, refusals (docs/c2g0_limit.md).
limsurf_add_test(c2g0_limit_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/c2g0_limit_test.cpp LABELS identity)
target_include_directories(c2g0_limit_test PRIVATE ${PROJECT_SOURCE_DIR}/src)
find_package(Python3 REQUIRED COMPONENTS Interpreter)
# The generated C2g0 regular patch table is what tools/make_c2g0_patch.py computes, and satisfies
# partition of unity, linear reproduction and the refinement equation of the mask (1.3).
add_test(NAME c2g0_patch_table.reproducible
    COMMAND Python3::Interpreter ${PROJECT_SOURCE_DIR}/tools/make_c2g0_patch.py --check
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(c2g0_patch_table.reproducible PROPERTIES LABELS identity)
# Interpolating control points (prescribed limit positions) and the projection onto implicit surfaces.
limsurf_add_test(interpolation_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/interpolation_test.cpp LABELS identity)
