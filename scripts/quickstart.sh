#!/usr/bin/env bash
# Builds emcv and runs its main job. Installs missing distribution packages first.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset default >/dev/null
cmake --build --preset default
build/bin/emcv-toy "$@"
