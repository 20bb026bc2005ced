# References for the limit basis (test support, no library code shared with it):
#   limsurf_limit_reference  deep subdivision with limsurf's refinement + regular patches
#   limsurf_osd_limit        OpenSubdiv Far limit positions and patch evaluation (peer)
# and their self-test osd_harness_test (peer): both agree on regular patches.
add_library(limsurf_limit_reference STATIC ${CMAKE_CURRENT_LIST_DIR}/support/deep_subdivision.cpp)
target_include_directories(limsurf_limit_reference PUBLIC ${CMAKE_CURRENT_LIST_DIR}/support)
target_link_libraries(limsurf_limit_reference PUBLIC limsurf_test_support PRIVATE limsurf::warnings)

if(TARGET limsurf::peer_opensubdiv)
    add_library(limsurf_osd_limit STATIC ${CMAKE_CURRENT_LIST_DIR}/support/osd_limit.cpp)
    target_include_directories(limsurf_osd_limit PUBLIC ${CMAKE_CURRENT_LIST_DIR}/support)
    target_link_libraries(limsurf_osd_limit PUBLIC limsurf_test_support limsurf::peer_opensubdiv PRIVATE limsurf::warnings)
    limsurf_add_test(osd_harness_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/osd_harness_test.cpp LABELS peer
                     LIBRARIES limsurf_osd_limit limsurf_limit_reference)
endif()
