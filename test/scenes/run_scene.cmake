# SPDX-License-Identifier: Apache-2.0
#
# CTest driver: run one scene file and check its results directory.
#   cmake -DPROGRAM=<hcimpact> -DSCENE=<file.nml> -DOUTPUT=<dir> -DHAVE_CVODE=<bool>
#         -P run_scene.cmake
# Passes when the program exits 0 and OUTPUT holds log.txt, scene.nml, parameters.csv,
# no *.partial file, and CSV files that each have a header and at least one row; and
# every file a line "! files: a.csv b.csv" of the scene names.
# Without CVODE, a scene that needs it must exit 3 and name the missing component.
file(REMOVE_RECURSE "${OUTPUT}")
execute_process(COMMAND "${PROGRAM}" "${SCENE}" -o "${OUTPUT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(err)
  message("stderr:\n${err}")
endif()
if(rc EQUAL 3 AND NOT HAVE_CVODE)
  if(err MATCHES "needs the CVODE component" AND NOT EXISTS "${OUTPUT}")
    message("PASS: the scene needs CVODE, which this build lacks, and says so")
    return()
  endif()
  message(FATAL_ERROR "exit code 3 without the expected message, or output was written")
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${SCENE}: exit code ${rc}")
endif()
file(GLOB partial "${OUTPUT}/*.partial")
if(partial)
  message(FATAL_ERROR "partial files left: ${partial}")
endif()
file(STRINGS "${SCENE}" wanted REGEX "^! files: ")
string(REGEX REPLACE "! files: " "" wanted "${wanted}")
string(REGEX REPLACE "[ ;]+" ";" wanted "${wanted}")
foreach(name log.txt scene.nml parameters.csv ${wanted})
  if(NOT EXISTS "${OUTPUT}/${name}")
    message(FATAL_ERROR "${OUTPUT}/${name} is missing")
  endif()
endforeach()
file(GLOB tables "${OUTPUT}/*.csv")
foreach(table IN LISTS tables)
  file(STRINGS "${table}" lines LIMIT_COUNT 2)
  list(LENGTH lines n)
  if(n LESS 2)
    message(FATAL_ERROR "${table}: no data rows")
  endif()
  list(GET lines 1 row)
  if(row MATCHES "(^|,)nan(,|$)" AND NOT table MATCHES "parameters.csv$")
    message(STATUS "note: ${table} has nan in its first row")
  endif()
endforeach()
list(LENGTH tables n)
message("PASS: ${n} CSV files in ${OUTPUT}")
