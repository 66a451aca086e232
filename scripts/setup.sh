#!/usr/bin/env bash
# Shared by scripts/run.sh and scripts/test.sh: installs the Debian 12 packages Lueur needs (only the missing ones),
# configures and builds. Quick when everything is already there.
set -euo pipefail

LUEUR_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LUEUR_BUILD="${LUEUR_BUILD:-$LUEUR_ROOT/build}"

LUEUR_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libtinyobjloader-dev libstb-dev libtinyexr-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libembree-dev
  libopenmpi-dev openmpi-bin  # lueur-mpi: batch renders across the ranks of an MPI job
  libglfw3-dev libimgui-dev libgl-dev libopengl-dev libegl-dev libosmesa6-dev libegl-mesa0 libgl1-mesa-dri libglx-mesa0
  xvfb xauth xdotool
  clang libclang-rt-14-dev  # sanitizer and fuzzing builds: scripts/sanitize.sh, scripts/fuzz.sh
)

lueur_install_packages() {
  local missing=()
  for p in "${LUEUR_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "lueur: installing Debian packages: ${missing[*]}" >&2
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

lueur_build() {
  if [ ! -f "$LUEUR_BUILD/build.ninja" ]; then
    cmake -S "$LUEUR_ROOT" -B "$LUEUR_BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >&2
  fi
  cmake --build "$LUEUR_BUILD" "$@" >&2
}
