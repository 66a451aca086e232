#!/usr/bin/env bash
# Display figures of the real window under Xvfb (a benchmark, not a test): the interval between displayed frames
# while the tracer works (median and worst) and about how many are displayed during one traced frame, and the
# latency from a camera change to the first displayed frame of the new view.
# Usage: scripts/bench-window.sh [WIDTHxHEIGHT] [extra lueur options]
# LUEUR_EXE=path/to/lueur measures that executable instead of building this checkout (before/after figures).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
lueur_install_packages
if [ -z "${LUEUR_EXE:-}" ]; then
  lueur_build --target lueur
  LUEUR_EXE="$LUEUR_BUILD/lueur"
fi
size="${1:-512x512}"
shift || true
state="$(mktemp -d)/state.json"
w="${size%x*}"
h="${size#*x}"
xvfb-run -a -s "-screen 0 $((w + 64))x$((h + 64))x24" bash -c '
  set -euo pipefail
  "$0" --size "$1" --state-file "$2" "${@:3}" &
  pid=$!
  trap "kill $pid 2>/dev/null" EXIT
  until [ -s "$2" ] && python3 -c "import json,sys; sys.exit(json.load(open(\"$2\"))[\"frames\"] < 2)" 2>/dev/null; do sleep 0.2; done
  win=$(xdotool search --sync --onlyvisible --name "^Lueur$" | head -1)
  sleep 2
  for i in $(seq 1 10); do   # ten camera drags in the image, right of the panel
    xdotool mousemove --window "$win" 420 300 mousedown 1 sleep 0.1 mousemove --window "$win" 430 305 sleep 0.1 mouseup 1
    sleep 1.5
  done
  python3 - "$2" <<PY
import json, sys, statistics
s = json.load(open(sys.argv[1]))
lat = s["restart_latency_ms"][-10:]
print("frame interval while tracing: median %.1f ms, worst %.1f ms (last 600 frames)" % (s["frame_interval_ms"]["median"], s["frame_interval_ms"]["worst"]))
print("camera change -> first frame of the new view: median %.1f ms, worst %.1f ms over %d drags" % (statistics.median(lat), max(lat), len(lat)))
print("tracer: last frame %.0f ms, %d frames" % (1e3 * s["last_frame_seconds"], s["frames"]))
print("frames displayed during the last traced frame: about %.0f (a display that waited for the tracer would show 1)" % (1e3 * s["last_frame_seconds"] / s["frame_interval_ms"]["median"]))
PY
' "$LUEUR_EXE" "$size" "$state" "$@"
