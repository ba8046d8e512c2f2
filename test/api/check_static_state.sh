#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
#
# Thread safety: the libraries keep no state. This check reads the symbol tables
# (nm) of the given libraries (static .a or shared .so) and fails on writable data
# that one thread could change under another:
#
#  - every local data symbol (nm type b or d): a SAVEd local variable (also implied
#    by an initialiser, `integer :: n = 0`), or a hidden static of the compiler,
#    such as gfortran's `slen.N`, the length of a deferred-length character function
#    result, which gfortran keeps in a static variable of the caller even with
#    -frecursive (two threads calling such a function at once race on it), or
#    `print_warning.N`, the once-only flag of -fcheck=array-temps where an array
#    argument may need a temporary copy;
#  - every module variable (nm type B, D, b or d with _MOD_ in the name), except the
#    compiler's read-only tables (__vtab_*, __def_init_*), the C layer's constant
#    message and version tables (hcimpact_api: message_table, version_text, `save,
#    target` so that C receives pointers into them, never written), the tables of
#    Lambert W (hcimpact_lambertw_tables: geo_z, geo_t, `protected` and initialised,
#    never written; see that module for why they are not parameters) and the indices
#    of implied-do loops in constant initialisers, which the library names with a
#    trailing underscore (jj_; written only at compile time);
#  - COMMON blocks (nm type C, or B/D named like FORTRAN 77 commons).
#
# The startup code that the linker puts into a shared library (completed.0,
# __TMC_END__, _DYNAMIC, ...) is not ours and is ignored.
#
# Usage: check_static_state.sh LIBRARY...   Exit 0 when clean, 1 with findings,
# 77 (skip) when nm is missing, 2 when a library has no symbol table (stripped).
set -euo pipefail

if ! command -v nm >/dev/null 2>&1; then
  echo "SKIPPED: nm not found"
  exit 77
fi
if [ "$#" -eq 0 ]; then
  echo "usage: $0 LIBRARY..." >&2
  exit 2
fi

# startup code of a shared library (crtstuff, the dynamic linker's tables)
toolchain='^(completed\.[0-9]+|__TMC_END__|_DYNAMIC|_GLOBAL_OFFSET_TABLE_|__dso_handle|__frame_dummy_init_array_entry|__do_global_dtors_aux_fini_array_entry|__bss_start|_edata|_end|__data_start|data_start)$'
# read-only module data of gfortran, of the C layer and of Lambert W's tables,
# implied-do indices
module_ok='(_MOD___vtab_|_MOD___def_init_|^__hcimpact_api_MOD_(message_table|version_text)$|^__hcimpact_lambertw_tables_MOD_geo_[zt]$|_MOD_[a-z0-9_]*[a-z0-9]_$)'

findings=0
for lib in "$@"; do
  if [ ! -f "$lib" ]; then
    echo "no such library: $lib" >&2
    exit 2
  fi
  # (a member without symbols, e.g. a module of only parameters or interfaces, is
  # fine; a library without any defined symbol is stripped)
  # The real symbol table of every member: with link-time optimisation an archive's
  # members carry an LTO symbol table too, which nm's plugin would read instead (every
  # datum of type D at address 0); a dummy plugin keeps nm to the machine code's.
  symbols="$(nm --plugin /dev/null "$lib" 2>/dev/null || true)"
  if ! grep -qE '^[0-9a-f]+ [A-Za-z] ' <<<"$symbols"; then
    symbols="$(nm "$lib" 2>&1 || true)"
  fi
  if ! grep -qE '^[0-9a-f]+ [A-Za-z] ' <<<"$symbols"; then
    echo "$lib: no symbol table (stripped?): cannot check" >&2
    exit 2
  fi
  # lines "address type name" (archive member headers and undefined symbols skipped)
  bad="$(awk -v toolchain="$toolchain" -v module_ok="$module_ok" '
    NF == 3 {
      type = $2; name = $3
      if (name ~ toolchain) next
      # (a private module variable is a local symbol in a shared library)
      if (name ~ /_MOD_/ && (type == "b" || type == "d" || type == "B" || type == "D")) {
        if (name !~ module_ok) print "module variable   " type "  " name
        next
      }
      if (type == "b" || type == "d") { print "local static      " type "  " name; next }
      if (type == "C") { print "common block      " type "  " name; next }
    }' <<<"$symbols")"
  if [ -n "$bad" ]; then
    findings=1
    echo "$lib: writable static data (shared by all threads):"
    sed 's/^/  /' <<<"$bad"
  else
    echo "$lib: no local statics, module variables or commons"
  fi
done
if [ "$findings" -ne 0 ]; then
  cat <<'EOF'
A `slen.N` is the length of a deferred-length character function result
(character(len=:), allocatable) kept by gfortran in a static variable of the
caller: give the result a length from a specification function, or make the
function a subroutine with an allocatable intent(out) argument (see
src/hcimpact/status.f90). Other names: a SAVEd local or a module variable.
EOF
  exit 1
fi
