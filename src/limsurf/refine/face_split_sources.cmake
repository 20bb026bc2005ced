# Catmull–Clark, Loop, bilinear, linear refinement (face-split schemes).
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/catmull_clark.cpp
    ${CMAKE_CURRENT_LIST_DIR}/loop.cpp
    ${CMAKE_CURRENT_LIST_DIR}/bilinear.cpp
    ${CMAKE_CURRENT_LIST_DIR}/linear.cpp
    ${CMAKE_CURRENT_LIST_DIR}/c2g0.cpp
    ${CMAKE_CURRENT_LIST_DIR}/../detail/c2g0_stencils.cpp
    ${CMAKE_CURRENT_LIST_DIR}/../detail/refine_face_split.cpp)
# Form subdivision (S1, S2) for Loop and Catmull–Clark.
target_sources(limsurf_subdiv PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/form_subdivision.cpp
    ${CMAKE_CURRENT_LIST_DIR}/loop_forms.cpp
    ${CMAKE_CURRENT_LIST_DIR}/catmull_clark_forms.cpp)
