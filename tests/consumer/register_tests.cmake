# SPDX-License-Identifier: Apache-2.0
# register_tests.cmake (included by the top-level CMakeLists.txt in every build, host and
# cross): ctest consumer.* build tests/consumer against this build's firmware library installed
# into a prefix under the build tree (consumer_test.cmake says what each asserts).
set(UVMS_CONSUMER_ROOT ${PROJECT_BINARY_DIR}/consumer)
set(UVMS_CONSUMER_ARGS -DBUILD_DIR=${PROJECT_BINARY_DIR} -DPREFIX=${UVMS_CONSUMER_ROOT}/prefix
    -DGENERATOR=${CMAKE_GENERATOR} -DREAL_FLOAT=$<BOOL:${UVMS_REAL_FLOAT}>
    -DBUILD_TYPE=${CMAKE_BUILD_TYPE})
if(CMAKE_CROSSCOMPILING)
  list(APPEND UVMS_CONSUMER_ARGS -DTOOLCHAIN=${CMAKE_TOOLCHAIN_FILE}
       -DBOARD_DIR=${PROJECT_SOURCE_DIR}/firmware/target)
else()
  set(flags "${CMAKE_C_FLAGS}")
  set(link_flags "")
  if(UVMS_SANITIZE)  # the library's objects need the sanitizer runtimes
    string(APPEND flags " -fsanitize=address,undefined")
    set(link_flags "-fsanitize=address,undefined")
  endif()
  list(APPEND UVMS_CONSUMER_ARGS -DC_COMPILER=${CMAKE_C_COMPILER} "-DC_FLAGS=${flags}"
       "-DLINK_FLAGS=${link_flags}")
endif()
set(UVMS_CONSUMER_SCRIPT ${PROJECT_SOURCE_DIR}/tests/consumer/consumer_test.cmake)

add_test(NAME consumer.install
  COMMAND ${CMAKE_COMMAND} -DMODE=install -DWORK=${UVMS_CONSUMER_ROOT}/install
          ${UVMS_CONSUMER_ARGS} -P ${UVMS_CONSUMER_SCRIPT})
set_tests_properties(consumer.install PROPERTIES LABELS integration TIMEOUT 120
                     FIXTURES_SETUP uvms_consumer_prefix)
foreach(mode paper_step ask_other stale_header)
  add_test(NAME consumer.${mode}
    COMMAND ${CMAKE_COMMAND} -DMODE=${mode} -DWORK=${UVMS_CONSUMER_ROOT}/${mode}
            ${UVMS_CONSUMER_ARGS} -P ${UVMS_CONSUMER_SCRIPT})
  set_tests_properties(consumer.${mode} PROPERTIES LABELS integration TIMEOUT 180
                       FIXTURES_REQUIRED uvms_consumer_prefix)
endforeach()
