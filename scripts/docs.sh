#!/usr/bin/env bash
# Generates the API reference with Doxygen (docs/Doxyfile): scripts/docs.sh [output dir, default build/docs].
# Any Doxygen warning is an error (WARN_AS_ERROR = YES): the command exits non-zero and names the line.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v doxygen >/dev/null || { echo "docs.sh: doxygen not found (scripts/install-deps.sh installs it)" >&2; exit 1; }
out="${1:-build/docs}"
mkdir -p "$out"
EMCV_DOXYGEN_OUTPUT="$(cd "$out" && pwd)" doxygen docs/Doxyfile
echo "docs.sh: $out/html/index.html"
