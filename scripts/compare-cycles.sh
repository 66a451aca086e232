#!/usr/bin/env bash
# Time to quality against Blender's Cycles (a benchmark, not a test; needs Debian's blender, which nothing else
# does): builds Lueur if needed and runs scripts/cycles/compare.py. Examples:
#   scripts/compare-cycles.sh cornell-original          # needs ../shared/scenes
#   scripts/compare-cycles.sh default --json default.json
#   scripts/compare-cycles.sh --help
# LUEUR_EXE=path/to/lueur measures that executable instead of building this checkout.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
if [ -z "${LUEUR_EXE:-}" ]; then
  lueur_install_packages
  lueur_build --target lueur
  LUEUR_EXE="$LUEUR_BUILD/lueur"
fi
exec python3 "$(dirname "${BASH_SOURCE[0]}")/cycles/compare.py" --lueur "$LUEUR_EXE" "$@"
