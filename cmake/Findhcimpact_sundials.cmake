# SPDX-License-Identifier: Apache-2.0
#
# Find module of SUNDIALS CVODE with its Fortran 2003 interface, for the CVODE
# component (components/cvode). The build calls it as
#
#   find_package(hcimpact_sundials)                      # libraries and Fortran modules
#
# and the installed CMake package of a static hcimpact, whose libhcimpact_cvode.a
# needs the SUNDIALS libraries at the consumer's link, as
#
#   find_dependency(hcimpact_sundials COMPONENTS libraries)   # the libraries only
#
# (it is installed next to hcimpact-config.cmake).
#
# SUNDIALS' own CMake package is not used: Debian's copy points at the wrong
# places. We look for the pieces directly, under (in this order) the variables
# SUNDIALS_ROOT and SUNDIALS_DIR (the prefix, or the directory of its
# SUNDIALSConfig.cmake), the environment variable SUNDIALS_ROOT, the list
# HCIMPACT_SUNDIALS_HINTS (the installed package sets it to where the build found
# SUNDIALS), then CMAKE_PREFIX_PATH and the system locations. Every piece can also be
# given directly by its cache variable: HCIMPACT_SUNDIALS_INCLUDE_DIR,
# HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR and HCIMPACT_SUNDIALS_<NAME>_LIBRARY
# (e.g. HCIMPACT_SUNDIALS_CVODE_LIBRARY; .ci/sundials7-check uses them).
#
# Results:
#   hcimpact_sundials_FOUND                 TRUE if everything asked for was found
#   hcimpact::sundials                      imported target: the libraries (in link
#                                           order) and the include directories
#   HCIMPACT_SUNDIALS_FOUND                 the same as hcimpact_sundials_FOUND
#   HCIMPACT_SUNDIALS_VERSION               e.g. 6.4.1
#   HCIMPACT_SUNDIALS_VERSION_MAJOR         e.g. 6 (SUNDIALS 7 adds sundials_core)
#   HCIMPACT_SUNDIALS_INCLUDE_DIR           directory holding sundials/sundials_config.h
#   HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR    directory holding fcvode_mod.mod
#   HCIMPACT_SUNDIALS_LIBRARIES             full paths, in link order
#   HCIMPACT_SUNDIALS_MISSING               what was not found (for messages)

set(_hcsun_hints "")
foreach(_hcsun_root IN ITEMS "${SUNDIALS_ROOT}" "${SUNDIALS_DIR}" "$ENV{SUNDIALS_ROOT}"
    ${HCIMPACT_SUNDIALS_HINTS})
  if(_hcsun_root)
    list(APPEND _hcsun_hints "${_hcsun_root}")
    # SUNDIALS_DIR is usually what find_package(SUNDIALS) wants, the directory of
    # SUNDIALSConfig.cmake (<prefix>/lib/cmake/sundials): search its prefix too.
    if(EXISTS "${_hcsun_root}/SUNDIALSConfig.cmake"
        AND _hcsun_root MATCHES "^(.+)/lib(64)?(/[^/]+)?/cmake/sundials/?$")
      list(APPEND _hcsun_hints "${CMAKE_MATCH_1}")
    endif()
  endif()
endforeach()

set(HCIMPACT_SUNDIALS_FOUND FALSE)
set(HCIMPACT_SUNDIALS_MISSING "")

find_path(HCIMPACT_SUNDIALS_INCLUDE_DIR
  NAMES sundials/sundials_config.h
  HINTS ${_hcsun_hints}
  PATH_SUFFIXES include)

set(HCIMPACT_SUNDIALS_VERSION "")
set(HCIMPACT_SUNDIALS_VERSION_MAJOR "")
if(HCIMPACT_SUNDIALS_INCLUDE_DIR)
  file(STRINGS "${HCIMPACT_SUNDIALS_INCLUDE_DIR}/sundials/sundials_config.h" _hcsun_lines
    REGEX "^#define[ \t]+SUNDIALS_VERSION_(MAJOR|MINOR|PATCH)[ \t]+[0-9]+")
  foreach(_hcsun_part IN ITEMS MAJOR MINOR PATCH)
    set(_hcsun_${_hcsun_part} "")
    foreach(_hcsun_line IN LISTS _hcsun_lines)
      if(_hcsun_line MATCHES "SUNDIALS_VERSION_${_hcsun_part}[ \t]+([0-9]+)")
        set(_hcsun_${_hcsun_part} "${CMAKE_MATCH_1}")
      endif()
    endforeach()
  endforeach()
  if(_hcsun_MAJOR STREQUAL "")
    # SUNDIALS before 6 only had the SUNDIALS_VERSION string.
    file(STRINGS "${HCIMPACT_SUNDIALS_INCLUDE_DIR}/sundials/sundials_config.h" _hcsun_lines
      REGEX "^#define[ \t]+SUNDIALS_VERSION[ \t]+\"[0-9.]+")
    if(_hcsun_lines MATCHES "\"([0-9]+)\\.([0-9]+)\\.([0-9]+)")
      set(_hcsun_MAJOR "${CMAKE_MATCH_1}")
      set(_hcsun_MINOR "${CMAKE_MATCH_2}")
      set(_hcsun_PATCH "${CMAKE_MATCH_3}")
    endif()
  endif()
  set(HCIMPACT_SUNDIALS_VERSION_MAJOR "${_hcsun_MAJOR}")
  set(HCIMPACT_SUNDIALS_VERSION "${_hcsun_MAJOR}.${_hcsun_MINOR}.${_hcsun_PATCH}")
else()
  list(APPEND HCIMPACT_SUNDIALS_MISSING "sundials/sundials_config.h")
endif()

# The F2003 interface needs SUNDIALS 6 or newer (SUNContext).
if(HCIMPACT_SUNDIALS_VERSION_MAJOR AND HCIMPACT_SUNDIALS_VERSION_MAJOR LESS 6)
  list(APPEND HCIMPACT_SUNDIALS_MISSING "SUNDIALS >= 6 (found ${HCIMPACT_SUNDIALS_VERSION})")
endif()

set(_hcsun_mod_suffixes fortran include/sundials/fortran include/fortran sundials/fortran
  fortran/modules)
if(HCIMPACT_SUNDIALS_INCLUDE_DIR)
  list(APPEND _hcsun_mod_hints "${HCIMPACT_SUNDIALS_INCLUDE_DIR}/sundials"
    "${HCIMPACT_SUNDIALS_INCLUDE_DIR}")
endif()
# The Fortran modules are needed to compile the component, not to link it: the
# component "libraries" alone skips them.
set(_hcsun_need_modules TRUE)
if(hcimpact_sundials_FIND_COMPONENTS AND NOT "fortran" IN_LIST hcimpact_sundials_FIND_COMPONENTS)
  set(_hcsun_need_modules FALSE)
endif()
if(_hcsun_need_modules)
  find_path(HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR
    NAMES fcvode_mod.mod
    HINTS ${_hcsun_hints} ${_hcsun_mod_hints}
    PATH_SUFFIXES ${_hcsun_mod_suffixes})
  if(NOT HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR)
    list(APPEND HCIMPACT_SUNDIALS_MISSING "fcvode_mod.mod (libsundials-fortran-dev)")
  endif()
endif()

# Link order: Fortran wrappers before the C libraries they call.
# Dense matrices and solvers for one impact, band matrices for the systems of bodies
# (whose linear solver is the component's own: chain_linear_solver.f90).
set(_hcsun_names
  sundials_fcvode_mod sundials_fnvecserial_mod sundials_fsunmatrixdense_mod
  sundials_fsunlinsoldense_mod sundials_fsunmatrixband_mod
  sundials_cvode sundials_nvecserial sundials_sunmatrixdense sundials_sunlinsoldense
  sundials_sunmatrixband)
set(_hcsun_optional "")
if(HCIMPACT_SUNDIALS_VERSION_MAJOR AND NOT HCIMPACT_SUNDIALS_VERSION_MAJOR LESS 7)
  # SUNDIALS 7 moved SUNContext and friends into sundials_core.
  list(INSERT _hcsun_names 6 sundials_fcore_mod)
  list(APPEND _hcsun_names sundials_core)
else()
  # SUNDIALS 6 keeps them in sundials_generic, which the shared libraries pull
  # in by themselves; a static build needs it named.
  list(APPEND _hcsun_optional sundials_generic)
endif()

set(HCIMPACT_SUNDIALS_LIBRARIES "")
foreach(_hcsun_name IN LISTS _hcsun_names _hcsun_optional)
  string(TOUPPER "${_hcsun_name}" _hcsun_var)
  find_library(HCIMPACT_${_hcsun_var}_LIBRARY
    NAMES ${_hcsun_name}
    HINTS ${_hcsun_hints}
    PATH_SUFFIXES lib lib64 "lib/${CMAKE_LIBRARY_ARCHITECTURE}")
  mark_as_advanced(HCIMPACT_${_hcsun_var}_LIBRARY)
  if(HCIMPACT_${_hcsun_var}_LIBRARY)
    list(APPEND HCIMPACT_SUNDIALS_LIBRARIES "${HCIMPACT_${_hcsun_var}_LIBRARY}")
  elseif(NOT _hcsun_name IN_LIST _hcsun_optional)
    list(APPEND HCIMPACT_SUNDIALS_MISSING "lib${_hcsun_name}")
  endif()
endforeach()

mark_as_advanced(HCIMPACT_SUNDIALS_INCLUDE_DIR HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR)

if(NOT HCIMPACT_SUNDIALS_MISSING)
  set(HCIMPACT_SUNDIALS_FOUND TRUE)
  if(NOT TARGET hcimpact::sundials)
    # GLOBAL in the build tree, so that a parent project that adds hcimpact with
    # add_subdirectory/FetchContent can link hcimpact::cvode from its own directories.
    if(PROJECT_NAME STREQUAL "hcimpact")
      add_library(hcimpact::sundials INTERFACE IMPORTED GLOBAL)
    else()
      add_library(hcimpact::sundials INTERFACE IMPORTED)
    endif()
    set_target_properties(hcimpact::sundials PROPERTIES
      INTERFACE_LINK_LIBRARIES "${HCIMPACT_SUNDIALS_LIBRARIES}"
      INTERFACE_INCLUDE_DIRECTORIES
        "${HCIMPACT_SUNDIALS_FORTRAN_MODULE_DIR};${HCIMPACT_SUNDIALS_INCLUDE_DIR}")
    if(NOT _hcsun_need_modules)
      set_target_properties(hcimpact::sundials PROPERTIES
        INTERFACE_INCLUDE_DIRECTORIES "${HCIMPACT_SUNDIALS_INCLUDE_DIR}")
    endif()
  endif()
else()
  list(JOIN HCIMPACT_SUNDIALS_MISSING ", " HCIMPACT_SUNDIALS_MISSING)
endif()

set(hcimpact_sundials_FOUND ${HCIMPACT_SUNDIALS_FOUND})
set(hcimpact_sundials_VERSION "${HCIMPACT_SUNDIALS_VERSION}")
if(NOT hcimpact_sundials_FOUND)
  set(_hcsun_message "SUNDIALS CVODE not found (missing: ${HCIMPACT_SUNDIALS_MISSING}); "
    "point SUNDIALS_ROOT at its prefix")
  if(hcimpact_sundials_FIND_REQUIRED)
    message(FATAL_ERROR ${_hcsun_message})
  elseif(NOT hcimpact_sundials_FIND_QUIETLY)
    message(STATUS ${_hcsun_message})
  endif()
elseif(NOT hcimpact_sundials_FIND_QUIETLY)
  message(STATUS "Found SUNDIALS ${HCIMPACT_SUNDIALS_VERSION}: ${HCIMPACT_SUNDIALS_INCLUDE_DIR}")
endif()
