# SPDX-License-Identifier: Apache-2.0
# check_no_alloc.cmake -DNM=<nm> -DLIB=<archive>
# Fails if the archive references (undefined symbol) or defines any dynamic-allocation
# function. Run as a POST_BUILD step of the firmware library and as a ctest test.
if(NOT NM OR NOT LIB)
  message(FATAL_ERROR "usage: cmake -DNM=nm -DLIB=libfoo.a -P check_no_alloc.cmake")
endif()
execute_process(COMMAND ${NM} -u ${LIB} OUTPUT_VARIABLE undef RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} -u ${LIB} failed: ${err}")
endif()
set(forbidden malloc calloc realloc free aligned_alloc posix_memalign memalign _malloc_r
    _calloc_r _realloc_r _free_r _sbrk sbrk)
set(found "")
foreach(sym IN LISTS forbidden)
  if(undef MATCHES "(^|\n)[ \t]*U[ \t]+${sym}(\n|$)")
    list(APPEND found ${sym})
  endif()
endforeach()
if(found)
  message(FATAL_ERROR "firmware library ${LIB} references dynamic allocation: ${found}")
endif()
string(REGEX MATCHALL "U [A-Za-z_0-9]+" refs "${undef}")
list(REMOVE_DUPLICATES refs)
string(REPLACE "U " "" refs "${refs}")
list(LENGTH refs nrefs)
message(STATUS "no-alloc check passed: ${LIB} has ${nrefs} external references, none to allocation: ${refs}")
