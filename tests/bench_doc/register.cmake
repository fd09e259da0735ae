# SPDX-License-Identifier: Apache-2.0
# register.cmake (included by the top-level CMakeLists.txt in every build; registers a test in
# the cortex-m4f build only, where the benchmark image exists): the generated footprint and
# Cortex-M4F tick table of docs/BENCHMARKS.md must equal a fresh measurement.
#
# docs.benchmarks_footprint_table_is_current runs bench/footprint_table.py in compare
# mode on this build's benchmark image (NO_BUILD=1: ctest runs after the build): QEMU with the
# instruction-counting plugin, compiled by the script with cc (HOST_BUILD=none: no host build
# needed), cases IV and VII over 2000 ticks each (about 2 s), and the double size probe compiled
# for the host. Instruction counts and sizes are exact, so the comparison is exact. On a
# difference it prints the diff and the command that regenerates the table.
if(CMAKE_CROSSCOMPILING AND UVMS_FIRMWARE_ONLY)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  add_test(NAME docs.benchmarks_footprint_table_is_current
    COMMAND ${CMAKE_COMMAND} -E env M4F_BUILD=${PROJECT_BINARY_DIR} HOST_BUILD=none NO_BUILD=1
            BENCH_OUT=${PROJECT_BINARY_DIR}/bench_doc
            ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/bench/footprint_table.py
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(docs.benchmarks_footprint_table_is_current PROPERTIES
                       LABELS "docs;target" TIMEOUT 300)
endif()
