# SPDX-License-Identifier: Apache-2.0
# print_symbol_size.cmake -DNM=<nm> -DOBJ=<object> -DSYMBOL=<name> -DLABEL=<text>
execute_process(COMMAND ${NM} -S ${OBJ} OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} -S ${OBJ} failed")
endif()
string(REGEX MATCH "[0-9a-fA-F]+ ([0-9a-fA-F]+) [BbCcDd] ${SYMBOL}" m "${out}")
if(NOT m)
  message(FATAL_ERROR "symbol ${SYMBOL} not found in ${OBJ}")
endif()
math(EXPR bytes "0x${CMAKE_MATCH_1}" OUTPUT_FORMAT DECIMAL)
message("${LABEL}: ${bytes} bytes")
