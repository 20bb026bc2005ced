# Runs instruction_set_hashes natively and under qemu-user's emulated x86-64 CPUs without AVX
# (qemu64: the SSE2 copy of every LIMSURF_TARGET_CLONES kernel) and without AVX-512 (Haswell: the
# AVX2 copy), and requires the same hashes from all: the copies sum in one order and are compiled
# with -ffp-contract=off, so they must give the same bits. The native run covers AVX-512 when the
# machine has it (its cpu line says). Skipped, saying so, without qemu-x86_64 (Debian qemu-user,
# installed by scripts/setup.sh) or off x86-64.
#   cmake -DPROGRAM=<instruction_set_hashes> -DQEMU=<qemu-x86_64 or empty> -P same_bits_on_every_cpu.cmake
function(run_hashes out_var)
    execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "`${ARGN}` failed (${rc}): ${err}")
    endif()
    set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

run_hashes(native ${PROGRAM})
string(REGEX MATCH "^cpu: [^\n]*" native_cpu "${native}")
string(REGEX REPLACE "^cpu: [^\n]*\n" "" native_hashes "${native}")
message("native (${native_cpu}):\n${native_hashes}")
if(native_cpu STREQUAL "cpu: not x86-64")
    message("SKIPPED: not an x86-64 machine: there are no instruction-set copies to compare")
    return()
endif()
if(NOT QEMU)
    message("SKIPPED: qemu-x86_64 (Debian qemu-user, scripts/setup.sh) is not installed: the SSE2 and AVX2 "
            "copies were not run")
    return()
endif()
foreach(case "qemu64|cpu: avx2 0 avx512f 0" "Haswell-noTSX|cpu: avx2 1 avx512f 0")
    string(REPLACE "|" ";" case "${case}")
    list(GET case 0 cpu)
    list(GET case 1 expected_cpu)
    run_hashes(emulated ${QEMU} -cpu ${cpu} ${PROGRAM})
    string(REGEX MATCH "^cpu: [^\n]*" emulated_cpu "${emulated}")
    string(REGEX REPLACE "^cpu: [^\n]*\n" "" emulated_hashes "${emulated}")
    if(NOT emulated_cpu STREQUAL expected_cpu)
        message(FATAL_ERROR "qemu -cpu ${cpu} reports `${emulated_cpu}`, expected `${expected_cpu}`")
    endif()
    if(NOT emulated_hashes STREQUAL native_hashes)
        message(FATAL_ERROR "qemu -cpu ${cpu} (${emulated_cpu}) gives other bits than the native run:\n"
                            "${emulated_hashes}")
    endif()
    message("qemu -cpu ${cpu} (${emulated_cpu}): the same hashes")
endforeach()
