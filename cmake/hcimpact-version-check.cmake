# SPDX-License-Identifier: Apache-2.0
#
# Script mode (cmake -DSOURCE_DIR=... -DEXPECTED=x.y.z -P this-file): check that
# the version written in CMakeLists.txt (EXPECTED) is also the one in fpm.toml,
# src/hcimpact/version_info.f90, include/hcimpact.h, the Python package
# (python/pyproject.toml, python/hcimpact/__init__.py), the components' fpm packages
# and CITATION.cff.

if(NOT SOURCE_DIR OR NOT EXPECTED)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<dir> -DEXPECTED=<x.y.z> -P hcimpact-version-check.cmake")
endif()

string(REPLACE "." ";" _parts "${EXPECTED}")
list(GET _parts 0 _major)
list(GET _parts 1 _minor)
list(GET _parts 2 _patch)
math(EXPR _compact "10000 * ${_major} + 100 * ${_minor} + ${_patch}")

set(_errors "")

function(_hc_expect file regex expected what)
  file(STRINGS "${SOURCE_DIR}/${file}" _lines REGEX "${regex}")
  set(_found "")
  foreach(_line IN LISTS _lines)
    if(_line MATCHES "${regex}")
      set(_found "${CMAKE_MATCH_1}")
      break()
    endif()
  endforeach()
  if(NOT _found STREQUAL "${expected}")
    set(_errors "${_errors}\n  ${file}: ${what} is '${_found}', expected '${expected}'" PARENT_SCOPE)
  endif()
endfunction()

_hc_expect("fpm.toml" "^version[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}" "version")
_hc_expect("src/hcimpact/version_info.f90" "hcimpact_version_string[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}"
  "hcimpact_version_string")
_hc_expect("src/hcimpact/version_info.f90" "version_major[ \t]*=[ \t]*([0-9]+)" "${_major}" "version_major")
_hc_expect("src/hcimpact/version_info.f90" "version_minor[ \t]*=[ \t]*([0-9]+)" "${_minor}" "version_minor")
_hc_expect("src/hcimpact/version_info.f90" "version_patch[ \t]*=[ \t]*([0-9]+)" "${_patch}" "version_patch")
_hc_expect("include/hcimpact.h" "#define[ \t]+HCIMPACT_VERSION_MAJOR[ \t]+([0-9]+)" "${_major}"
  "HCIMPACT_VERSION_MAJOR")
_hc_expect("include/hcimpact.h" "#define[ \t]+HCIMPACT_VERSION_MINOR[ \t]+([0-9]+)" "${_minor}"
  "HCIMPACT_VERSION_MINOR")
_hc_expect("include/hcimpact.h" "#define[ \t]+HCIMPACT_VERSION_PATCH[ \t]+([0-9]+)" "${_patch}"
  "HCIMPACT_VERSION_PATCH")
_hc_expect("include/hcimpact.h" "#define[ \t]+HCIMPACT_VERSION[ \t]+([0-9]+)" "${_compact}"
  "HCIMPACT_VERSION")

_hc_expect("python/pyproject.toml" "^version[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}" "version")
_hc_expect("python/hcimpact/__init__.py" "^__version__[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}"
  "__version__")
_hc_expect("components/cvode/fpm.toml" "^version[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}" "version")
_hc_expect("components/lapack/fpm.toml" "^version[ \t]*=[ \t]*\"([^\"]*)\"" "${EXPECTED}" "version")
_hc_expect("CITATION.cff" "^version:[ \t]*([0-9.]+)" "${EXPECTED}" "version")

if(_errors)
  message(FATAL_ERROR "Version numbers disagree with CMakeLists.txt (${EXPECTED}):${_errors}")
endif()
message(STATUS "hcimpact ${EXPECTED}: fpm.toml, version_info.f90, hcimpact.h, the Python "
  "package, the components' fpm.toml and CITATION.cff agree")
