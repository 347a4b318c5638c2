#!/usr/bin/env bash
# The adaptive methods' measured tables and plots (docs/demo.md "Adaptive methods", docs/renderer.md):
# renders each scene with spvg, cv, cv-notex and the reference through emcv-demo (headless, llvmpipe), then
# tools/cvstudy/adaptive_report.py writes docs/adaptive/<scene>.png and prints the Markdown table.
# Usage: bash tools/cvstudy/adaptive_report.sh [BUILD_DIR (default build)] [WxH (default 128x96)]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
size="${2:-128x96}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
scenes=("$root/tools/cvstudy/scenes/light-switch.json" light-off flicker club static)
for scene in "${scenes[@]}"; do
  name="$(basename "$scene" .json)"
  LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/emcv-demo" --scene "$scene" --method spvg,cv,cv-notex,reference \
    --size "$size" --seed 1 --out "$work/$name" > "$work/$name.log"
  "$build/bin/emcv-light-curves" "$scene" > "$work/$name/lights.csv"
done
mkdir -p "$root/docs/adaptive"
/usr/bin/python3 "$root/tools/cvstudy/adaptive_report.py" "$work" "$root/docs/adaptive" "$size" \
  light-switch:20 light-off:30 flicker:0 club:0 static:2
