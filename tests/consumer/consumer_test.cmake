# SPDX-License-Identifier: Apache-2.0
# consumer_test.cmake: the installed firmware package as an application sees it (ctest
# consumer.*, registered by tests/consumer/register_tests.cmake). Uses the already built library.
#   cmake -DMODE=<mode> -DBUILD_DIR=<uvms build> -DPREFIX=<install prefix> -DWORK=<dir>
#         -DGENERATOR=<gen> -DREAL_FLOAT=0|1 [-DTOOLCHAIN=<file> -DBOARD_DIR=<dir>]
#         [-DC_COMPILER=<cc>] [-DC_FLAGS=<flags>] [-DLINK_FLAGS=<flags>] [-DBUILD_TYPE=<type>]
#         -P consumer_test.cmake
# MODE
#   install          cmake --install BUILD_DIR into a fresh PREFIX
#   paper_step       configure and build tests/consumer against PREFIX, run it (on the host or
#                    the emulated Cortex-M4F): status UVMS_OK, the library's precision
#   ask_other        the consumer passes -DUVMS_REAL_FLOAT=<the other precision>: the build must
#                    fail with the headers' "uvms precision mismatch" error naming the library's
#   stale_header     the consumer compiles against a copy of uvms/config.h of the other
#                    precision: the build must fail at link time, naming the missing precision
#                    marker uvms_abi_real_<other>_v1
foreach(var MODE BUILD_DIR PREFIX WORK GENERATOR REAL_FLOAT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "consumer_test.cmake: ${var} is not set")
  endif()
endforeach()
set(consumer_source ${CMAKE_CURRENT_LIST_DIR})
if(REAL_FLOAT)
  set(lib_precision float)
  set(other_precision double)
  set(other_flag 0)
else()
  set(lib_precision double)
  set(other_precision float)
  set(other_flag 1)
endif()

include(${CMAKE_CURRENT_LIST_DIR}/../../cmake/package_consumer.cmake)  # run_checked, args

# Configure the consumer in WORK with the extra cache arguments; returns the build's output and
# exit code in build_out / build_rc.
function(configure_and_build)
  file(REMOVE_RECURSE ${WORK})
  package_consumer_args(args ${consumer_source} ${WORK})
  if(TOOLCHAIN)
    list(APPEND args -DUVMS_CONSUMER_BOARD_DIR=${BOARD_DIR})
  endif()
  run_checked(${CMAKE_COMMAND} ${args} ${ARGN})
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  set(build_out "${out}" PARENT_SCOPE)
  set(build_rc "${rc}" PARENT_SCOPE)
endfunction()

function(expect_build_failure regex)
  if(build_rc EQUAL 0)
    message(FATAL_ERROR "the mismatched consumer built; expected a failure matching '${regex}'")
  endif()
  if(NOT build_out MATCHES "${regex}")
    message(FATAL_ERROR "the build failed, but not with '${regex}':\n${build_out}")
  endif()
  string(REGEX MATCH "[^\n]*${regex}[^\n]*" line "${build_out}")
  message(STATUS "refused as expected: ${line}")
endfunction()

if(MODE STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  run_checked(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(f include/uvms/config.h include/uvms/types.h include/uvms/controller.h
            include/uvms/version.h lib/cmake/uvms_firmware/uvms_firmware-config.cmake)
    if(NOT EXISTS ${PREFIX}/${f})
      message(FATAL_ERROR "not installed: ${PREFIX}/${f}")
    endif()
  endforeach()
  message(STATUS "installed into ${PREFIX}")
elseif(MODE STREQUAL "paper_step")
  configure_and_build(-DUVMS_CONSUMER_EXPECT_FLOAT=${REAL_FLOAT})
  if(NOT build_rc EQUAL 0)
    message(FATAL_ERROR "the consumer did not build:\n${build_out}")
  endif()
  run_checked(${CMAKE_CTEST_COMMAND} --test-dir ${WORK} --output-on-failure -V)
  set(expected "precision ${lib_precision}, step status UVMS_OK")
  if(NOT out MATCHES "${expected}")
    message(FATAL_ERROR "expected '${expected}' in the consumer's output:\n${out}")
  endif()
  string(REGEX MATCH "uvms consumer: [^\n]*" line "${out}")
  message(STATUS "${line}")
elseif(MODE STREQUAL "ask_other")
  configure_and_build(-DUVMS_CONSUMER_ASK_REAL_FLOAT=${other_flag})
  expect_build_failure("uvms precision mismatch: the uvms_firmware library was built with ${lib_precision}")
elseif(MODE STREQUAL "stale_header")
  # A copy of the installed config.h, rewritten to the other precision.
  file(READ ${PREFIX}/include/uvms/config.h config)
  string(REGEX REPLACE "#define UVMS_CONFIG_REAL_FLOAT [01]"
         "#define UVMS_CONFIG_REAL_FLOAT ${other_flag}" config "${config}")
  file(WRITE ${WORK}-stale/uvms/config.h "${config}")
  configure_and_build(-DUVMS_CONSUMER_STALE_CONFIG_DIR=${WORK}-stale)
  expect_build_failure("undefined reference to .uvms_abi_real_${other_precision}_v1")
else()
  message(FATAL_ERROR "consumer_test.cmake: unknown MODE '${MODE}'")
endif()
