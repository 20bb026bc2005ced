# Quadrature rules on the interval, the square and the triangle.
target_sources(limsurf_subdiv PRIVATE ${CMAKE_CURRENT_LIST_DIR}/rules.cpp)
