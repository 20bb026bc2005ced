# Doo–Sabin refinement (docs/doo_sabin.md).
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/doo_sabin.cpp)
