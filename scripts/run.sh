#!/usr/bin/env bash
# Renders Lueur's default scene (the Cornell box with an apple) to out/lueur.png and prints the image's path.
# Extra arguments go to lueur, e.g. scripts/run.sh --lights uniform --frames 16.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages
lueur_build --target lueur
mkdir -p "$LUEUR_ROOT/out"
"$LUEUR_BUILD/lueur" --headless --out "$LUEUR_ROOT/out/lueur.png" "$@"
