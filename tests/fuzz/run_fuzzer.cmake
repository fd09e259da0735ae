# SPDX-License-Identifier: Apache-2.0
# run_fuzzer.cmake: one ctest step of a libFuzzer target (tests/fuzz/CMakeLists.txt).
#
#   cmake -DMODE=run    -DFUZZER=exe -DWORK=dir -DSEEDS="d1;d2" -DSECONDS=25 -DOPTIONS="a;b"
#         -P run_fuzzer.cmake
#     A fresh copy of every file of the seed directories goes to WORK/corpus (the source tree
#     is only read), then the fuzzer runs for SECONDS on it; what it finds lands in
#     WORK/artifacts/ and fails the test.
#   cmake -DMODE=nightly (as run) -P run_fuzzer.cmake
#     As run, but WORK/corpus is kept between runs (target fuzz_nightly) and the environment
#     variable UVMS_FUZZ_NIGHTLY_SECONDS, when set, overrides SECONDS.
#   cmake -DMODE=replay -DFUZZER=exe -DSEEDS="d1;d2" -P run_fuzzer.cmake
#     Every file of the directories is run once (libFuzzer's file arguments), nothing else.
foreach(v MODE FUZZER SEEDS)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "run_fuzzer.cmake: -D${v}= is required")
  endif()
endforeach()

set(files "")
set(i 0)
foreach(dir IN LISTS SEEDS)
  if(NOT IS_DIRECTORY "${dir}")
    message(FATAL_ERROR "run_fuzzer.cmake: seed directory ${dir} does not exist")
  endif()
  file(GLOB these LIST_DIRECTORIES false "${dir}/*")
  list(SORT these)
  foreach(f IN LISTS these)
    list(APPEND files "${f}")
  endforeach()
endforeach()

if(MODE STREQUAL "replay")
  list(LENGTH files n)
  message(STATUS "replaying ${n} inputs through ${FUZZER}")
  if(n EQUAL 0)
    return()
  endif()
  execute_process(COMMAND "${FUZZER}" ${OPTIONS} ${files} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "a regression input fails again (exit ${rc}): see the output above")
  endif()
  return()
endif()

if(NOT (MODE STREQUAL "run" OR MODE STREQUAL "nightly") OR NOT WORK OR NOT SECONDS)
  message(FATAL_ERROR "run_fuzzer.cmake: MODE=run|nightly needs -DWORK= and -DSECONDS=")
endif()
if(MODE STREQUAL "nightly")
  # The corpus stays (it grows night after night; the seeds are copied over it again), the
  # artifacts of a previous night are cleared; UVMS_FUZZ_NIGHTLY_SECONDS in the environment
  # overrides SECONDS.
  if(DEFINED ENV{UVMS_FUZZ_NIGHTLY_SECONDS} AND NOT "$ENV{UVMS_FUZZ_NIGHTLY_SECONDS}" STREQUAL "")
    set(SECONDS "$ENV{UVMS_FUZZ_NIGHTLY_SECONDS}")
  endif()
  file(REMOVE_RECURSE "${WORK}/artifacts")
else()
  file(REMOVE_RECURSE "${WORK}")
endif()
file(MAKE_DIRECTORY "${WORK}/corpus" "${WORK}/artifacts")
foreach(f IN LISTS files)
  # Prefixed by a counter: seed files of different directories may share a name.
  get_filename_component(name "${f}" NAME)
  math(EXPR i "${i} + 1")
  file(COPY_FILE "${f}" "${WORK}/corpus/seed${i}_${name}")
endforeach()
message(STATUS "fuzzing ${FUZZER} for ${SECONDS} s from ${i} seeds in ${WORK}/corpus")
execute_process(
  COMMAND "${FUZZER}" ${OPTIONS} -max_total_time=${SECONDS} -print_final_stats=1
          "-artifact_prefix=${WORK}/artifacts/" "${WORK}/corpus"
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  file(GLOB found "${WORK}/artifacts/*")
  message(FATAL_ERROR "the fuzzer found something (exit ${rc}): ${found}\n"
          "Reproduce: ${FUZZER} <artifact>. Once fixed, copy it into "
          "tests/fuzz/regressions/<target>/ (tests/fuzz/README.md).")
endif()
