# SPDX-License-Identifier: Apache-2.0
#
# CTest driver: a scene that must be refused (a bad scene file, exit code 2) or whose
# computation must fail (exit code 1) stops with that exit code and the message its
# first line announces ("! expect: <text>", "<file>" standing for the file's path),
# and leaves nothing behind: the results directory is asked for three levels below
# OUTPUT (OUTPUT/a/b/c), and OUTPUT, which the run would create, must not exist
# afterwards.
#   cmake -DPROGRAM=<hcimpact> -DSCENE=<scene.nml> -DOUTPUT=<dir> -DEXIT=<2 or 1>
#         -P run_bad_scene.cmake
if(NOT DEFINED EXIT)
  set(EXIT 2)
endif()
file(STRINGS "${SCENE}" first LIMIT_COUNT 1)
if(NOT first MATCHES "^! expect: (.*)$")
  message(FATAL_ERROR "${SCENE}: the first line must be '! expect: <message>'")
endif()
set(expected "${CMAKE_MATCH_1}")
string(REPLACE "<file>" "${SCENE}" expected "${expected}")
file(REMOVE_RECURSE "${OUTPUT}")
execute_process(COMMAND "${PROGRAM}" "${SCENE}" -o "${OUTPUT}/a/b/c"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("stderr: ${err}")
if(NOT rc EQUAL EXIT)
  message(FATAL_ERROR "exit code ${rc}, expected ${EXIT}")
endif()
string(FIND "${err}" "${expected}" at)
if(at LESS 0)
  message(FATAL_ERROR "the message does not contain: ${expected}")
endif()
if(EXISTS "${OUTPUT}")
  file(GLOB_RECURSE left LIST_DIRECTORIES true "${OUTPUT}/*")
  message(FATAL_ERROR "${OUTPUT} was left behind: ${left}")
endif()
message("PASS")
