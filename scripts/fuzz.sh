#!/usr/bin/env bash
# Builds the libFuzzer targets with clang in build-fuzz/ and runs each for a bounded time.
#   bash scripts/fuzz.sh [SECONDS per target, default 60] [TARGET...]   (targets: estimators scene sampling; default all)
# Each run starts from the repository corpus (tests/fuzz/corpus/<target>/, read only: the run's new inputs go
# to build-fuzz/corpus/<target>/, kept between runs), with ASan + UBSan; a crash, hang (-timeout 10 s per
# input), invariant violation or sanitizer report leaves the input in build-fuzz/artifacts/<target>/ and makes
# the script exit non-zero. Once fixed, copy that input into the repository corpus as regression-<what>: the
# test command replays the corpus (label fuzz) without clang.
# Needs clang and libFuzzer: apt-get install clang libclang-rt-14-dev (not part of install-deps.sh: the test
# command itself does not need them).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2;; esac
all_targets=(estimators scene sampling)
targets=("${@:2}")
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  case " ${all_targets[*]} " in *" $t "*) ;; *) echo "fuzz.sh: unknown target '$t' (targets: ${all_targets[*]})" >&2; exit 2;; esac
done
command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }

# The scene target links the demo's scene library (EMCV_BUILD_DEMO=ON; only the fuzz targets are built). Every
# object file gets libFuzzer's coverage and the sanitizers, so that the loader's own branches guide the search.
CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DEMCV_BUILD_FUZZERS=ON \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer" \
  -DEMCV_BUILD_DEMO=ON -DEMCV_BUILD_BENCH=OFF -DEMCV_INSTALL=OFF >/dev/null
cmake --build build-fuzz --target "${targets[@]/#/emcv-fuzz-}"

status=0
for t in "${targets[@]}"; do
  work=build-fuzz/corpus/$t artifacts=build-fuzz/artifacts/$t
  mkdir -p "$work" "$artifacts"
  echo "== $t: ${seconds} s"
  rc=0
  build-fuzz/bin/emcv-fuzz-$t -max_total_time="$seconds" -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" "$work" "tests/fuzz/corpus/$t" >"build-fuzz/$t.log" 2>&1 || rc=$?
  grep -E "^(Done|stat::number_of_executed_units|stat::average_exec_per_sec|stat::new_units_added)|ERROR|SUMMARY|emcv fuzz invariant" \
    "build-fuzz/$t.log" || true
  if [ "$rc" -ne 0 ] || [ -n "$(ls -A "$artifacts")" ]; then
    echo "fuzz.sh: $t found a problem (exit $rc); inputs in $artifacts/, log in build-fuzz/$t.log" >&2
    status=1
  fi
done
exit $status
