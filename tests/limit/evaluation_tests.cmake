# The limit basis (Catmull–Clark, Loop): identities on every bundled mesh.
limsurf_add_test(limit_identity_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_identity_test.cpp LABELS identity)
