# The limit sampler and the integrals: identities, an analytic value, deep subdivision as witness.
limsurf_add_test(quadrature_integrals_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/integrals_test.cpp LABELS identity)
