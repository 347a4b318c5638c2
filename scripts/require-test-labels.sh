#!/usr/bin/env bash
# Fails unless the CTest tree in BUILD_DIR registers at least one test under each LABEL: scripts/test.sh uses it
# so that the GPU parity and shader tests cannot vanish from a run (they are not built when the demo is off).
# Usage: bash scripts/require-test-labels.sh BUILD_DIR LABEL...   Exit: 0 all present, 1 one missing, 2 usage.
set -euo pipefail
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/require-test-labels.sh BUILD_DIR LABEL..." >&2
  exit 2
fi
build=$1
shift
if [ ! -d "$build" ]; then
  echo "require-test-labels: no build directory '$build'" >&2
  exit 1
fi
missing=()
for label in "$@"; do
  count=$(ctest --test-dir "$build" -N -L "^${label}\$" 2>/dev/null | sed -n 's/^Total Tests: *\([0-9][0-9]*\)$/\1/p')
  [ "${count:-0}" -gt 0 ] || missing+=("$label")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "require-test-labels: $build has no tests labelled: ${missing[*]} (built with EMCV_BUILD_DEMO=OFF?)" >&2
  exit 1
fi
