#!/usr/bin/env bash
# The GPU runs behind docs/results.md, section "GPU": run on the machine with the GPU, then turn the output into
# the tables there with scripts/eval/gpu_report.py (which also judges issue 18's GPU targets from them).
#   bash scripts/eval/gpu_runs.sh [--smoke] OUT_DIR [BIN_DIR]
# BIN_DIR (default build/bin) holds emcv-glinfo, emcv-demo and emcv-eval; a build configured with
# -DEMCV_GL_IMAGE_FILES=OFF is enough (no OpenImageIO on the GPU machine: emcv-demo --no-frames writes metrics only).
#  1. the paper's teaser on light-off at 1920x1080 and 3360x1440: emcv-demo (PSNR against the converged reference,
#     per frame) and emcv-eval three times (SSS pass ms per frame, medians over frames and runs);
#  2. how the cost grows with resolution: emcv-eval from 128x128 to 3840x2160;
#  3. the SSS passes at equal samples (scripts/eval/sss_cost.py, builds of BIN_DIR/.., each run's CSV kept in
#     cost-*/): burley-B against spvg, cv and cv-notex under --spp-budget 8 and 16 at 1920x1080 with GPU
#     timestamps, the same under the wall clock (what glFinish at every pass boundary adds), and quality-target
#     mode's 30 frames after the switch; then the GPU's clocks (nvidia-smi, where present).
# steps.txt records each step's seconds, so that the next device session knows what the script costs.
# Times use emcv-eval's default clock: GPU timestamps on a hardware renderer (--timing auto).
# --smoke runs every step at 48x48, one run each, over the frames up to 3 after the switch (frame 30)
# (tests/eval/test_gpu_runs_smoke.py runs it on llvmpipe): the same commands and files, so that the script is known
# to run before a GPU session spends its device time on it.
set -euo pipefail
smoke=0
if [ "${1:-}" = --smoke ]; then smoke=1; shift; fi
[ $# -ge 1 ] && [ $# -le 2 ] || { echo "usage: gpu_runs.sh [--smoke] OUT_DIR [BIN_DIR]" >&2; exit 2; }
out=$(realpath -m "$1")
bin=$(realpath -m "${2:-build/bin}")
for exe in emcv-glinfo emcv-demo emcv-eval; do
  [ -x "$bin/$exe" ] || { echo "gpu_runs.sh: $bin/$exe not found" >&2; exit 2; }
done
if [ "$smoke" = 1 ]; then
  teaser_sizes=(48x48); scaling_sizes=(32x32 48x48); cost_size=48x48; runs=1
  frames=34; last=33; scaling_frames=4
else
  teaser_sizes=(1920x1080 3360x1440)
  scaling_sizes=(128x128 256x256 640x360 1280x720 1920x1080 2560x1440 3360x1440 3840x2160)
  cost_size=1920x1080; runs=3
  frames=60; last=59; scaling_frames=40  # light-off's 60 frames: the 30 from the switch are frames 30-59
fi
cd "$(dirname "$0")/../.."
mkdir -p "$out"
: > "$out/steps.txt"
step_start=$SECONDS
step() { echo "$1 $((SECONDS - step_start))" >> "$out/steps.txt"; step_start=$SECONDS; }
# The commit the runs are made at, for gpu_report.py's provenance line: git's where the tree is a checkout, else
# EMCV_COMMIT (set it when the tree was copied without .git, as onto a lent GPU machine).
git describe --always --dirty 2>/dev/null > "$out/commit.txt" || echo "${EMCV_COMMIT:-unknown}" > "$out/commit.txt"
"$bin/emcv-glinfo" > "$out/glinfo.txt"
teaser_methods=diffuse,separable-17,burley-16,spvg,cv,cv-notex
for size in "${teaser_sizes[@]}"; do
  "$bin/emcv-demo" --scene light-off --method "$teaser_methods" --size "$size" --frames "$frames" --no-frames \
    --out "$out/demo-$size" > "$out/demo-$size.txt"
  for run in $(seq "$runs"); do
    "$bin/emcv-eval" --scene light-off --method "$teaser_methods" --size "$size" --frames "$frames" \
      > "$out/eval-$size-run$run.csv"
  done
  step "teaser-$size"
done
for size in "${scaling_sizes[@]}"; do
  "$bin/emcv-eval" --scene light-off --method burley-16,separable-17,spvg,cv,cv-notex --size "$size" \
    --frames "$scaling_frames" > "$out/scaling-$size.csv"
done
step scaling
python=$(command -v /usr/bin/python3 || command -v python3 || true)
if [ -n "$python" ]; then
  build=$(realpath --relative-to=. "$(dirname "$bin")")  # the tables' build column: a path within the tree
  for budget in 8 16; do
    for clock in gpu wall; do
      "$python" scripts/eval/sss_cost.py --build "$build" --runs "$runs" --size "$cost_size" --frames "$frames" \
        --spp-budget "$budget" --timing "$clock" --save-raw "$out/cost-budget$budget-$clock" \
        > "$out/cost-budget$budget-$clock.md"
      step "cost-budget$budget-$clock"
    done
  done
  "$python" scripts/eval/sss_cost.py --build "$build" --runs "$runs" --size "$cost_size" --frames "$frames" \
    --first 30 --last "$last" --target-variance 0.0001 --methods spvg,cv,cv-notex,burley-8 --timing gpu \
    --save-raw "$out/cost-quality-gpu" > "$out/cost-quality-gpu.md"
  step cost-quality-gpu
  # The statistics' grain (EMCV_HISTORY_BLOCK, docs/renderer.md "Block statistics") at equal samples, GPU clock.
  "$python" scripts/eval/sss_cost.py --build "$build" --runs "$runs" --size "$cost_size" --frames "$frames" \
    --spp-budget 8 --timing gpu --variant "K1=EMCV_HISTORY_BLOCK=1" --variant "K2=EMCV_HISTORY_BLOCK=2" \
    --variant "K4=EMCV_HISTORY_BLOCK=4" --save-raw "$out/cost-blocks-gpu" > "$out/cost-blocks-gpu.md"
  step cost-blocks-gpu
else
  echo "gpu_runs.sh: no python3, the equal-samples cost tables are skipped" >&2
fi
# Equal time: the adaptive methods against burley-N at their own SSS time (the summary's last lines, PSNR
# interpolated in log time between the burley runs that bracket it), budget 8.
"$bin/emcv-demo" --scene light-off --method spvg,cv,cv-notex,burley-8,burley-16,burley-32,burley-64 --spp-budget 8 \
  --size "$cost_size" --frames "$frames" --no-frames --out "$out/equal-time" > "$out/equal-time.txt"
step equal-time
if command -v nvidia-smi >/dev/null 2>&1; then nvidia-smi -q -d CLOCK,PERFORMANCE > "$out/clocks.txt" || true; fi
echo "gpu_runs.sh: wrote $out"
