# SPDX-License-Identifier: Apache-2.0
# cmake/ccache.cmake: compile C and C++ through ccache (Debian's, installed by tools/bootstrap)
# when it is found and UVMS_CCACHE is ON (the default).
#
# The cache: for the presets' build directories (build/<preset>), build/ccache beside them, so a
# fresh clone starts with an empty cache (the fresh-clone CI time is not helped by earlier runs)
# and deleting build/ deletes it; for a build directory elsewhere, <build dir>/ccache; where
# CCACHE_DIR is set in the environment when configuring, that cache. CCACHE_BASEDIR is the source
# directory, so ccache hashes the paths under it relative to each build directory: a translation
# unit that is the same text with the same flags in two presets (the truth model and the LCM
# types in host and host-float, which differ only in the controller's real type) is compiled
# once. Anything that differs (flags, a header's contents such as
# build/<preset>/firmware/include/uvms/config.h) is a miss, compiled as usual. Compiler messages
# keep absolute paths (CCACHE_ABSSTDERR). `ccache -s` with CCACHE_DIR set so prints the hit rate.
option(UVMS_CCACHE "Compile through ccache when it is installed (cache in build/ccache)" ON)
if(UVMS_CCACHE AND NOT CMAKE_C_COMPILER_LAUNCHER AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(UVMS_CCACHE_PROGRAM ccache)
  find_program(UVMS_ENV_PROGRAM env) # coreutils; `cmake -E env` costs ~14 ms per compile
  if(DEFINED ENV{CCACHE_DIR})
    set(uvms_ccache_dir "$ENV{CCACHE_DIR}")
  else()
    cmake_path(GET CMAKE_BINARY_DIR PARENT_PATH uvms_binary_parent)
    if(uvms_binary_parent STREQUAL "${PROJECT_SOURCE_DIR}/build")
      set(uvms_ccache_dir "${PROJECT_SOURCE_DIR}/build/ccache")
    else()
      set(uvms_ccache_dir "${CMAKE_BINARY_DIR}/ccache")
    endif()
  endif()
  if(NOT UVMS_CCACHE_PROGRAM)
    message(STATUS "ccache not found: compiling without it (tools/bootstrap installs it)")
  elseif(NOT UVMS_ENV_PROGRAM)
    message(STATUS "env (coreutils) not found: compiling without ccache")
  else()
    # pch_defines,time_macros: what ccache asks before it caches a file compiled with a
    # precompiled header (the tests' uvms_test_pch, tests/CMakeLists.txt).
    set(uvms_launcher ${UVMS_ENV_PROGRAM} "CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}"
        "CCACHE_DIR=${uvms_ccache_dir}" "CCACHE_SLOPPINESS=pch_defines,time_macros"
        "CCACHE_ABSSTDERR=1" ${UVMS_CCACHE_PROGRAM})
    set(CMAKE_C_COMPILER_LAUNCHER ${uvms_launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${uvms_launcher})
    message(STATUS "Compiling through ccache: ${UVMS_CCACHE_PROGRAM} (cache ${uvms_ccache_dir})")
  endif()
endif()
