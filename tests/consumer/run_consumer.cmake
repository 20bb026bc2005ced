# Installs limsurf into SCRATCH_DIR/prefix, then builds and runs the consumer project against it.
file(REMOVE_RECURSE ${SCRATCH_DIR})
set(prefix ${SCRATCH_DIR}/prefix)

function(run)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT result EQUAL 0)
        message(FATAL_ERROR "command failed (${result}): ${ARGN}\n${out}\n${err}")
    endif()
    set(last_output "${out}" PARENT_SCOPE)
endfunction()

run(${CMAKE_COMMAND} --install ${LIMSURF_BINARY_DIR} --prefix ${prefix})
# The same compiler and flags as the build under test (a sanitizer build's
# library needs the sanitizer runtime in the consumer too).
run(${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${SCRATCH_DIR}/build -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CONSUMER_CXX_COMPILER}
    "-DCMAKE_CXX_FLAGS=${CONSUMER_CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${CONSUMER_LINKER_FLAGS}")
run(${CMAKE_COMMAND} --build ${SCRATCH_DIR}/build)
run(${SCRATCH_DIR}/build/consumer ${MESH})
if(NOT last_output MATCHES "vertices=8 edges=12 faces=6 genus=0")
    message(FATAL_ERROR "unexpected consumer output: ${last_output}")
endif()
message(STATUS "consumer: ${last_output}")

# The Python module, when built: `make install` put it where the prefix's Python finds it.
if(PYTHON AND PYTHON_DIR)
    set(ENV{PYTHONPATH} ${prefix}/${PYTHON_DIR})
    # (no semicolons in the code: run() passes its arguments on as a CMake list)
    run(${PYTHON} -c "import limsurf, sys
assert limsurf.__file__.startswith('${prefix}'), limsurf.__file__
m = limsurf.read_mesh(sys.argv[1])
print('python', m.num_vertices, m.num_edges, m.num_faces, m.genus)" ${MESH})
    if(NOT last_output MATCHES "python 8 12 6 0")
        message(FATAL_ERROR "unexpected output of the installed Python module: ${last_output}")
    endif()
    message(STATUS "consumer: ${last_output}")
endif()
