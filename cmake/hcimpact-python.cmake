# SPDX-License-Identifier: Apache-2.0
#
# The Python wheel (python/pyproject.toml): scikit-build-core configures this project
# with SKBUILD set, installs the component hcimpact_runtime (the shared libraries) into
# the package directory, <site-packages>/hcimpact/lib/, and this file adds
# hcimpact/_build.json: which optional components the wheel has, and why one is
# missing (the configuration summary's words), so that the package can name the
# missing piece instead of saying only "not found".

if(NOT BUILD_SHARED_LIBS)
  message(FATAL_ERROR "The Python wheel needs the shared library: BUILD_SHARED_LIBS=ON "
    "(python/pyproject.toml sets it)")
endif()

function(_hcimpact_json_string out_var text)
  string(REPLACE "\\" "\\\\" text "${text}")
  string(REPLACE "\"" "\\\"" text "${text}")
  set(${out_var} "\"${text}\"" PARENT_SCOPE)
endfunction()

set(_hcimpact_json_entries "")
foreach(_hcimpact_component IN ITEMS cvode lapack)
  string(TOUPPER "${_hcimpact_component}" _hcimpact_upper)
  if(TARGET hcimpact_${_hcimpact_component})
    set(_hcimpact_built true)
  else()
    set(_hcimpact_built false)
  endif()
  _hcimpact_json_string(_hcimpact_status "${HCIMPACT_${_hcimpact_upper}_STATUS}")
  list(APPEND _hcimpact_json_entries
    "    \"${_hcimpact_component}\": {\"built\": ${_hcimpact_built}, \"status\": ${_hcimpact_status}}")
endforeach()
list(JOIN _hcimpact_json_entries ",\n" _hcimpact_json_entries)
file(WRITE "${PROJECT_BINARY_DIR}/python/_build.json" "{
  \"version\": \"${PROJECT_VERSION}\",
  \"libdir\": \"${CMAKE_INSTALL_LIBDIR}\",
  \"components\": {
${_hcimpact_json_entries}
  }
}
")
install(FILES "${PROJECT_BINARY_DIR}/python/_build.json" DESTINATION "."
  COMPONENT hcimpact_runtime)
