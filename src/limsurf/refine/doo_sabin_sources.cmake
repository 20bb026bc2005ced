# Doo–Sabin refinement.
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/doo_sabin_stub.cpp)
