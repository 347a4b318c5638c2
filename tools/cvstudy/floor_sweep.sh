#!/usr/bin/env bash
# docs/renderer.md, "The light-switch targets": cv's count floor (the n_min of emcv_history_count_residual,
# SPVG's 8 in the shipped rule) swept without rebuilding: the shaders include the port at run time, and
# EMCV_INCLUDE_DIR points them at a copy of include/ with the floor edited. For each floor it prints, on
# light-off, the summary's cv vs spvg line over the 30 frames from the switch, and on static, cv's mean N and
# PSNR against spvg's over frames 2 to the end (the issue's 10% / 0.5 dB bounds).
# Usage: bash tools/cvstudy/floor_sweep.sh [BUILD_DIR (default build)] [WxH (default 128x96)] [FLOOR...]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build}"
size="${2:-128x96}"
shift $(( $# < 2 ? $# : 2 ))
floors=(8 10 12)
[ $# -gt 0 ] && floors=("$@")
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for floor in "${floors[@]}"; do
  rm -rf "$work/include" "$work/out"
  cp -r "$root/include" "$work/include"
  sed -i "s/(residual_variance, EMCV_HISTORY_TARGET, EMCV_HISTORY_SPVG_N_MIN,/(residual_variance, EMCV_HISTORY_TARGET, $floor,/" \
    "$work/include/emcv/port/history.h"
  # Only the residual rule (cv, cv-notex) changes; SPVG's own count keeps its floor of 8.
  [ "$(grep -c "EMCV_HISTORY_TARGET, $floor, EMCV_HISTORY_N_MAX" "$work/include/emcv/port/history.h")" = 1 ] || {
    echo "floor_sweep.sh: could not edit the residual rule's floor in include/emcv/port/history.h" >&2; exit 1; }
  echo "floor $floor:"
  EMCV_INCLUDE_DIR="$work/include" LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/emcv-demo" --scene light-off \
    --method spvg,cv --size "$size" --seed 1 | grep '^cv vs spvg' | sed 's/^/  light-off: /'
  EMCV_INCLUDE_DIR="$work/include" LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/emcv-demo" --scene static \
    --method spvg,cv --size "$size" --seed 1 --out "$work/out" > /dev/null
  /usr/bin/python3 - "$work/out/metrics.csv" <<'PY'
import csv, sys
rows = {}
for r in csv.DictReader(open(sys.argv[1])):
    if int(r["frame"]) >= 2:
        rows.setdefault(r["method"], []).append(r)
mean = lambda m, k: sum(float(r[k]) for r in rows[m]) / len(rows[m])
n, db = mean("cv", "mean_spp") / mean("spvg", "mean_spp"), mean("cv", "psnr_db") - mean("spvg", "psnr_db")
print(f"  static, frames 2-{len(rows['cv']) + 1}: cv's mean N {n:.3f}x spvg's, PSNR {db:+.2f} dB")
PY
done
