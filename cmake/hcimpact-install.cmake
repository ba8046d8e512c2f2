# SPDX-License-Identifier: Apache-2.0
#
# Install rules: the library and the built components, the .mod files, the C
# headers, the CMake package hcimpact (targets hcimpact::hcimpact, hcimpact::cvode,
# hcimpact::lapack, hcimpact::mpi) and the pkg-config files. Layout, relative to the prefix:
#
#   lib/libhcimpact{,_cvode,_lapack,_mpi}.{a,so}    (CMAKE_INSTALL_LIBDIR)
#   include/hcimpact*.h                             (CMAKE_INSTALL_INCLUDEDIR)
#   include/hcimpact/<compiler>-<major>/*.mod       (HCIMPACT_INSTALL_MODULEDIR)
#   lib/cmake/hcimpact/hcimpact-config.cmake, -config-version.cmake,
#     hcimpact-targets.cmake (core), hcimpact-<component>-targets.cmake,
#     Findhcimpact_sundials.cmake                   (HCIMPACT_INSTALL_CMAKEDIR)
#   lib/pkgconfig/hcimpact.pc, hcimpact-<component>.pc (HCIMPACT_INSTALL_PKGCONFIGDIR)
#
# Install components: hcimpact_runtime (the shared libraries) and
# hcimpact_development (everything else: static libraries, the shared libraries'
# names for the linker, headers, .mod files, CMake and pkg-config files); the Python
# wheel takes the runtime only (python/pyproject.toml).
#
# Everything is relocatable: the CMake package finds itself from its own directory,
# and the pkg-config files name their prefix relative to theirs (${pcfiledir}), so a
# prefix chosen at install time (cmake --install <build> --prefix <dir>) works, and
# so does moving the installed tree.

include(CMakePackageConfigHelpers)

get_property(_hcimpact_components GLOBAL PROPERTY HCIMPACT_COMPONENT_TARGETS)

# The core and each component in an export set of its own: the package loads a
# component's targets only when that component is wanted and its dependency found.
set(_hcimpact_library_destinations
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT hcimpact_development
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT hcimpact_runtime
    NAMELINK_COMPONENT hcimpact_development
  RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}" COMPONENT hcimpact_runtime)
install(TARGETS hcimpact EXPORT hcimpact-targets ${_hcimpact_library_destinations})
install(
  EXPORT hcimpact-targets
  NAMESPACE hcimpact::
  DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}"
  COMPONENT hcimpact_development)
set(HCIMPACT_PACKAGE_COMPONENTS "")
foreach(_hcimpact_component_target IN LISTS _hcimpact_components)
  string(REGEX REPLACE "^hcimpact_" "" _hcimpact_component "${_hcimpact_component_target}")
  list(APPEND HCIMPACT_PACKAGE_COMPONENTS "${_hcimpact_component}")
  install(TARGETS ${_hcimpact_component_target}
    EXPORT hcimpact-${_hcimpact_component}-targets ${_hcimpact_library_destinations})
  install(
    EXPORT hcimpact-${_hcimpact_component}-targets
    NAMESPACE hcimpact::
    DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}"
    COMPONENT hcimpact_development)
endforeach()

# The installed .mod files are the Fortran API: the umbrella modules and the topic
# modules the documentation names (doc/building.md). gfortran writes into a module file
# everything a user of it needs, so the internal modules (double-double, rules, the C
# and FORTRAN 77 layers, the components' solvers) stay in the build tree.
set(_hcimpact_public_modules
  hcimpact hcimpact_kinds hcimpact_status hcimpact_version_info hcimpact_lambertw
  hcimpact_restitution_law hcimpact_quadrature hcimpact_impact_model hcimpact_hertz
  hcimpact_elastic hcimpact_force_element hcimpact_chain hcimpact_chain_types
  hcimpact_legacy_damping hcimpact_parallel)
if(TARGET hcimpact_cvode)
  list(APPEND _hcimpact_public_modules hcimpact_cvode)
endif()
if(TARGET hcimpact_lapack)
  list(APPEND _hcimpact_public_modules hcimpact_calibration)
endif()
if(TARGET hcimpact_mpi)
  list(APPEND _hcimpact_public_modules hcimpact_mpi_sweep hcimpact_mpi_hand_out)
endif()
list(TRANSFORM _hcimpact_public_modules PREPEND "${HCIMPACT_MODULE_DIR}/")
list(TRANSFORM _hcimpact_public_modules APPEND ".mod")
install(
  FILES ${_hcimpact_public_modules}
  DESTINATION "${HCIMPACT_INSTALL_MODULEDIR}"
  COMPONENT hcimpact_development)
install(
  DIRECTORY "${PROJECT_SOURCE_DIR}/include/"
  DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
  COMPONENT hcimpact_development
  FILES_MATCHING PATTERN "hcimpact*.h")

# ---------------------------------------------------------------------------
# CMake package
# ---------------------------------------------------------------------------
if(BUILD_SHARED_LIBS)
  set(HCIMPACT_PACKAGE_SHARED TRUE)
else()
  set(HCIMPACT_PACKAGE_SHARED FALSE)
endif()
# Why each component that was not built is missing, for the package's messages.
set(HCIMPACT_PACKAGE_CVODE_STATUS "${HCIMPACT_CVODE_STATUS}")
set(HCIMPACT_PACKAGE_LAPACK_STATUS "${HCIMPACT_LAPACK_STATUS}")
set(HCIMPACT_PACKAGE_MPI_STATUS "${HCIMPACT_MPI_COMPONENT_STATUS}")
# Where the build found SUNDIALS: a hint (not a requirement) for the consumer's search.
set(HCIMPACT_PACKAGE_SUNDIALS_HINT "")
if(HCIMPACT_SUNDIALS_INCLUDE_DIR)
  get_filename_component(HCIMPACT_PACKAGE_SUNDIALS_HINT "${HCIMPACT_SUNDIALS_INCLUDE_DIR}" DIRECTORY)
endif()

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
    "${PROJECT_SOURCE_DIR}/cmake/Findhcimpact_sundials.cmake"
  DESTINATION "${HCIMPACT_INSTALL_CMAKEDIR}"
  COMPONENT hcimpact_development)

# ---------------------------------------------------------------------------
# pkg-config: hcimpact.pc, and hcimpact-<component>.pc for each built component
# ---------------------------------------------------------------------------
# The prefix relative to the .pc file's own directory, so that the files stay right
# wherever the tree is installed; absolute only when a directory was given absolute.
if(IS_ABSOLUTE "${HCIMPACT_INSTALL_PKGCONFIGDIR}")
  set(HCIMPACT_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _hcimpact_up "/hcimpact-root/${HCIMPACT_INSTALL_PKGCONFIGDIR}" "/hcimpact-root")
  string(REGEX REPLACE "/$" "" _hcimpact_up "${_hcimpact_up}")
  set(HCIMPACT_PC_PREFIX "\${pcfiledir}/${_hcimpact_up}")
endif()
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

# "-L<dir> -l<name>" for a list of libraries given as full paths, names or targets
# (imported targets are expanded through their INTERFACE_LINK_LIBRARIES); the
# linker's own directories are left out.
function(_hcimpact_pc_link_flags out_var)
  set(flags "")
  set(dirs "")
  set(items ${ARGN})
  while(items)
    list(POP_FRONT items item)
    if(TARGET "${item}")
      get_target_property(inner "${item}" INTERFACE_LINK_LIBRARIES)
      if(inner)
        list(PREPEND items ${inner})
      endif()
      continue()
    endif()
    if(item MATCHES "^-")
      list(APPEND flags "${item}")
    elseif(IS_ABSOLUTE "${item}")
      get_filename_component(dir "${item}" DIRECTORY)
      get_filename_component(name "${item}" NAME_WE)
      string(REGEX REPLACE "^lib" "" name "${name}")
      if(NOT dir IN_LIST CMAKE_C_IMPLICIT_LINK_DIRECTORIES
          AND NOT dir IN_LIST CMAKE_Fortran_IMPLICIT_LINK_DIRECTORIES
          AND NOT dir IN_LIST dirs)
        list(APPEND dirs "${dir}")
        list(APPEND flags "-L${dir}")
      endif()
      list(APPEND flags "-l${name}")
    elseif(item)
      list(APPEND flags "-l${item}")
    endif()
  endwhile()
  list(JOIN flags " " flags)
  set(${out_var} "${flags}" PARENT_SCOPE)
endfunction()

_hcimpact_pc_link_flags(HCIMPACT_PC_LIBS_PRIVATE ${HCIMPACT_FORTRAN_RUNTIME})
set(HCIMPACT_PC_NAME "hcimpact")
set(HCIMPACT_PC_DESCRIPTION "${PROJECT_DESCRIPTION}")
set(HCIMPACT_PC_REQUIRES "")
set(HCIMPACT_PC_LIBS "-L\${libdir} -lhcimpact")
# A static libhcimpact.a built with OpenMP calls the OpenMP runtime, which a Fortran
# or C link does not name by itself: in Libs, so that `pkg-config --libs` (without
# --static, as legacy makefiles call it) is enough.
if(NOT BUILD_SHARED_LIBS AND HCIMPACT_OPENMP_ENABLED)
  _hcimpact_pc_link_flags(_hcimpact_pc_openmp ${OpenMP_Fortran_LIB_NAMES})
  string(APPEND HCIMPACT_PC_LIBS " ${_hcimpact_pc_openmp}")
endif()
set(HCIMPACT_PC_CFLAGS "Cflags: -I\${includedir} -I\${moduledir}")
configure_file("${PROJECT_SOURCE_DIR}/cmake/hcimpact.pc.in" "${PROJECT_BINARY_DIR}/hcimpact.pc" @ONLY)
install(FILES "${PROJECT_BINARY_DIR}/hcimpact.pc" DESTINATION "${HCIMPACT_INSTALL_PKGCONFIGDIR}"
  COMPONENT hcimpact_development)

set(_hcimpact_pc_cvode_what "the ODE path through SUNDIALS CVODE (hcimpact_simulate)")
set(_hcimpact_pc_lapack_what "calibration with LAPACK (hcimpact_fit_*)")
set(_hcimpact_pc_mpi_what "sweeps of impacts over the ranks of an MPI communicator (hcimpact_mpi_impact_sweep)")
foreach(_hcimpact_component IN LISTS HCIMPACT_PACKAGE_COMPONENTS)
  get_target_property(_hcimpact_deps hcimpact_${_hcimpact_component} LINK_LIBRARIES)
  list(REMOVE_ITEM _hcimpact_deps hcimpact)
  # (a dependency linked both privately and publicly, as MPI by the mpi component)
  list(REMOVE_DUPLICATES _hcimpact_deps)
  _hcimpact_pc_link_flags(HCIMPACT_PC_LIBS_PRIVATE ${_hcimpact_deps})
  set(HCIMPACT_PC_NAME "hcimpact-${_hcimpact_component}")
  set(HCIMPACT_PC_DESCRIPTION "hcimpact component ${_hcimpact_component}: ${_hcimpact_pc_${_hcimpact_component}_what}")
  set(HCIMPACT_PC_REQUIRES "Requires: hcimpact = ${PROJECT_VERSION}")
  set(HCIMPACT_PC_LIBS "-L\${libdir} -lhcimpact_${_hcimpact_component}")
  # the include directories come with hcimpact (Requires)
  set(HCIMPACT_PC_CFLAGS "")
  configure_file("${PROJECT_SOURCE_DIR}/cmake/hcimpact.pc.in"
    "${PROJECT_BINARY_DIR}/hcimpact-${_hcimpact_component}.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/hcimpact-${_hcimpact_component}.pc"
    DESTINATION "${HCIMPACT_INSTALL_PKGCONFIGDIR}" COMPONENT hcimpact_development)
endforeach()
