#!/usr/bin/env bash
# Builds and runs the whole emcv test suite: the Release build (every label), then the ASan + UBSan build
# (every label except "slow"). Installs missing distribution packages first.
# The GPU parity and shader tests must run here: EMCV_REQUIRE_GL=1 turns their "no EGL display" skip into a
# failure, and a build without the labels gpu and shader (demo off) fails before any test runs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
export EMCV_REQUIRE_GL=1
build_dir() { case $1 in default) echo build ;; sanitize) echo build-sanitize ;; esac; }
for preset in default sanitize; do
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset"
  bash scripts/require-test-labels.sh "$(build_dir "$preset")" gpu shader
  ctest --preset "$preset"
done
