#!/usr/bin/env bash
# Regenerates the golden regression images in tests/image/golden/ (the cases in tests/image/golden/cases.txt)
# and prints, per image, what changed against the committed one: "unchanged", "new", or the idiff-style line
# (pixels over the fail threshold, their share, the largest difference, RMSE, PSNR). Review the diff before
# committing: a golden changes only with an intended change of the renderer.
#   bash scripts/update-golden.sh                 # every case
#   bash scripts/update-golden.sh --only light-off.   # cases whose stem contains the text
# BUILD_DIR (default build/) is configured and emcv-golden built there. Renders on Mesa llvmpipe, like CI.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" --target emcv-golden >/dev/null
LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/emcv-golden" update "$@"
git status --short tests/image/golden/
