#!/usr/bin/env bash
# Builds and runs the whole emcv test suite: the Release build (every label), the ASan + UBSan build (every
# label except "slow"), then the library alone (EMCV_BUILD_DEMO, _TOOLS and _BENCH off, every label except
# "slow"), so that a build without the demo keeps building and passing. Installs missing distribution packages
# first. The Python module's tests (label python) run in the Release and library builds.
# The GPU parity and shader tests must run here: EMCV_REQUIRE_GL=1 turns their "no EGL display" skip into a
# failure, and a demo build without the labels gpu and shader fails before any test runs. The library build has
# no GL by design, so it is not held to those labels.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
export EMCV_REQUIRE_GL=1
build_dir() { case $1 in default) echo build ;; sanitize) echo build-sanitize ;; library) echo build-library ;; esac; }
for preset in default sanitize library; do
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset"
  if [ "$preset" != library ]; then
    bash scripts/require-test-labels.sh "$(build_dir "$preset")" gpu shader
  fi
  # the adaptive-sampling policy is GL-free: every preset runs it
  bash scripts/require-test-labels.sh "$(build_dir "$preset")" policy
  # the Python module (docs/python.md): every preset but sanitize (an ASan module needs LD_PRELOAD in python)
  if [ "$preset" != sanitize ]; then
    bash scripts/require-test-labels.sh "$(build_dir "$preset")" python
  fi
  ctest --preset "$preset"
done
