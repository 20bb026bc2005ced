# The limit basis of Catmull–Clark and Loop: local patches and their evaluation.
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/limit_basis.cpp
    ${CMAKE_CURRENT_LIST_DIR}/local_patch.cpp)
