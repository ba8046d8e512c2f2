# SPDX-License-Identifier: Apache-2.0
#
# CTest driver: the built-in default scene (hcimpact --show-default) is the file
# example/scenes/steel_ball.nml, line for line (trailing blanks aside).
#   cmake -DPROGRAM=<hcimpact> -DEXPECTED=<steel_ball.nml> -P check_default_scene.cmake
execute_process(COMMAND "${PROGRAM}" --show-default
  RESULT_VARIABLE rc OUTPUT_VARIABLE shown)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "hcimpact --show-default: exit code ${rc}")
endif()
file(READ "${EXPECTED}" expected)
string(REGEX REPLACE "[ \t]+\n" "\n" shown "${shown}")
string(REGEX REPLACE "[ \t]+\n" "\n" expected "${expected}")
if(NOT shown STREQUAL expected)
  message(FATAL_ERROR "the built-in default scene differs from ${EXPECTED}:\n"
    "--- built in:\n${shown}\n--- file:\n${expected}")
endif()
message("PASS: the built-in default scene is ${EXPECTED}")
