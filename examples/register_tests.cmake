# SPDX-License-Identifier: Apache-2.0
# register_tests.cmake (included by the top-level CMakeLists.txt in every build, host and
# cross, after tests/consumer/register_tests.cmake, whose install it reuses): ctest example.*
# build examples/flight_loop against this build's firmware library as installed by
# consumer.install (fixture uvms_consumer_prefix), then run it: on the host, or in QEMU
# (mps2-an386, -icount) for the Cortex-M4F. example_test.cmake says what each asserts.
set(UVMS_EXAMPLE_SCRIPT ${PROJECT_SOURCE_DIR}/examples/example_test.cmake)
set(UVMS_EXAMPLE_ARGS ${UVMS_CONSUMER_ARGS} -DSOURCE=${PROJECT_SOURCE_DIR}/examples/flight_loop
    -DWORK=${PROJECT_BINARY_DIR}/examples/flight_loop -DCROSS=$<BOOL:${CMAKE_CROSSCOMPILING}>)

add_test(NAME example.flight_loop.build
  COMMAND ${CMAKE_COMMAND} -DMODE=build ${UVMS_EXAMPLE_ARGS} -P ${UVMS_EXAMPLE_SCRIPT})
set_tests_properties(example.flight_loop.build PROPERTIES LABELS integration TIMEOUT 180
                     FIXTURES_REQUIRED uvms_consumer_prefix FIXTURES_SETUP uvms_example_build)
foreach(mode nominal stall config_upset)
  add_test(NAME example.flight_loop.${mode}
    COMMAND ${CMAKE_COMMAND} -DMODE=${mode} ${UVMS_EXAMPLE_ARGS} -P ${UVMS_EXAMPLE_SCRIPT})
  set_tests_properties(example.flight_loop.${mode} PROPERTIES LABELS integration TIMEOUT 120
                       FIXTURES_REQUIRED "uvms_consumer_prefix;uvms_example_build")
endforeach()
