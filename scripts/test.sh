#!/usr/bin/env bash
# Builds and runs the whole emcv test suite: the Release build (every label), then the ASan + UBSan build
# (every label except "slow"). Installs missing distribution packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
for preset in default sanitize; do
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset"
  ctest --preset "$preset"
done
