#!/usr/bin/env bash
# LABEL scripts: scripts/require-test-labels.sh passes only when every named label has a registered test, so
# that scripts/test.sh fails (not skips) when the gpu and shader tests are absent. Uses hand-written CTest
# files in a scratch directory (no configure, no build).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
check="$here/../../scripts/require-test-labels.sh"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0

expect_status() {  # NAME WANT_STATUS ARGS...
  local name=$1 want=$2 status=0
  shift 2
  bash "$check" "$@" >"$scratch/out" 2>&1 || status=$?
  if [ $status -eq "$want" ]; then echo "ok   $name"; else
    echo "FAIL $name: exit $status, expected $want: $(cat "$scratch/out")"; failures=$((failures + 1)); fi
}

mkdir -p "$scratch/full" "$scratch/no-gl" "$scratch/empty"
cat > "$scratch/full/CTestTestfile.cmake" <<'CT'
add_test(parity "true")
set_tests_properties(parity PROPERTIES LABELS "gpu")
add_test(shaders "true")
set_tests_properties(shaders PROPERTIES LABELS "shader")
CT
cat > "$scratch/no-gl/CTestTestfile.cmake" <<'CT'
add_test(unit "true")
set_tests_properties(unit PROPERTIES LABELS "unit")
add_test(lookalike "true")
set_tests_properties(lookalike PROPERTIES LABELS "gpux")
CT

expect_status "both labels present" 0 "$scratch/full" gpu shader
expect_status "demo off: neither label (a label 'gpux' is not 'gpu')" 1 "$scratch/no-gl" gpu shader
expect_status "one of two missing" 1 "$scratch/full" gpu shader slow
expect_status "an empty build tree" 1 "$scratch/empty" gpu
expect_status "a missing build directory" 1 "$scratch/nonexistent" gpu
expect_status "usage" 2 "$scratch/full"
message=$(bash "$check" "$scratch/no-gl" gpu shader 2>&1 || true)
case $message in
  *"no tests labelled: gpu shader"*) echo "ok   the message names the missing labels" ;;
  *) echo "FAIL message: $message"; failures=$((failures + 1)) ;;
esac

[ $failures -eq 0 ] || { echo "$failures case(s) failed"; exit 1; }
echo "all cases passed"
