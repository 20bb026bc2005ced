# Doo–Sabin limit evaluation (private evaluator, wired into LimitBasis by the lead).
target_sources(limsurf_subdiv PRIVATE ${CMAKE_CURRENT_LIST_DIR}/doo_sabin_limit.cpp)
