# SPDX-License-Identifier: Apache-2.0
# cmake/linker.cmake: link the host programs with LLVM's lld (Debian's `lld`, installed by
# tools/bootstrap) when the compiler accepts -fuse-ld=lld and UVMS_LLD is ON (the default).
# lld links this project's programs about 3 times faster than GNU ld (the host-asan build's
# 54 links: 20.2 s with ld.bfd, 7.3 s with lld; docs/BENCHMARKS.md "Setup and CI"). The
# linker changes the layout of a program, not its code. Cross builds (cortex-m4f) keep their
# toolchain's linker and linker scripts.
option(UVMS_LLD "Link the host programs with lld when it is installed" ON)
if(UVMS_LLD AND NOT CMAKE_CROSSCOMPILING)
  include(CheckLinkerFlag)
  check_linker_flag(C "-fuse-ld=lld" UVMS_HAVE_LLD)
  if(UVMS_HAVE_LLD)
    add_link_options(-fuse-ld=lld)
  else()
    message(STATUS "lld not found: linking with the compiler's default linker "
                   "(tools/bootstrap installs lld)")
  endif()
endif()
