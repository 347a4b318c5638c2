#!/usr/bin/env bash
# docs/renderer.md, "The light-switch targets": one knob of cv's count rule swept without rebuilding. The shaders
# include the port at run time, and emcv-demo --define sets the port's tunable (include/emcv/port/history.h):
#   floor   the residual rule's floor (EMCV_HISTORY_RESIDUAL_N_MIN: cv and cv-notex, everywhere; SPVG keeps 8)
#   settle  cv's settling floor after a light change (EMCV_HISTORY_CV_SETTLE_N; 8 = no settling, the paper's rule)
# For each value it prints, on light-off, the summary's cv vs spvg line over the 30 frames from the switch; on
# flicker and club, cv's mean N and PSNR against spvg's over the whole sequence; on static, the same over frames
# 2 to the end (the issue's 10% / 0.5 dB bounds). Seed 1, llvmpipe.
# Usage: bash tools/cvstudy/count_sweep.sh floor|settle [BUILD_DIR (default build)] [WxH (default 128x96)] [VALUE...]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
knob="${1:-}"
case "$knob" in
  floor | settle) ;;
  *) echo "usage: count_sweep.sh floor|settle [BUILD_DIR] [WxH] [VALUE...] (got knob '$knob')" >&2; exit 2 ;;
esac
build="${2:-$root/build}"
size="${3:-128x96}"
shift $(( $# < 3 ? $# : 3 ))
values=(8 10 12)
[ $# -gt 0 ] && values=("$@")
for v in "${values[@]}"; do
  [[ "$v" =~ ^[0-9]+$ ]] && [ "$v" -le 64 ] || { echo "count_sweep.sh: '$v' is not a count in 0..64" >&2; exit 2; }
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
compare() {  # metrics.csv, first frame, label
  /usr/bin/python3 - "$@" <<'PY'
import csv, sys
path, first, label = sys.argv[1], int(sys.argv[2]), sys.argv[3]
rows = {}
for r in csv.DictReader(open(path)):
    if int(r["frame"]) >= first:
        rows.setdefault(r["method"], []).append(r)
mean = lambda m, k: sum(float(r[k]) for r in rows[m]) / len(rows[m])
n, db = mean("cv", "mean_spp") / mean("spvg", "mean_spp"), mean("cv", "psnr_db") - mean("spvg", "psnr_db")
last = first + len(rows["cv"]) - 1
print(f"  {label}, frames {first}-{last}: cv's mean N {n:.3f}x spvg's, PSNR {db:+.2f} dB")
PY
}
for v in "${values[@]}"; do
  rm -rf "$work/out"
  if [ "$knob" = floor ]; then define="EMCV_HISTORY_RESIDUAL_N_MIN=$v"; else define="EMCV_HISTORY_CV_SETTLE_N=$v"; fi
  echo "$knob $v:"
  run() { LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/emcv-demo" --method spvg,cv --define "$define" \
            --size "$size" --seed 1 "$@"; }
  run --scene light-off | grep '^cv vs spvg' | sed 's/^/  light-off: /'
  for scene in flicker club; do
    run --scene "$scene" --no-frames --out "$work/out/$scene" > /dev/null
    compare "$work/out/$scene/metrics.csv" 0 "$scene"
  done
  run --scene static --no-frames --out "$work/out/static" > /dev/null
  compare "$work/out/static/metrics.csv" 2 static
done
