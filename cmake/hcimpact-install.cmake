# SPDX-License-Identifier: Apache-2.0
#
# Install rules: the library (and built components), the .mod files, the C
# header, the CMake package hcimpact (target hcimpact::hcimpact) and the
# pkg-config file hcimpact.pc. Layout, relative to the prefix:
#
#   lib/libhcimpact.{a,so}                      (CMAKE_INSTALL_LIBDIR)
#   include/hcimpact.h                          (CMAKE_INSTALL_INCLUDEDIR)
#   include/hcimpact/<compiler>-<major>/*.mod   (HCIMPACT_INSTALL_MODULEDIR)
#   lib/cmake/hcimpact/hcimpact-*.cmake         (HCIMPACT_INSTALL_CMAKEDIR)
#   lib/pkgconfig/hcimpact.pc                   (HCIMPACT_INSTALL_PKGCONFIGDIR)

include(CMakePackageConfigHelpers)

get_property(_hcimpact_components GLOBAL PROPERTY HCIMPACT_COMPONENT_TARGETS)

install(
  TARGETS hcimpact ${_hcimpact_components}
  EXPORT hcimpact-targets
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
  RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(
  DIRECTORY "${HCIMPACT_MODULE_DIR}/"
  DESTINATION "${HCIMPACT_INSTALL_MODULEDIR}"
  FILES_MATCHING PATTERN "*.mod" PATTERN "*.smod")
install(
  FILES "${PROJECT_SOURCE_DIR}/include/hcimpact.h"
  DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}")
install(
  EXPORT hcimpact-targets
  NAMESPACE hcimpact::
  DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}")

# Libraries a non-Fortran linker needs in addition to a static libhcimpact.a:
# the Fortran runtime. For gfortran that is -lgfortran -lm; for other
# compilers, what the Fortran link adds beyond the C link.
if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
  set(HCIMPACT_FORTRAN_RUNTIME gfortran m)
else()
  set(HCIMPACT_FORTRAN_RUNTIME ${CMAKE_Fortran_IMPLICIT_LINK_LIBRARIES})
  if(HCIMPACT_HAVE_C)
    list(REMOVE_ITEM HCIMPACT_FORTRAN_RUNTIME ${CMAKE_C_IMPLICIT_LINK_LIBRARIES})
  endif()
  list(REMOVE_DUPLICATES HCIMPACT_FORTRAN_RUNTIME)
endif()

if(BUILD_SHARED_LIBS)
  set(HCIMPACT_PACKAGE_SHARED TRUE)
else()
  set(HCIMPACT_PACKAGE_SHARED FALSE)
endif()
set(HCIMPACT_PACKAGE_COMPONENTS "")
foreach(_hcimpact_component_target IN LISTS _hcimpact_components)
  string(REGEX REPLACE "^hcimpact_" "" _hcimpact_component "${_hcimpact_component_target}")
  list(APPEND HCIMPACT_PACKAGE_COMPONENTS "${_hcimpact_component}")
endforeach()

configure_package_config_file(
  "${PROJECT_SOURCE_DIR}/cmake/hcimpact-config.cmake.in"
  "${PROJECT_BINARY_DIR}/hcimpact-config.cmake"
  INSTALL_DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}")
# 0.x releases promise nothing across minor versions.
write_basic_package_version_file(
  "${PROJECT_BINARY_DIR}/hcimpact-config-version.cmake"
  VERSION "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)
install(
  FILES
    "${PROJECT_BINARY_DIR}/hcimpact-config.cmake"
    "${PROJECT_BINARY_DIR}/hcimpact-config-version.cmake"
  DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}")

# pkg-config: directories are written relative to ${prefix} (the install
# prefix given at configure time) unless they were given as absolute paths;
# pkg-config then drops the system ones such as -I/usr/include by itself.
foreach(_hcimpact_dir IN ITEMS LIBDIR INCLUDEDIR MODULEDIR)
  if(_hcimpact_dir STREQUAL "MODULEDIR")
    set(_hcimpact_path "${HCIMPACT_INSTALL_MODULEDIR}")
  else()
    set(_hcimpact_path "${CMAKE_INSTALL_${_hcimpact_dir}}")
  endif()
  if(IS_ABSOLUTE "${_hcimpact_path}")
    set(HCIMPACT_PC_${_hcimpact_dir} "${_hcimpact_path}")
  else()
    set(HCIMPACT_PC_${_hcimpact_dir} "\${prefix}/${_hcimpact_path}")
  endif()
endforeach()
set(HCIMPACT_PC_LIBS_PRIVATE "")
foreach(_hcimpact_lib IN LISTS HCIMPACT_FORTRAN_RUNTIME)
  string(APPEND HCIMPACT_PC_LIBS_PRIVATE " -l${_hcimpact_lib}")
endforeach()
string(STRIP "${HCIMPACT_PC_LIBS_PRIVATE}" HCIMPACT_PC_LIBS_PRIVATE)
configure_file(
  "${PROJECT_SOURCE_DIR}/cmake/hcimpact.pc.in"
  "${PROJECT_BINARY_DIR}/hcimpact.pc"
  @ONLY)
install(
  FILES "${PROJECT_BINARY_DIR}/hcimpact.pc"
  DESTINATION "${HCIMPACT_INSTALL_PKGCONFIGDIR}")
