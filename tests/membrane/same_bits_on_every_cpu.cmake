# Runs instruction_set_hashes natively and under qemu-user's emulated x86-64 CPUs without AVX
# (qemu64: the SSE2 copy of every LIMSURF_TARGET_CLONES kernel) and without AVX-512 (Haswell: the
# AVX2 copy), and requires the same hashes from all: the copies sum in one order and are compiled
# with -ffp-contract=off, so they must give the same bits. The native run covers AVX-512 when the
# machine has it (its cpu line says). Skipped, saying so, without qemu-x86_64 (Debian qemu-user,
# installed by scripts/setup.sh) or off x86-64; a copy is skipped, saying so, where the qemu knows
# none of the CPU models listed for it.
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
# The CPU models this qemu knows (`-cpu help`): each copy runs under the first model listed for it
# (qemu 7.2, Debian 12, has all of them; the names come and go between qemu versions).
# (qemu-user exits with 1 after listing them.)
execute_process(COMMAND ${QEMU} -cpu help OUTPUT_VARIABLE models ERROR_QUIET)
if(NOT models MATCHES "\nx86 ")
    message(FATAL_ERROR "`${QEMU} -cpu help` listed no x86 CPU model")
endif()
foreach(case "SSE2|qemu64,kvm64|cpu: avx2 0 avx512f 0"
             "AVX2|Haswell-noTSX,Haswell,Broadwell-noTSX,Broadwell,Skylake-Client|cpu: avx2 1 avx512f 0")
    string(REPLACE "|" ";" case "${case}")
    list(GET case 0 copy)
    list(GET case 1 models_wanted)
    list(GET case 2 expected_cpu)
    string(REPLACE "," ";" candidates "${models_wanted}")
    set(cpu "")
    foreach(candidate IN LISTS candidates)
        if(models MATCHES "(^|\n)x86 +${candidate}[ \n]")
            set(cpu ${candidate})
            break()
        endif()
    endforeach()
    if(NOT cpu)
        message("SKIPPED: the ${copy} copy was not run: ${QEMU} knows none of the CPU models ${models_wanted}")
        continue()
    endif()
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
