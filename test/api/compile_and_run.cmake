# SPDX-License-Identifier: Apache-2.0
#
# Script mode: compile (and optionally link and run) one source with a given
# compiler, outside the CMake build, the way a user of the installed header would.
#
#   cmake -DCOMPILER=<cc> -DFLAGS="<a>|<b>|..." -DSOURCE=<file> -DOUTPUT=<exe>
#         [-DLIBS="<lib>|..."] [-DRUN=ON] -P compile_and_run.cmake
#
# FLAGS and LIBS are separated by '|'. Without OUTPUT the flags should include
# -fsyntax-only (compile only).

foreach(var COMPILER FLAGS SOURCE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "compile_and_run.cmake: ${var} is not set")
  endif()
endforeach()
string(REPLACE "|" ";" flags "${FLAGS}")
string(REPLACE "|" ";" libs "${LIBS}")
set(command "${COMPILER}" ${flags} "${SOURCE}")
if(OUTPUT)
  # -x none: the libraries are not sources of the language forced by -x
  list(APPEND command -x none ${libs} -o "${OUTPUT}")
endif()
list(JOIN command " " shown)
message(STATUS "${shown}")
execute_process(COMMAND ${command} RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "compilation failed (${result})")
endif()
if(OUTPUT AND RUN)
  execute_process(COMMAND "${OUTPUT}" RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${OUTPUT} failed (${result})")
  endif()
endif()
