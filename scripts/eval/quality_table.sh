#!/usr/bin/env bash
# Quality-target mode after a light change: for each scene, emcv-demo renders spvg, cv and cv-notex with the
# default target (or --target-variance V from TARGET=V) against the reference, and this prints one Markdown row
# per scene and method: the mean samples per SSS pixel and the mean PSNR (dB, display image) over the 30 frames
# from the first light change and over every frame from it to the end, with cv's and cv-notex's samples as a
# ratio of spvg's. The first light change is the one emcv-demo's summary names. docs/renderer.md holds its output.
# Usage: bash scripts/eval/quality_table.sh [BUILD_DIR (default build)] [WxH (default 96x96)] [SCENE...]
#        (default: light-off and demo/scenes/variations/*.json)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
size=${2:-96x96}
shift $(( $# > 2 ? 2 : $# )) || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(light-off demo/scenes/variations/*.json)
demo="$build/bin/emcv-demo"
[ -x "$demo" ] || { echo "quality_table.sh: no $demo (build first)" >&2; exit 2; }
target=()
[ -z "${TARGET:-}" ] || target=(--target-variance "$TARGET")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | method | 30 after: spp | x spvg | dB | to the end: spp | x spvg | dB |"
echo "|---|---|---|---|---|---|---|---|"
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .json)
  dir="$out/$name"
  "$demo" --scene "$scene" --method spvg,cv,cv-notex,reference "${target[@]}" --size "$size" --out "$dir" \
    --no-frames > "$dir.summary"
  /usr/bin/python3 - "$dir/metrics.csv" "$dir.summary" "$name" <<'PY'
import csv, collections, re, sys
path, summary, scene = sys.argv[1], sys.argv[2], sys.argv[3]
found = re.search(r"from the first light change at frame (\d+)", open(summary).read())
if not found:
    sys.exit(f"quality_table.sh: {scene} has no light change")
change = int(found.group(1))
by = collections.defaultdict(list)
for r in csv.DictReader(open(path)):
    by[r["method"]].append(r)
def window(method, last):
    rs = by[method][change:last]
    return (sum(float(r["mean_spp"]) for r in rs) / len(rs), sum(float(r["psnr_db"]) for r in rs) / len(rs))
end = len(by["spvg"])
for method in ("spvg", "cv", "cv-notex"):
    n30, db30 = window(method, change + 30)
    nall, dball = window(method, end)
    s30, sall = window("spvg", change + 30)[0], window("spvg", end)[0]
    print(f"| {scene} | {method} | {n30:.2f} | {n30 / s30:.2f} | {db30:.2f} | {nall:.2f} | {nall / sall:.2f} | {dball:.2f} |")
PY
done
