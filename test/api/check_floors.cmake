# SPDX-License-Identifier: Apache-2.0
#
# Script mode: cmake -DSOURCE_DIR=<repository> -P check_floors.cmake
#
# The floors of the core library (README "Architecture"): a module of
# src/hcimpact/<floor>/ may use modules of its own floor and of the floors below
# it, never of a floor above. The floors, from the bottom: base (the files directly
# in src/hcimpact/), numerics, special, model, impact, system, then capi and f77 (the
# bindings, which may use each other's floor only through the ones below).

if(NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<dir> -P check_floors.cmake")
endif()

set(floor_names base numerics special model impact system capi f77)
set(level_base 0)
set(level_numerics 1)
set(level_special 2)
set(level_model 3)
set(level_impact 4)
set(level_system 5)
set(level_capi 6)
set(level_f77 6)

# module name -> floor, from the file that defines it
file(GLOB_RECURSE sources "${SOURCE_DIR}/src/hcimpact/*.f90")
foreach(source IN LISTS sources)
  file(RELATIVE_PATH rel "${SOURCE_DIR}/src/hcimpact" "${source}")
  if(rel MATCHES "^([a-z0-9_]+)/")
    set(floor "${CMAKE_MATCH_1}")
  else()
    set(floor base)
  endif()
  if(NOT DEFINED level_${floor})
    string(APPEND errors "  ${rel}: the folder ${floor} is not a floor (${floor_names})\n")
    continue()
  endif()
  file(STRINGS "${source}" module_lines REGEX "^[ \t]*module[ \t]+[a-z0-9_]+[ \t]*$")
  foreach(line IN LISTS module_lines)
    string(REGEX REPLACE "^[ \t]*module[ \t]+([a-z0-9_]+).*" "\\1" name "${line}")
    set(floor_of_${name} "${floor}")
  endforeach()
  set(file_floor_${rel} "${floor}")
endforeach()

set(checked 0)
foreach(source IN LISTS sources)
  file(RELATIVE_PATH rel "${SOURCE_DIR}/src/hcimpact" "${source}")
  set(floor "${file_floor_${rel}}")
  if(NOT floor)
    continue()
  endif()
  file(STRINGS "${source}" use_lines REGEX "^[ \t]*use[ \t]+hcimpact_[a-z0-9_]+")
  foreach(line IN LISTS use_lines)
    string(REGEX REPLACE "^[ \t]*use[ \t]+(hcimpact_[a-z0-9_]+).*" "\\1" used "${line}")
    if(NOT DEFINED floor_of_${used})
      continue()
    endif()
    set(used_floor "${floor_of_${used}}")
    math(EXPR checked "${checked} + 1")
    if(level_${used_floor} GREATER level_${floor})
      string(APPEND errors
        "  ${rel} (floor ${floor}) uses ${used} of the floor above, ${used_floor}\n")
    elseif(level_${used_floor} EQUAL level_${floor} AND NOT used_floor STREQUAL floor)
      string(APPEND errors
        "  ${rel} (floor ${floor}) uses ${used} of the side floor ${used_floor}\n")
    endif()
  endforeach()
endforeach()

if(errors)
  message(FATAL_ERROR "the floors of src/hcimpact are crossed upwards:\n${errors}")
endif()
message(STATUS "floors: ${checked} uses of hcimpact modules checked, none upwards")
