# SPDX-License-Identifier: Apache-2.0
# package_consumer.cmake: shared by the script-mode tests that build a project against the
# INSTALLED firmware package as a user would (tests/consumer/consumer_test.cmake,
# examples/example_test.cmake).
#
#   run_checked(<command> ...)            runs it; a non-zero exit is a FATAL_ERROR with its
#                                         output; the output is left in `out`
#   package_consumer_args(<var> <source> <work>)
#                                         the configure arguments of <source> in <work> against
#                                         PREFIX: generator GENERATOR, and when set BUILD_TYPE,
#                                         TOOLCHAIN, C_COMPILER, C_FLAGS, LINK_FLAGS (variables
#                                         of the calling script)

function(run_checked)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "FAILED (${rc}): ${ARGN}\n${out}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

function(package_consumer_args var source work)
  set(args -S ${source} -B ${work} -G ${GENERATOR} -DCMAKE_PREFIX_PATH=${PREFIX})
  if(BUILD_TYPE)
    list(APPEND args -DCMAKE_BUILD_TYPE=${BUILD_TYPE})
  endif()
  if(TOOLCHAIN)
    list(APPEND args -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN})
  endif()
  if(C_COMPILER)
    list(APPEND args -DCMAKE_C_COMPILER=${C_COMPILER})
  endif()
  if(C_FLAGS)
    list(APPEND args "-DCMAKE_C_FLAGS=${C_FLAGS}")
  endif()
  if(LINK_FLAGS)
    list(APPEND args "-DCMAKE_EXE_LINKER_FLAGS=${LINK_FLAGS}")
  endif()
  set(${var} "${args}" PARENT_SCOPE)
endfunction()
