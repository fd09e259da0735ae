# SPDX-License-Identifier: Apache-2.0
# cmake/ccache.cmake: compile C and C++ through ccache (Debian's, installed by tools/bootstrap)
# when it is found and UVMS_CCACHE is ON (the default).
#
# The cache lives in build/ccache, beside the preset build directories: a fresh clone starts
# with an empty cache (the fresh-clone CI time is not helped by earlier runs), and deleting
# build/ deletes it. CCACHE_BASEDIR is the source directory, so ccache hashes the paths under it
# relative to each build directory: a translation unit that is the same text with the same
# flags in two presets (the truth model and the LCM types in host and host-float, which differ
# only in the controller's real type) is compiled once. Anything that differs (flags, a header's
# contents such as build/<preset>/firmware/include/uvms/config.h) is a miss, compiled as usual.
# `ccache -s` with CCACHE_DIR=build/ccache prints the hit rate.
option(UVMS_CCACHE "Compile through ccache when it is installed (cache in build/ccache)" ON)
if(UVMS_CCACHE AND NOT CMAKE_C_COMPILER_LAUNCHER AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(UVMS_CCACHE_PROGRAM ccache)
  find_program(UVMS_ENV_PROGRAM env) # coreutils; `cmake -E env` costs ~14 ms per compile
  if(UVMS_CCACHE_PROGRAM AND UVMS_ENV_PROGRAM)
    # pch_defines,time_macros: what ccache asks before it caches a file compiled with a
    # precompiled header (the tests' uvms_test_pch, tests/CMakeLists.txt).
    set(uvms_launcher ${UVMS_ENV_PROGRAM} "CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}"
        "CCACHE_DIR=${PROJECT_SOURCE_DIR}/build/ccache" "CCACHE_SLOPPINESS=pch_defines,time_macros"
        ${UVMS_CCACHE_PROGRAM})
    set(CMAKE_C_COMPILER_LAUNCHER ${uvms_launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${uvms_launcher})
    message(STATUS "Compiling through ccache: ${UVMS_CCACHE_PROGRAM} (cache build/ccache)")
  elseif(UVMS_CCACHE)
    message(STATUS "ccache not found: compiling without it (tools/bootstrap installs it)")
  endif()
endif()
