#!/usr/bin/env bash
# Budget mode at equal cost: for each scene and budget B, emcv-demo renders burley-B, spvg, cv and cv-notex
# spending B samples per SSS pixel (--spp-budget B) against the reference, and this prints one Markdown row per
# scene, B and method: mean PSNR (dB, display image) over the static frames before the first light change, over
# the 30 frames from it, and over every frame, with the mean samples per SSS pixel and the largest deviation of a
# frame's mean from B (frames 2 on). docs/renderer.md ("Spending a budget") holds its output.
# Usage: bash scripts/eval/budget_table.sh [BUILD_DIR (default build)] [WxH (default 96x96)] [SCENE...]
set -euo pipefail
build=${1:-build}
size=${2:-96x96}
shift $(( $# > 2 ? 2 : $# )) || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(static light-off)
demo="$build/bin/emcv-demo"
[ -x "$demo" ] || { echo "budget_table.sh: no $demo (build first)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | B | method | static dB | 30 after change dB | all frames dB | mean spp | max deviation from B |"
echo "|---|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  for b in 8 12 16; do
    "$demo" --scene "$scene" --method "burley-$b,spvg,cv,cv-notex" --spp-budget "$b" --size "$size" \
      --out "$out/$scene-$b" --no-frames >/dev/null
    /usr/bin/python3 - "$out/$scene-$b/metrics.csv" "$scene" "$b" "$build" <<'PY'
import csv, collections, subprocess, sys
path, scene, budget, build = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
rows = list(csv.DictReader(open(path)))
by = collections.defaultdict(list)
for r in rows:
    by[r["method"]].append(r)
# The first light change of the built-in scenes that have one (light-off switches its key at frame 30).
change = {"light-off": 30}.get(scene)
def mean(values):
    values = [v for v in values if v != float("inf")]
    return sum(values) / len(values) if values else float("nan")
for method, rs in by.items():
    if method == "reference":
        continue
    db = [float(r["psnr_db"]) for r in rs]
    spp = [float(r["mean_spp"]) for r in rs]
    static = mean(db[2:change] if change else db[2:])
    after = f"{mean(db[change:change + 30]):.2f}" if change else "-"
    dev = max(abs(s - budget) / budget for s in spp[2:]) if method != f"burley-{int(budget)}" else 0.0
    print(f"| {scene} | {int(budget)} | {method} | {static:.2f} | {after} | {mean(db):.2f} | {mean(spp):.2f} | {100 * dev:.2f}% |")
PY
  done
done
