# SPDX-License-Identifier: Apache-2.0
#
# Helper functions of the hcimpact build: compile flags, optional components
# and examples.

# Normalise a tri-state option (AUTO / ON / OFF, any CMake boolean spelling for
# the last two) into one of the words AUTO, ON, OFF.
function(hcimpact_feature_mode option_name out_var)
  set(value "${${option_name}}")
  string(TOUPPER "${value}" upper)
  if(upper STREQUAL "" OR upper STREQUAL "AUTO")
    set(mode "AUTO")
  elseif(value)
    set(mode "ON")
  else()
    set(mode "OFF")
  endif()
  set(${out_var} "${mode}" PARENT_SCOPE)
endfunction()

# The libraries a C or C++ linker needs, beyond its own, to link objects compiled by
# the Fortran compiler: -lgfortran -lm for gfortran; for other compilers what the
# Fortran link adds beyond the C link.
function(hcimpact_fortran_runtime out_var)
  if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
    set(runtime gfortran m)
  else()
    set(runtime ${CMAKE_Fortran_IMPLICIT_LINK_LIBRARIES})
    if(CMAKE_C_IMPLICIT_LINK_LIBRARIES)
      list(REMOVE_ITEM runtime ${CMAKE_C_IMPLICIT_LINK_LIBRARIES})
    endif()
    list(REMOVE_DUPLICATES runtime)
  endif()
  set(${out_var} "${runtime}" PARENT_SCOPE)
endfunction()

# VERSION and SOVERSION of a library (libhcimpact.so.0.1 -> libhcimpact.so.0.1.0),
# except in the Python wheel: a wheel cannot hold the symbolic links, so there the
# libraries are plain libhcimpact.so, libhcimpact_cvode.so, ...
function(hcimpact_library_version target)
  if(NOT SKBUILD)
    set_target_properties(${target} PROPERTIES
      VERSION "${PROJECT_VERSION}"
      SOVERSION "${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}")
  endif()
endfunction()

# The extra Fortran flags of a Debug build with HCIMPACT_DEBUG_CHECKS=ON.
# -ffpe-trap takes effect in programs whose main unit is compiled with it; it
# turns an invalid operation (including an ordered comparison such as x < y
# with a NaN operand), a division by zero or an overflow into SIGFPE.
function(hcimpact_debug_flags out_var)
  set(flags "")
  if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
    # -Wno-compare-reals: exact comparisons are deliberate in this library
    # (branch points, exactly representable results) and in its tests
    # -Werror=character-truncation: a constant cut to its declared length (a list
    # of names longer than its array's length lost its last names)
    set(flags -Wall -Wextra -Wno-compare-reals -Werror=character-truncation -fcheck=all
      -ffpe-trap=invalid,zero,overflow -fbacktrace)
  elseif(CMAKE_Fortran_COMPILER_ID MATCHES "^Intel")
    set(flags -warn all -check all -fpe0 -traceback)
  endif()
  set(${out_var} "${flags}" PARENT_SCOPE)
endfunction()

# Compile options for every target built from our own sources (library,
# components, tests, examples).
function(hcimpact_target_flags target)
  hcimpact_debug_flags(debug_flags)
  if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
    # No contraction of a*b+c into a fused multiply-add behind our back (it is
    # the default of GCC once FMA instructions are enabled, e.g. by -march):
    # the error-free transformations of the library need each operation
    # rounded on its own.
    target_compile_options(${target} PRIVATE "$<$<COMPILE_LANGUAGE:Fortran>:-ffp-contract=off>")
    # Thread safety (the C API promises it; test/threads checks it):
    # -frecursive keeps every local variable on the stack (gfortran would put
    # large local arrays in static storage) and disables -fcheck=recursion,
    # whose per-procedure static flag aborts when two threads call the same
    # procedure at once ("Recursive call to nonrecursive procedure").
    target_compile_options(${target} PRIVATE "$<$<COMPILE_LANGUAGE:Fortran>:-frecursive>")
  endif()
  if(HCIMPACT_DEBUG_CHECKS AND debug_flags)
    target_compile_options(${target} PRIVATE
      "$<$<AND:$<CONFIG:Debug>,$<COMPILE_LANGUAGE:Fortran>>:${debug_flags}>")
  endif()
  if(HCIMPACT_DEBUG_CHECKS AND HCIMPACT_HAVE_C AND CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE
      "$<$<AND:$<CONFIG:Debug>,$<COMPILE_LANGUAGE:C>>:-Wall;-Wextra>")
  endif()
endfunction()

# Link-time optimisation of a library of ours in the optimised configurations
# (Release, RelWithDebInfo, MinSizeRel), when HCIMPACT_LTO is on and the compiler
# supports it. It lets the compiler inline small procedures across modules: the
# double-double operators of hcimpact_double_double, applied about a hundred times in
# the set-up of one impact, are otherwise a call each (measured: one impact about 7 %
# faster than the former copies of the operators in every module, 10 % faster than
# calls; doc/building.md). A static archive keeps fat objects (machine code next to
# the intermediate code), so that programs linked without LTO, or by another
# compiler's linker, link it as before.
function(hcimpact_library_lto target)
  if(NOT HCIMPACT_LTO OR NOT HCIMPACT_LTO_SUPPORTED)
    return()
  endif()
  foreach(config RELEASE RELWITHDEBINFO MINSIZEREL)
    set_property(TARGET ${target} PROPERTY INTERPROCEDURAL_OPTIMIZATION_${config} TRUE)
  endforeach()
  # GCC's inliner at -O2 leaves most double-double operators of the set-up of an impact
  # as calls even under LTO (-fopt-info-inline-missed at the link: mul_dd_dd, about 55
  # instructions, is above max-inline-insns-auto, 15 at -O2, and once that is raised
  # the library's whole inline-unit-growth budget is spent before it). These two
  # limits, read from the compile options of each function, let them be inlined:
  # 8.6 % fewer instructions per impact for beta <= 1.8, 3.5 to 4.6 % beyond,
  # bit-identical outcomes (doc/building.md; the library grows by 94 kB)
  if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE
      "$<$<AND:$<CONFIG:Release,RelWithDebInfo,MinSizeRel>,$<COMPILE_LANGUAGE:Fortran>>:--param=max-inline-insns-auto=80;--param=inline-unit-growth=300>")
  endif()
  get_target_property(type ${target} TYPE)
  # Fat objects (machine code next to the compiler's IR) for a static library, which
  # a program may link without LTO, and for the benchmarks' renamed static copy of
  # the shared library's objects (bench/lambertw/prefix_symbols.cmake)
  if((type STREQUAL "STATIC_LIBRARY" OR HCIMPACT_BUILD_BENCH)
     AND CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE
      "$<$<CONFIG:Release,RelWithDebInfo,MinSizeRel>:-ffat-lto-objects>")
  endif()
endfunction()

# Link options of a shared library of ours: -Bsymbolic-functions binds the
# library's calls of its own functions inside the library, so that a C entry
# point reaches the Fortran procedure it wraps by a direct jump instead of
# through the library's own PLT (issue 17: 1.4x on the shortest Lambert W
# path). The price: a program can no longer interpose (replace) one of the
# library's functions for the library's own calls; nothing relies on that
# (doc/building.md). No effect on a static library, nor on data symbols.
function(hcimpact_shared_link_flags target)
  get_target_property(type ${target} TYPE)
  if(NOT type STREQUAL "SHARED_LIBRARY")
    return()
  endif()
  if(NOT DEFINED CACHE{HCIMPACT_LINKER_BSYMBOLIC_FUNCTIONS})
    include(CheckLinkerFlag)
    check_linker_flag(Fortran "-Wl,-Bsymbolic-functions" HCIMPACT_LINKER_BSYMBOLIC_FUNCTIONS)
  endif()
  if(HCIMPACT_LINKER_BSYMBOLIC_FUNCTIONS)
    target_link_options(${target} PRIVATE "-Wl,-Bsymbolic-functions")
    # The calls inside the library are then bound to its own procedures; let the
    # compiler know, so that it may inline one module's procedures into another's
    # (with -fPIC and default visibility it otherwise assumes they may be interposed,
    # and link-time optimisation keeps every call: bit_exponent, two_prod, ...).
    if(NOT DEFINED CACHE{HCIMPACT_FORTRAN_NO_SEMANTIC_INTERPOSITION})
      include(CheckCompilerFlag)
      check_compiler_flag(Fortran "-fno-semantic-interposition"
        HCIMPACT_FORTRAN_NO_SEMANTIC_INTERPOSITION)
    endif()
    if(HCIMPACT_FORTRAN_NO_SEMANTIC_INTERPOSITION)
      target_compile_options(${target} PRIVATE
        "$<$<COMPILE_LANGUAGE:Fortran>:-fno-semantic-interposition>")
    endif()
  endif()
endfunction()

# hcimpact_add_component(<name> [LIBRARIES ...] [DEFINITIONS ...])
#
# Build the library hcimpact_<name> (alias hcimpact::<name>, exported as
# hcimpact::<name>) from components/<name>/*.f90 / *.F90, if that directory
# holds any source. Sources are preprocessed, so DEFINITIONS reach them.
# The target is only created when there is something to compile.
function(hcimpact_add_component name)
  cmake_parse_arguments(arg "" "" "LIBRARIES;DEFINITIONS" ${ARGN})
  set(dir "${PROJECT_SOURCE_DIR}/components/${name}")
  if(NOT IS_DIRECTORY "${dir}")
    return()
  endif()
  file(GLOB sources CONFIGURE_DEPENDS "${dir}/*.f90" "${dir}/*.F90")
  if(NOT sources)
    return()
  endif()
  list(SORT sources)
  set(target "hcimpact_${name}")
  add_library(${target} ${sources})
  add_library(hcimpact::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES
    EXPORT_NAME "${name}"
    POSITION_INDEPENDENT_CODE ON
    Fortran_PREPROCESS ON
    Fortran_MODULE_DIRECTORY "${HCIMPACT_MODULE_DIR}"
    INSTALL_RPATH_USE_LINK_PATH TRUE)
  hcimpact_library_version(${target})
  # An installed component finds libhcimpact beside it, wherever the tree was
  # installed (the prefix may be chosen at install time) or moved to.
  if(APPLE)
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "@loader_path")
  elseif(UNIX)
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "\$ORIGIN")
  endif()
  target_link_libraries(${target} PUBLIC hcimpact)
  if(arg_LIBRARIES)
    target_link_libraries(${target} PRIVATE ${arg_LIBRARIES})
  endif()
  if(arg_DEFINITIONS)
    target_compile_definitions(${target} PRIVATE ${arg_DEFINITIONS})
  endif()
  hcimpact_target_flags(${target})
  hcimpact_shared_link_flags(${target})
  set_property(GLOBAL APPEND PROPERTY HCIMPACT_COMPONENT_TARGETS ${target})
endfunction()

# Every directory example/<name>/ with a main.f90 (Fortran) or main.c (C)
# becomes the executable <build>/example/<name>; other sources in the same
# directory are compiled into it too. With testing on, each example also runs
# as the CTest test hcimpact/example/<name>.
#
# An example that needs optional components lists their names, one per line
# (`#` starts a comment), in example/<name>/components.txt, e.g. `cvode`: it is
# linked to hcimpact::<component> as well, and skipped (with a note in the
# summary) when one of them is not built.
function(hcimpact_add_examples root)
  file(GLOB entries LIST_DIRECTORIES true CONFIGURE_DEPENDS "${root}/*")
  list(SORT entries)
  set(built "")
  set(skipped "")
  set(skipped_components "")
  foreach(dir IN LISTS entries)
    if(NOT IS_DIRECTORY "${dir}")
      continue()
    endif()
    get_filename_component(name "${dir}" NAME)
    if(EXISTS "${dir}/main.f90" OR EXISTS "${dir}/main.F90")
      set(lang Fortran)
    elseif(EXISTS "${dir}/main.c")
      set(lang C)
      if(NOT HCIMPACT_HAVE_C)
        list(APPEND skipped "${name}")
        continue()
      endif()
    else()
      continue()
    endif()
    set(needs "")
    if(EXISTS "${dir}/components.txt")
      file(STRINGS "${dir}/components.txt" lines)
      foreach(line IN LISTS lines)
        string(REGEX REPLACE "#.*$" "" line "${line}")
        string(STRIP "${line}" line)
        if(line)
          list(APPEND needs "${line}")
        endif()
      endforeach()
    endif()
    set(missing "")
    foreach(component IN LISTS needs)
      if(NOT TARGET hcimpact_${component})
        list(APPEND missing "${component}")
      endif()
    endforeach()
    if(missing)
      list(JOIN missing "+" text)
      list(APPEND skipped_components "${name} (needs ${text})")
      continue()
    endif()
    file(GLOB sources CONFIGURE_DEPENDS "${dir}/*.f90" "${dir}/*.F90")
    if(HCIMPACT_HAVE_C)
      file(GLOB c_sources CONFIGURE_DEPENDS "${dir}/*.c")
      list(APPEND sources ${c_sources})
    endif()
    set(target "hcimpact-example-${name}")
    add_executable(${target} ${sources})
    target_link_libraries(${target} PRIVATE hcimpact)
    foreach(component IN LISTS needs)
      target_link_libraries(${target} PRIVATE hcimpact_${component})
    endforeach()
    set_target_properties(${target} PROPERTIES
      OUTPUT_NAME "${name}"
      RUNTIME_OUTPUT_DIRECTORY "${PROJECT_BINARY_DIR}/example"
      Fortran_MODULE_DIRECTORY "${PROJECT_BINARY_DIR}/example/modules/${name}")
    if(lang STREQUAL "C")
      # A C main program still needs the Fortran runtime of the library.
      set_target_properties(${target} PROPERTIES LINKER_LANGUAGE Fortran)
    endif()
    hcimpact_target_flags(${target})
    if(BUILD_TESTING AND HCIMPACT_IS_TOP_LEVEL)
      add_test(NAME "hcimpact/example/${name}" COMMAND ${target})
      set_tests_properties("hcimpact/example/${name}" PROPERTIES
        LABELS "example"
        ENVIRONMENT "HCIMPACT_REFERENCE_DIR=${PROJECT_SOURCE_DIR}/test/reference")
    endif()
    list(APPEND built "${name}")
  endforeach()
  if(built)
    list(JOIN built ", " text)
    set(status "ON (${text})")
  else()
    set(status "ON (none found)")
  endif()
  if(skipped)
    list(JOIN skipped ", " text)
    string(APPEND status "; skipped without a C compiler: ${text}")
  endif()
  if(skipped_components)
    list(JOIN skipped_components ", " text)
    string(APPEND status "; skipped: ${text}")
  endif()
  set(HCIMPACT_EXAMPLES_STATUS "${status}" PARENT_SCOPE)
endfunction()
