# SPDX-License-Identifier: Apache-2.0
#
# Find a provider of the Fortran module `testdrive` for the unit tests.
#
# Tried in this order:
#   1. an installed test-drive CMake package   (find_package(test-drive CONFIG))
#   2. an installed test-drive pkg-config file  (pkg-config test-drive)
#   3. test-drive ${HCIMPACT_TESTDRIVE_TAG} downloaded with FetchContent,
#      only when HCIMPACT_FETCH_TESTDRIVE=ON
#   4. mctc-lib (Debian: libmctc-lib-dev), whose mctc_env_testing has the same
#      interface; test/unit/testdrive_mctc.f90 turns it into `module testdrive`
#
# Results:
#   HCIMPACT_TESTDRIVE_FOUND    TRUE if one of them works
#   HCIMPACT_TESTDRIVE_BACKEND  human-readable name of the provider
#   HCIMPACT_TESTDRIVE_TARGET   target to link the tester with
#   HCIMPACT_TESTDRIVE_ADAPTER  TRUE if testdrive_mctc.f90 must be compiled in

set(HCIMPACT_TESTDRIVE_FOUND FALSE)
set(HCIMPACT_TESTDRIVE_BACKEND "")
set(HCIMPACT_TESTDRIVE_TARGET "")
set(HCIMPACT_TESTDRIVE_ADAPTER FALSE)

# 1. CMake package
find_package(test-drive CONFIG QUIET)
if(TARGET test-drive::test-drive)
  set(HCIMPACT_TESTDRIVE_FOUND TRUE)
  set(HCIMPACT_TESTDRIVE_BACKEND "test-drive ${test-drive_VERSION} (CMake package)")
  set(HCIMPACT_TESTDRIVE_TARGET test-drive::test-drive)
  return()
endif()

# 2. pkg-config
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(HCIMPACT_TESTDRIVE_PC QUIET IMPORTED_TARGET test-drive)
  if(HCIMPACT_TESTDRIVE_PC_FOUND)
    set(HCIMPACT_TESTDRIVE_FOUND TRUE)
    set(HCIMPACT_TESTDRIVE_BACKEND "test-drive ${HCIMPACT_TESTDRIVE_PC_VERSION} (pkg-config)")
    set(HCIMPACT_TESTDRIVE_TARGET PkgConfig::HCIMPACT_TESTDRIVE_PC)
    return()
  endif()
endif()

# 3. Download, on request only. Only the sources are fetched (SOURCE_SUBDIR
# names a directory without a CMakeLists.txt); we compile them into a static
# library of our own that is never installed.
if(HCIMPACT_FETCH_TESTDRIVE)
  include(FetchContent)
  FetchContent_Declare(
    hcimpact_testdrive
    GIT_REPOSITORY "https://github.com/fortran-lang/test-drive"
    GIT_TAG "${HCIMPACT_TESTDRIVE_TAG}"
    GIT_SHALLOW TRUE
    SOURCE_SUBDIR "hcimpact-sources-only")
  FetchContent_MakeAvailable(hcimpact_testdrive)
  file(GLOB _hctd_sources
    "${hcimpact_testdrive_SOURCE_DIR}/src/*.F90"
    "${hcimpact_testdrive_SOURCE_DIR}/src/*.f90")
  if(NOT _hctd_sources)
    message(FATAL_ERROR "HCIMPACT_FETCH_TESTDRIVE: no sources in ${hcimpact_testdrive_SOURCE_DIR}/src")
  endif()
  add_library(hcimpact_testdrive STATIC ${_hctd_sources})
  set_target_properties(hcimpact_testdrive PROPERTIES
    Fortran_MODULE_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/testdrive-modules")
  target_include_directories(hcimpact_testdrive PUBLIC
    "${CMAKE_CURRENT_BINARY_DIR}/testdrive-modules")
  set(HCIMPACT_TESTDRIVE_FOUND TRUE)
  set(HCIMPACT_TESTDRIVE_BACKEND "test-drive ${HCIMPACT_TESTDRIVE_TAG} (FetchContent)")
  set(HCIMPACT_TESTDRIVE_TARGET hcimpact_testdrive)
  return()
endif()

# 4. mctc-lib with the adapter
set(_hctd_mctc_includes "")
set(_hctd_mctc_libraries "")
if(PKG_CONFIG_FOUND)
  pkg_check_modules(HCIMPACT_MCTC_PC QUIET mctc-lib)
  if(HCIMPACT_MCTC_PC_FOUND)
    set(_hctd_mctc_includes ${HCIMPACT_MCTC_PC_INCLUDE_DIRS})
    # full paths of the libraries, as found along the pkg-config -L flags
    set(_hctd_mctc_libraries ${HCIMPACT_MCTC_PC_LINK_LIBRARIES})
  endif()
endif()
if(NOT _hctd_mctc_libraries)
  find_path(HCIMPACT_MCTC_MODULE_DIR NAMES mctc_env_testing.mod
    PATH_SUFFIXES mctc-lib include/mctc-lib)
  find_library(HCIMPACT_MCTC_LIBRARY NAMES mctc-lib)
  mark_as_advanced(HCIMPACT_MCTC_MODULE_DIR HCIMPACT_MCTC_LIBRARY)
  if(HCIMPACT_MCTC_MODULE_DIR AND HCIMPACT_MCTC_LIBRARY)
    set(_hctd_mctc_includes "${HCIMPACT_MCTC_MODULE_DIR}")
    set(_hctd_mctc_libraries "${HCIMPACT_MCTC_LIBRARY}")
  endif()
endif()

if(_hctd_mctc_libraries)
  # The .mod files were written by one particular compiler: make sure ours
  # can read them and that the entities the adapter re-exports are there.
  include(CheckFortranSourceCompiles)
  set(CMAKE_REQUIRED_INCLUDES ${_hctd_mctc_includes})
  set(CMAKE_REQUIRED_LIBRARIES ${_hctd_mctc_libraries})
  set(CMAKE_REQUIRED_QUIET TRUE)
  check_fortran_source_compiles([=[
program probe
   use mctc_env_testing, only : new_unittest, unittest_type, error_type, check, &
      & test_failed, run_testsuite, run_selected, new_testsuite, testsuite_type, &
      & select_suite, select_test
   use mctc_env_system, only : get_argument, get_variable
   implicit none
   type(error_type), allocatable :: error
   call check(error, .true.)
end program probe
]=] HCIMPACT_MCTC_USABLE SRC_EXT f90)
  unset(CMAKE_REQUIRED_INCLUDES)
  unset(CMAKE_REQUIRED_LIBRARIES)
  unset(CMAKE_REQUIRED_QUIET)
  if(HCIMPACT_MCTC_USABLE)
    add_library(hcimpact_testdrive_mctc INTERFACE)
    target_include_directories(hcimpact_testdrive_mctc INTERFACE ${_hctd_mctc_includes})
    target_link_libraries(hcimpact_testdrive_mctc INTERFACE ${_hctd_mctc_libraries})
    set(HCIMPACT_TESTDRIVE_FOUND TRUE)
    set(HCIMPACT_TESTDRIVE_BACKEND "mctc-lib through test/unit/testdrive_mctc.f90")
    set(HCIMPACT_TESTDRIVE_TARGET hcimpact_testdrive_mctc)
    set(HCIMPACT_TESTDRIVE_ADAPTER TRUE)
  endif()
endif()
