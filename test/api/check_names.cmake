# SPDX-License-Identifier: Apache-2.0
#
# Script mode: cmake -DSOURCE_DIR=<repository> -P check_names.cmake
#
# Consistency of the C and FORTRAN 77 interfaces with the Fortran sources:
#   1. no binding label (bind(C, name="...") or the name of a bind(C) procedure
#      without name=) and no FORTRAN 77 external (src/hcimpact/f77/f77.f90) equals a
#      module name: gfortran miscompiles a call in a unit that uses module M when
#      the unit also defines the label M (it became an infinite loop once);
#   2. every hcimpact_* label of src/ and components/ is declared in one of the
#      headers include/hcimpact*.h (the core's in hcimpact.h, a component's in
#      hcimpact_<component>.h), and every function a header declares is defined,
#      each with the export macro HCIMPACT_API;
#   3. the HCIMPACT_OK / HCIMPACT_ERR_* macros of the header have the values of
#      the parameters of src/hcimpact/status.f90, and none is missing.

cmake_policy(VERSION 3.18)

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<dir> -P check_names.cmake")
endif()

set(errors "")

file(GLOB_RECURSE fortran_sources
  "${SOURCE_DIR}/src/*.f90" "${SOURCE_DIR}/src/*.F90"
  "${SOURCE_DIR}/components/*.f90" "${SOURCE_DIR}/components/*.F90")
list(SORT fortran_sources)

set(modules "")
set(labels "")
set(label_files "")
foreach(source IN LISTS fortran_sources)
  file(READ "${source}" text)
  string(TOLOWER "${text}" text)
  # join continuation lines, drop comments
  string(REGEX REPLACE "&[ \t]*\n[ \t]*&?" " " text "${text}")
  string(REGEX REPLACE "![^\n]*" "" text "${text}")
  string(REPLACE ";" "," text "${text}")
  # square brackets would group list elements
  string(REPLACE "[" "(" text "${text}")
  string(REPLACE "]" ")" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  file(RELATIVE_PATH rel "${SOURCE_DIR}" "${source}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[ \t]*module[ \t]+([a-z0-9_]+)[ \t]*$")
      list(APPEND modules "${CMAKE_MATCH_1}")
    endif()
    if(line MATCHES "bind[ \t]*\\([ \t]*c[ \t]*,[ \t]*name[ \t]*=[ \t]*[\"']([^\"']*)[\"']")
      if(NOT CMAKE_MATCH_1 STREQUAL "")
        list(APPEND labels "${CMAKE_MATCH_1}")
        list(APPEND label_files "${CMAKE_MATCH_1}@${rel}")
      endif()
    elseif(line MATCHES "(function|subroutine)[ \t]+([a-z0-9_]+)[ \t]*\\(.*bind[ \t]*\\([ \t]*c[ \t]*\\)")
      list(APPEND labels "${CMAKE_MATCH_2}")
      list(APPEND label_files "${CMAKE_MATCH_2}@${rel}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES modules)

# FORTRAN 77 externals: the subroutines of f77.f90 outside any module
set(f77_names "")
if(EXISTS "${SOURCE_DIR}/src/hcimpact/f77/f77.f90")
  file(STRINGS "${SOURCE_DIR}/src/hcimpact/f77/f77.f90" f77_lines REGEX "^subroutine[ \t]+[a-z0-9_]+")
  foreach(line IN LISTS f77_lines)
    if(line MATCHES "^subroutine[ \t]+([a-z0-9_]+)")
      list(APPEND f77_names "${CMAKE_MATCH_1}")
    endif()
  endforeach()
endif()

# 1. labels and externals against module names
foreach(name IN LISTS labels f77_names)
  list(FIND modules "${name}" hit)
  if(NOT hit EQUAL -1)
    string(APPEND errors "\n  '${name}' is both a module and a binding label / external procedure")
  endif()
endforeach()

# 2. the headers against the labels: a label of components/<name>/ belongs in
# include/hcimpact_<name>.h, any other in include/hcimpact.h
file(GLOB header_files "${SOURCE_DIR}/include/hcimpact*.h")
list(SORT header_files)
set(header "")
set(declared_where "")
foreach(header_file IN LISTS header_files)
  file(READ "${header_file}" text)
  string(APPEND header "${text}")
  get_filename_component(header_name "${header_file}" NAME)
  string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" text_code "${text}")
  string(REGEX MATCHALL "hcimpact_[a-z0-9_]+[ \t]*\\(" items "${text_code}")
  foreach(item IN LISTS items)
    string(REGEX REPLACE "[ \t]*\\($" "" item "${item}")
    list(APPEND declared_where "${item}@${header_name}")
  endforeach()
  # every function declaration starts with the export macro
  string(REGEX MATCHALL "\n(const char \\*|int |double )hcimpact_[a-z0-9_]+\\(" bare "${text_code}")
  foreach(item IN LISTS bare)
    string(STRIP "${item}" item)
    string(APPEND errors "\n  ${header_name}: '${item}' lacks HCIMPACT_API")
  endforeach()
endforeach()
# declarations: identifiers hcimpact_* followed by '(' outside comments
string(REGEX REPLACE "/\\*([^*]|\\*+[^*/])*\\*+/" "" header_code "${header}")
string(REGEX MATCHALL "hcimpact_[a-z0-9_]+[ \t]*\\(" declared "${header_code}")
set(declared_names "")
foreach(item IN LISTS declared)
  string(REGEX REPLACE "[ \t]*\\($" "" item "${item}")
  list(APPEND declared_names "${item}")
endforeach()
list(REMOVE_DUPLICATES declared_names)
set(exported "")
foreach(label IN LISTS labels)
  if(label MATCHES "^hcimpact_")
    list(APPEND exported "${label}")
  endif()
endforeach()
list(REMOVE_DUPLICATES exported)
foreach(label IN LISTS exported)
  list(FIND declared_names "${label}" hit)
  if(hit EQUAL -1)
    set(where "")
    foreach(entry IN LISTS label_files)
      if(entry MATCHES "^${label}@(.*)$")
        set(where " (${CMAKE_MATCH_1})")
      endif()
    endforeach()
    string(APPEND errors "\n  ${label}${where} is not declared in include/hcimpact*.h")
  else()
    set(expected_header "hcimpact.h")
    foreach(entry IN LISTS label_files)
      if(entry MATCHES "^${label}@components/([a-z0-9_]+)/")
        set(expected_header "hcimpact_${CMAKE_MATCH_1}.h")
      endif()
    endforeach()
    if(NOT "${label}@${expected_header}" IN_LIST declared_where)
      string(APPEND errors "\n  ${label} is not declared in include/${expected_header}")
    endif()
  endif()
endforeach()
foreach(name IN LISTS declared_names)
  list(FIND exported "${name}" hit)
  if(hit EQUAL -1)
    string(APPEND errors "\n  include/hcimpact*.h declare ${name}, which no Fortran source defines")
  endif()
endforeach()

# 3. status codes
file(STRINGS "${SOURCE_DIR}/src/hcimpact/status.f90" status_lines
  REGEX "integer, parameter :: hcimpact_(ok|err_[a-z_]+) = [0-9]+")
set(n_codes 0)
foreach(line IN LISTS status_lines)
  if(line MATCHES "(hcimpact_(ok|err_[a-z_]+)) = ([0-9]+)")
    string(TOUPPER "${CMAKE_MATCH_1}" macro)
    set(value "${CMAKE_MATCH_3}")
    math(EXPR n_codes "${n_codes} + 1")
    if(header MATCHES "#define[ \t]+${macro}[ \t]+([0-9]+)")
      if(NOT CMAKE_MATCH_1 STREQUAL value)
        string(APPEND errors "\n  ${macro} is ${CMAKE_MATCH_1} in hcimpact.h, ${value} in status.f90")
      endif()
    else()
      string(APPEND errors "\n  ${macro} (= ${value} in status.f90) is missing from hcimpact.h")
    endif()
  endif()
endforeach()
string(REGEX MATCHALL "#define[ \t]+HCIMPACT_(OK|ERR_[A-Z_]+)[ \t]" header_codes "${header}")
list(LENGTH header_codes n_header_codes)
if(NOT n_header_codes EQUAL n_codes)
  string(APPEND errors "\n  hcimpact.h defines ${n_header_codes} status macros, status.f90 has ${n_codes}")
endif()

list(LENGTH modules n_modules)
list(LENGTH exported n_exported)
list(LENGTH f77_names n_f77)
if(errors)
  message(FATAL_ERROR "C / FORTRAN 77 interface check failed:${errors}")
endif()
message(STATUS "${n_modules} modules, ${n_exported} C functions (each declared in its header), "
  "${n_f77} FORTRAN 77 externals, ${n_codes} status codes: no clash, header and sources agree")
