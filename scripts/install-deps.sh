#!/usr/bin/env bash
# Installs everything emcv needs to build, run and test, from the distribution's packages only.
# Debian 12 (bookworm) ships Catch2 2.x in main; Catch2 v3 comes from bookworm-backports, which this
# script enables on bookworm only. Re-running is fast: nothing is fetched when every package is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  catch2                                   # v3 (backports on Debian 12)
  libglm-dev libglfw3-dev                  # GLM, GLFW (window only on request)
  libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev   # headless GL (Mesa llvmpipe)
  libopenimageio-dev                       # EXR / PNG output
  fonts-dejavu-core                        # the scale text of emcv-demo's heatmap PNGs (OIIO render_text)
  nlohmann-json3-dev                       # scene files, JSON output
  libassimp-dev libmeshoptimizer-dev       # mesh files in scenes; decimating the demo assets
  libbenchmark-dev libboost-dev            # emcv-bench and the Boost.Accumulators comparison
  glslang-tools spirv-cross                # offline GLSL validation; share/emcv/emcv_port_reference.hlsl; SPIR-V to HLSL/MSL and reflection (tests)
  doxygen                                  # API reference (scripts/docs.sh, ctest -L docs)
  xvfb xauth                               # xvfb-run: the emcv-demo --window test
  python3 python3-matplotlib python3-numpy python3-pil # plots in docs/ (Pillow: palette-encoded PNGs)
  python3-jsonschema                       # tests/scene: the scene schema against the built-in scenes
  python3-dev python3-pybind11 python3-pytest   # the Python module emcv (docs/python.md) and its tests
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

catch2_v3() { dpkg-query -W -f='${Version}' catch2 2>/dev/null | grep -q '^3'; }
catch2_v3 || missing+=(catch2)

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  sudo=sudo
else
  sudo=
fi
export DEBIAN_FRONTEND=noninteractive

codename=$( . /etc/os-release && echo "${VERSION_CODENAME:-}")
catch2_from=()
if [ "$codename" = "bookworm" ]; then
  list=/etc/apt/sources.list.d/bookworm-backports.list
  if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
    # backports from the mirror that already serves bookworm main here (a local mirror or proxy included)
    source "$(dirname "$0")/debian-mirror.sh"
    mirror=$(debian_mirror_uri bookworm) || {
      echo "install-deps: cannot add bookworm-backports for Catch2 v3: no apt source serves bookworm main" >&2
      exit 1
    }
    echo "deb $mirror bookworm-backports main" | $sudo tee "$list.tmp" >/dev/null
    $sudo mv "$list.tmp" "$list"
  fi
  catch2_from=(-t bookworm-backports)
fi

echo "install-deps: installing ${missing[*]}" >&2
$sudo apt-get update -qq
# Catch2 v3 first, pinned to backports on bookworm; everything else from the main archive.
$sudo apt-get install -y -qq --no-install-recommends "${catch2_from[@]}" catch2 >/dev/null
others=()
for p in "${packages[@]}"; do [ "$p" = catch2 ] || others+=("$p"); done
$sudo apt-get install -y -qq --no-install-recommends "${others[@]}" >/dev/null
catch2_v3 || { echo "install-deps: Catch2 v3 is required but $(dpkg-query -W -f='${Version}' catch2) is installed" >&2; exit 1; }
