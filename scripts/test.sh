#!/usr/bin/env bash
# Builds Lueur and runs every test (CTest over the GoogleTest suites).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages
lueur_build
cd "$LUEUR_BUILD"
ctest --output-on-failure -j "$(nproc)" "$@"
