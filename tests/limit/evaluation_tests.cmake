# The limit basis (Catmull–Clark, Loop): identities on every bundled mesh.
limsurf_add_test(limit_identity_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_identity_test.cpp LABELS identity)
# Peers: OpenSubdiv Far (regular patches, vertex limits, Gregory deviation) and deep subdivision.
if(TARGET limsurf::peer_opensubdiv)
    limsurf_add_test(limit_peer_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_peer_test.cpp LABELS peer
                     LIBRARIES limsurf_osd_limit limsurf_limit_reference)
endif()
# Published limit masks (regular and extraordinary Catmull–Clark, Loop, boundary curve).
limsurf_add_test(limit_published_test SOURCES ${CMAKE_CURRENT_LIST_DIR}/evaluation_published_test.cpp LABELS published)
