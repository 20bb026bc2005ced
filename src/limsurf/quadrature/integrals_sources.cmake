# The limit sampler (quadrature samples with precomputed limit weights) and the
# integrals built on it: area, enclosed volume, centroids, gradients, error estimates.
target_sources(limsurf_subdiv PRIVATE ${CMAKE_CURRENT_LIST_DIR}/sampler.cpp ${CMAKE_CURRENT_LIST_DIR}/integrals.cpp)
