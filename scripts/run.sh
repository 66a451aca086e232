#!/usr/bin/env bash
# Opens Lueur's window on the default scene (the Cornell box with an apple). With no display, renders a headless
# screenshot through the same display shaders (EGL, else OSMesa) to out/lueur.png and prints its path.
# Extra arguments go to lueur, e.g. scripts/run.sh --lights uniform, or scripts/run.sh path/to/scene.obj.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages
lueur_build --target lueur
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  if "$LUEUR_BUILD/lueur" "$@"; then exit 0; fi
  echo "lueur: the window could not run here; rendering a headless screenshot instead" >&2
fi
mkdir -p "$LUEUR_ROOT/out"
"$LUEUR_BUILD/lueur" --headless --gl auto --out "$LUEUR_ROOT/out/lueur.png" "$@"
