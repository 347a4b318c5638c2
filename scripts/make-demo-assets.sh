#!/usr/bin/env bash
# Remakes demo/assets/ (the small mesh copies the built-in scenes use) from the full scans in
# ../shared/assets (or $EMCV_SHARED_ASSETS): builds emcv-decimate (off by default) in build-assets/ and runs
# it once per asset. Each line below is the command that made the committed file (demo/assets/CREDITS.md).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
src=${EMCV_SHARED_ASSETS:-$root/../shared/assets}
out=$root/demo/assets
build=${EMCV_ASSET_BUILD:-$root/build-assets}
if [ ! -f "$src/README.md" ]; then
  echo "make-demo-assets: no shared assets in $src (set EMCV_SHARED_ASSETS)" >&2
  exit 2
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DEMCV_BUILD_ASSET_TOOLS=ON \
  -DEMCV_BUILD_TESTS=OFF -DEMCV_BUILD_BENCH=OFF -DEMCV_BUILD_TOOLS=ON >/dev/null
cmake --build "$build" --target emcv-decimate >/dev/null
decimate=$build/bin/emcv-decimate
mkdir -p "$out"
"$decimate" "$src/stanford-bunny.obj" "$out/bunny.ply" --triangles 12000 --fit-height 1
"$decimate" "$src/igea.ply" "$out/igea.ply" --triangles 12000 --fit-height 1
"$decimate" "$src/spot.obj" "$out/spot.ply" --fit-height 1
install -m 644 "$src/spot_texture.png" "$out/spot_texture.png"
