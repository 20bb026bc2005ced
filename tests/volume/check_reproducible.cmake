# Runs the volume-form generator into WORK_DIR and compares with the committed tables.
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${GENERATOR} ${WORK_DIR}/shipped_forms.cpp 12 ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "generate_volume_forms failed (${rc})")
endif()
foreach(pair "shipped_forms.cpp;${SHIPPED}" "catmull_clark_regular.txt;${EXACT_DIR}/catmull_clark_regular.txt"
        "loop_regular.txt;${EXACT_DIR}/loop_regular.txt" "doo_sabin_regular.txt;${EXACT_DIR}/doo_sabin_regular.txt")
    list(GET pair 0 generated)
    list(GET pair 1 committed)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/${generated} ${committed} RESULT_VARIABLE diff)
    if(NOT diff EQUAL 0)
        message(FATAL_ERROR "${committed} differs from what tools/volume_forms/generate_volume_forms writes; "
                            "regenerate it (see tools/volume_forms/CMakeLists.txt)")
    endif()
endforeach()
