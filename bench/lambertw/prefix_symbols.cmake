# SPDX-License-Identifier: Apache-2.0
#
# cmake -DNM=... -DOBJCOPY=... -DINPUT=lib.a -DOUTPUT=lib_prefixed.a -DPREFIX=p_ -P prefix_symbols.cmake
#
# Copy the static archive INPUT to OUTPUT with every global symbol it defines renamed
# to PREFIX<name> (references between its objects follow; references to other
# libraries, the C and Fortran run-time libraries, keep their names). The
# Lambert W benchmark links such a copy of the library next to the shared
# library, so that one program times both.
foreach(var NM OBJCOPY INPUT OUTPUT PREFIX)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "prefix_symbols.cmake: -D${var}=... missing")
  endif()
endforeach()
execute_process(COMMAND "${NM}" -g --defined-only "${INPUT}"
  OUTPUT_VARIABLE listing RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prefix_symbols.cmake: ${NM} failed on ${INPUT}: ${err}")
endif()
string(REPLACE "\n" ";" lines "${listing}")
set(map "")
set(count 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^[0-9a-fA-F]+ [A-Za-z] ([^ ]+)$")
    string(APPEND map "${CMAKE_MATCH_1} ${PREFIX}${CMAKE_MATCH_1}\n")
    math(EXPR count "${count} + 1")
  endif()
endforeach()
if(count EQUAL 0)
  message(FATAL_ERROR "prefix_symbols.cmake: no global symbols defined in ${INPUT}")
endif()
file(WRITE "${OUTPUT}.map" "${map}")
# (the link-time optimiser's sections go: their symbols would keep the old names, and
# a linker with the LTO plugin would take them instead of the renamed machine code)
execute_process(COMMAND "${OBJCOPY}" "--redefine-syms=${OUTPUT}.map" "--remove-section=.gnu.lto_*"
    "--remove-section=.gnu.debuglto_*" "${INPUT}" "${OUTPUT}"
  RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "prefix_symbols.cmake: ${OBJCOPY} failed: ${err}")
endif()
