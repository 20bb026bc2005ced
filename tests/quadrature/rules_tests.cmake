# Quadrature rules: exactness, symmetry, positivity.
limsurf_add_test(quadrature_rules_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/rules_test.cpp LABELS unit)
