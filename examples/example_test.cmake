# SPDX-License-Identifier: Apache-2.0
# example_test.cmake: the flight-loop example (examples/flight_loop) built against the installed
# firmware package and run (ctest example.*, registered by examples/register_tests.cmake).
#   cmake -DMODE=<mode> -DSOURCE=<examples/flight_loop> -DWORK=<dir> -DPREFIX=<install prefix>
#         -DGENERATOR=<gen> -DREAL_FLOAT=0|1 -DCROSS=0|1 [-DTOOLCHAIN=<file>]
#         [-DC_COMPILER=<cc>] [-DC_FLAGS=<flags>] [-DLINK_FLAGS=<flags>] [-DBUILD_TYPE=<type>]
#         -P example_test.cmake
# MODE
#   build     configure and build the example in WORK against PREFIX, as a user would
#             (find_package(uvms_firmware CONFIG REQUIRED)); cross builds: the image for QEMU
#             mps2-an386 with the example's own startup and linker script
#   nominal   run it (host, or QEMU with -icount shift=5,sleep=off): exit code 0 (the image's
#             own checks passed), 200 ticks, 200 steps, no missed tick, no overrun; statuses
#             198 UVMS_OK and 2 UVMS_ERR_NONFINITE; 6 ticks held on the last good record
#             (tick 60's bad quaternion, the first 5 of the NaN burst 120..126), the safe
#             output on ticks 125 and 126 (status NONFINITE, flags SENSOR_NONFINITE |
#             SENSOR_HOLD_EXPIRED = 0x00040001, no force, current command 0); station held
#             within the bound; 7 configuration checks, no change; on the Cortex-M4F the
#             longest step under 10 % of the 30 ms tick
#   stall     run it with stall_at=150 (a 2.5-tick stall after tick 150's step): 2 overruns,
#             199 steps, tick 151 missed, TICK_GAP (0x00000020) reported on tick 152
#   config_upset  run it with config_upset_at=90 (a bit of the configuration flipped after
#             tick 90): the configuration check on tick 99 finds the change (uvms_ctrl_config_
#             verify), the controller is initialised again and captures its station anew on
#             tick 100 (REFERENCE_CAPTURED, 0x00000400); statuses as in the nominal run
foreach(var MODE SOURCE WORK PREFIX GENERATOR CROSS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "example_test.cmake: ${var} is not set")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../cmake/package_consumer.cmake)  # run_checked, args

function(expect_lines output)
  foreach(regex ${ARGN})
    if(NOT output MATCHES "${regex}")
      message(FATAL_ERROR "expected '${regex}' in the example's output:\n${output}")
    endif()
  endforeach()
endfunction()

if(MODE STREQUAL "build")
  file(REMOVE_RECURSE ${WORK})
  package_consumer_args(args ${SOURCE} ${WORK})
  run_checked(${CMAKE_COMMAND} ${args})
  run_checked(${CMAKE_COMMAND} --build ${WORK})
  if(CROSS)
    string(REGEX MATCH "FLASH:[^\n]*\n[^\n]*RAM:[^\n]*" usage "${out}")
    message(STATUS "flight_loop.elf memory use:\n${usage}")
  endif()
  message(STATUS "built ${WORK}")
elseif(MODE STREQUAL "nominal" OR MODE STREQUAL "stall" OR MODE STREQUAL "config_upset")
  if(MODE STREQUAL "nominal")
    set(test flight_loop)
  else()
    set(test flight_loop_${MODE})
  endif()
  execute_process(COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${WORK} -R "^${test}$" -V
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  # ctest -V prefixes each output line with "<n>: ".
  string(REGEX REPLACE "(^|\n)[0-9]+: " "\\1" out "${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "the example's run failed (exit code != 0: failed checks):\n${out}")
  endif()
  set(safe_output "\nT,125,UVMS_ERR_NONFINITE,0x00040001,-?[0-9]+,-?[0-9]+,-?[0-9]+,0,0,0,[0-9]+\n")
  if(MODE STREQUAL "nominal")
    expect_lines("${out}"
      "summary: ticks 200 steps 200 missed 0 overruns 0\n"
      "summary: status ok 198 nonfinite 2 range 0 singular 0 state 0 other 0 [|] held 6 safe_output 2 tick_gap 0\n"
      "summary: config checks 7 changed 0 reinit 0\n"
      "\nT,60,UVMS_OK,0x00020002,"
      "\nT,124,UVMS_OK,0x00020001,"
      "${safe_output}"
      "\nT,126,UVMS_ERR_NONFINITE,0x00040001,"
      "-> PASS [(]0 failed checks[)]")
  elseif(MODE STREQUAL "config_upset")
    # Statuses as in the nominal run; the change found on tick 99; the station captured anew on
    # tick 100 (REFERENCE_CAPTURED, 0x400).
    expect_lines("${out}"
      "summary: ticks 200 steps 200 missed 0 overruns 0\n"
      "summary: status ok 198 nonfinite 2 range 0 singular 0 state 0 other 0 [|] held 6 safe_output 2 tick_gap 0\n"
      "summary: config checks 7 changed 1 reinit 1\n"
      "\nT,100,UVMS_OK,0x00000400,"
      "${safe_output}"
      "-> PASS [(]0 failed checks[)]")
  else()
    expect_lines("${out}"
      "summary: ticks 200 steps 199 missed 1 overruns 2\n"
      "summary: status ok 197 nonfinite 2 range 0 singular 0 state 0 other 0 [|] held 6 safe_output 2 tick_gap 1\n"
      "summary: config checks 7 changed 0 reinit 0\n"
      "${safe_output}"
      "\nT,152,UVMS_OK,0x00000020,"
      "-> PASS [(]0 failed checks[)]")
    if(out MATCHES "\nT,151,")
      message(FATAL_ERROR "tick 151 was stepped although the stall covered it:\n${out}")
    endif()
  endif()
  string(REGEX MATCH "summary: step_us max ([0-9]+)" timing "${out}")
  set(step_us_max ${CMAKE_MATCH_1})
  if(CROSS AND NOT step_us_max LESS 3000)
    message(FATAL_ERROR "the longest step took ${step_us_max} us, over 10 % of the 30 ms tick:\n${out}")
  endif()
  string(REGEX MATCHALL "summary: [^\n]*" summary "${out}")
  string(REPLACE ";" "\n" summary "${summary}")
  message(STATUS "${summary}")
else()
  message(FATAL_ERROR "example_test.cmake: unknown MODE '${MODE}'")
endif()
