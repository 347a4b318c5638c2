#!/usr/bin/env bash
# emcv-port.pc adds GLM to emcv's flags for the port's C++ side: with the system's glm.pc, a translation unit
# of the per-frame API compiles from pkg-config's flags alone; without any system .pc file pkg-config refuses
# emcv-port, naming glm (while emcv.pc alone needs nothing: the pkg_config consumer).
# Usage: check_pkg_config_port.sh PKGCONFIG_DIR CXX WORK_DIR
set -euo pipefail
pc_dir=$1 cxx=$2 work=$3
mkdir -p "$work"
flags=$(PKG_CONFIG_PATH="$pc_dir" pkg-config --cflags emcv-port)
cat > "$work/port_consumer.cpp" <<'CPP'
#include <emcv/adaptive_sampling.hpp>
int main() { emcv::sampling_params p; return p.n_min > 0 ? 0 : 1; }
CPP
# shellcheck disable=SC2086
"$cxx" -std=c++17 -Wall -Wextra -Werror -fsyntax-only $flags "$work/port_consumer.cpp"
if PKG_CONFIG_LIBDIR="$pc_dir" pkg-config --cflags emcv-port 2> "$work/port.err"; then
  echo "emcv-port resolved without glm.pc" >&2
  exit 1
fi
grep -q glm "$work/port.err" || { cat "$work/port.err" >&2; exit 1; }
echo "port: OK"
