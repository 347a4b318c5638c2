#!/usr/bin/env bash
# The adaptive methods' tables (docs/notebook/2026-12-07-renderer-budget-measured.md), each from emcv-demo runs
# against the reference
# (PSNR of the display image, mean over frames; the first light change is the one emcv-demo's summary names):
#   budget   for each scene and B in $BUDGETS (default 8 12 16): burley-B, spvg, cv and cv-notex, the adaptive ones
#            spending B per SSS pixel (--spp-budget B). One row per scene, B and method: PSNR before the first
#            change (from frame 2), over the 30 frames from it, over the frames after those, over every frame
#            from frame 2; mean samples per SSS pixel; the largest deviation of a frame's mean from B (frames 2
#            on); the SSS passes' time p95 over its median (frames 2 on; emcv-demo's per-pass clock, on llvmpipe a
#            measure of work that varies 20-30% from run to run).
#   quality  for each scene: spvg, cv and cv-notex under the default target (or TARGET=V). One row per scene and
#            method: samples per SSS pixel (and as a ratio of spvg's) and PSNR over the 30 frames from the first
#            change and over every frame from it to the end.
# Usage: bash scripts/eval/adaptive_tables.sh budget|quality [BUILD_DIR (default build)] [WxH (default 96x96)] [SCENE...]
#        EXTRA='--define NAME=VALUE ...' passes more emcv-demo flags to every run (a tunable's other value).
#        (SCENE: a built-in name or a scene file; default: static (budget only), light-off and
#        demo/scenes/variations/*.json)
set -euo pipefail
cd "$(dirname "$0")/../.."
table=${1:-}
case "$table" in
  budget | quality) ;;
  *) echo "usage: adaptive_tables.sh budget|quality [BUILD_DIR] [WxH] [SCENE...] (got '$table')" >&2; exit 2 ;;
esac
build=${2:-build}
size=${3:-96x96}
shift $(( $# > 3 ? 3 : $# )) || true
scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=(light-off demo/scenes/variations/*.json)
  [ "$table" = quality ] || scenes=(static "${scenes[@]}")
fi
demo="$build/bin/emcv-demo"
[ -x "$demo" ] || { echo "adaptive_tables.sh: no $demo (build first)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One emcv-demo run into $out/<name>: its metrics.csv, and its summary in <name>.summary.
render() {  # NAME SCENE ARGS...
  local name=$1 scene=$2
  shift 2
  # shellcheck disable=SC2086 # EXTRA is a list of flags
  "$demo" --scene "$scene" --size "$size" --out "$out/$name" --no-frames "$@" ${EXTRA:-} > "$out/$name.summary"
}

if [ "$table" = budget ]; then
  echo "| scene | B | method | before change dB | 30 after dB | later dB | all frames dB | mean spp | max deviation from B | SSS ms p95 / median |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for scene in "${scenes[@]}"; do
    for b in ${BUDGETS:-8 12 16}; do
      name=$(basename "$scene" .json)-$b
      render "$name" "$scene" --method "burley-$b,spvg,cv,cv-notex" --spp-budget "$b"
      /usr/bin/python3 scripts/eval/adaptive_rows.py budget "$out/$name" "$(basename "$scene" .json)" "$b"
    done
  done
else
  target=()
  [ -z "${TARGET:-}" ] || target=(--target-variance "$TARGET")
  echo "| scene | method | 30 after: spp | x spvg | dB | to the end: spp | x spvg | dB |"
  echo "|---|---|---|---|---|---|---|---|"
  for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .json)
    render "$name" "$scene" --method spvg,cv,cv-notex,reference "${target[@]}"
    /usr/bin/python3 scripts/eval/adaptive_rows.py quality "$out/$name" "$name"
  done
fi
