#!/usr/bin/env bash
# Budget mode at equal cost: for each scene and budget B, emcv-demo renders burley-B, spvg, cv and cv-notex, the
# adaptive ones spending B samples per SSS pixel (--spp-budget B), against the reference, and this prints one
# Markdown row per scene, B and method: mean PSNR (dB, display image, against the reference) over the frames
# before the first light change (from frame 2), over the 30 frames from it, over the frames after those, and over
# every frame; the mean samples per SSS pixel; the largest deviation of a frame's mean from B (frames 2 on); and
# the SSS passes' time p95 over its median (frames 2 on; emcv-demo's per-pass clock: glFinish-bracketed steady
# clock, on llvmpipe a measure of work that varies 20-30% from run to run).
# The first light change is the one emcv-demo's summary names. docs/renderer.md ("Measured") holds its output.
# Usage: bash scripts/eval/budget_table.sh [BUILD_DIR (default build)] [WxH (default 96x96)] [SCENE...]
#        (SCENE: a built-in name or a scene file; default: static light-off and demo/scenes/variations/*.json)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
size=${2:-96x96}
shift $(( $# > 2 ? 2 : $# )) || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(static light-off demo/scenes/variations/*.json)
budgets=${BUDGETS:-8 12 16}
demo="$build/bin/emcv-demo"
[ -x "$demo" ] || { echo "budget_table.sh: no $demo (build first)" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | B | method | before change dB | 30 after dB | later dB | all frames dB | mean spp | max deviation from B | SSS ms p95 / median |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  for b in $budgets; do
    dir="$out/$name-$b"
    "$demo" --scene "$scene" --method "burley-$b,spvg,cv,cv-notex" --spp-budget "$b" --size "$size" \
      --out "$dir" --no-frames > "$dir.summary"
    /usr/bin/python3 - "$dir/metrics.csv" "$dir.summary" "$name" "$b" <<'PY'
import csv, collections, re, sys
path, summary, scene, budget = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
found = re.search(r"from the first light change at frame (\d+)", open(summary).read())
change = int(found.group(1)) if found else None
by = collections.defaultdict(list)
for r in csv.DictReader(open(path)):
    by[r["method"]].append(r)
def mean(values):
    values = [v for v in values if v != float("inf")]
    return f"{sum(values) / len(values):.2f}" if values else "-"
for method, rs in by.items():
    if method == "reference":
        continue
    db = [float(r["psnr_db"]) for r in rs]
    spp = [float(r["mean_spp"]) for r in rs]
    before = mean(db[2:change] if change is not None else db[2:])
    after = mean(db[change:change + 30]) if change is not None else "-"
    later = mean(db[change + 30:]) if change is not None else "-"
    dev = max(abs(s - budget) / budget for s in spp[2:])
    ms = sorted(float(r["sss_ms"]) for r in rs[2:])
    steady = ms[int(0.95 * (len(ms) - 1))] / ms[len(ms) // 2] if ms and ms[len(ms) // 2] > 0 else float("nan")
    print(f"| {scene} | {int(budget)} | {method} | {before} | {after} | {later} | {mean(db[2:])} | "
          f"{sum(spp) / len(spp):.2f} | {100 * dev:.2f}% | {steady:.2f} |")
PY
  done
done
