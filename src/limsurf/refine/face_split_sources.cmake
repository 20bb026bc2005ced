# Catmull–Clark, Loop, bilinear, linear refinement (face-split schemes).
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/face_split_stub.cpp)
