#!/usr/bin/env bash
# Builds emcv and runs its main job: the SSS demo renders the paper's teaser scene (light-off: the key light
# switches off mid-sequence) headless with every implemented method, writes the frames and per-frame metrics
# under build/quickstart/ and prints the summary table. The adaptive methods spend a budget of 8 samples per SSS
# pixel and frame, compared on the summary's last lines with burley-8 at equal samples, then with the burley-N
# runs at each adaptive method's own SSS time (burley-16, -32 and -64 bracket it). Installs missing distribution
# packages first.
# Extra arguments go to emcv-demo (later flags win), e.g. `bash scripts/quickstart.sh --size 128x128`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset default >/dev/null
cmake --build --preset default
build/bin/emcv-demo --scene light-off --method all,burley-8,burley-32,burley-64 --spp-budget 8 --size 256x256 --out build/quickstart "$@"
