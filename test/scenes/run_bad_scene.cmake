# SPDX-License-Identifier: Apache-2.0
#
# CTest driver: a bad scene file is refused with exit code 2 and the message its first
# line announces ("! expect: <text>", "<file>" standing for the file's path), and no
# results directory is created.
#   cmake -DPROGRAM=<hcimpact> -DSCENE=<bad.nml> -DOUTPUT=<dir> -P run_bad_scene.cmake
file(STRINGS "${SCENE}" first LIMIT_COUNT 1)
if(NOT first MATCHES "^! expect: (.*)$")
  message(FATAL_ERROR "${SCENE}: the first line must be '! expect: <message>'")
endif()
set(expected "${CMAKE_MATCH_1}")
string(REPLACE "<file>" "${SCENE}" expected "${expected}")
file(REMOVE_RECURSE "${OUTPUT}")
execute_process(COMMAND "${PROGRAM}" "${SCENE}" -o "${OUTPUT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("stderr: ${err}")
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "exit code ${rc}, expected 2")
endif()
string(FIND "${err}" "${expected}" at)
if(at LESS 0)
  message(FATAL_ERROR "the message does not contain: ${expected}")
endif()
if(EXISTS "${OUTPUT}")
  message(FATAL_ERROR "${OUTPUT} was created for a bad scene")
endif()
message("PASS")
