#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
#
# Run a test command only if the tools it needs are present; otherwise print why
# and exit 77, which CTest reports as "Skipped" (SKIP_RETURN_CODE 77), not failed.
#
#   skip_unless.sh <tool>[,<tool>...] -- <command> [args...]
#   skip_unless.sh python:<module>[,<module>...] -- <command> [args...]   (with $PYTHON)
set -u
needs="$1"
shift
[ "${1:-}" = "--" ] && shift
case "$needs" in
  python:*)
    modules="${needs#python:}"
    py="${PYTHON:-python3}"
    for module in $(echo "$modules" | tr ',' ' '); do
      if ! "$py" -c "import $module" >/dev/null 2>&1; then
        echo "SKIPPED: the Python module '$module' is not available to $py"
        echo "(pip install $module, or see .ci/install)"
        exit 77
      fi
    done
    ;;
  *)
    for tool in $(echo "$needs" | tr ',' ' '); do
      if ! command -v "$tool" >/dev/null 2>&1; then
        echo "SKIPPED: '$tool' is not installed (see .ci/install)"
        exit 77
      fi
    done
    ;;
esac
exec "$@"
