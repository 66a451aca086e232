#!/usr/bin/env bash
# The README's two commands, in order, as a new user runs them: scripts/run.sh (with no display it must write a
# headless screenshot and print its path), then scripts/test.sh. Names the command that failed and its status.
# .ci/run starts this inside a brand-new Debian 12 root (../shared/tools/fresh-debian.sh), or on the host.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

fail() {  # command status
  echo "ci: FAILED: '$1' exited with status $2" >&2
  exit "$2"
}

start=$SECONDS
echo "ci: running scripts/run.sh" >&2
screenshot=$(scripts/run.sh | tail -n 1)
status=$?  # pipefail: run.sh's own status
[ "$status" -eq 0 ] || fail scripts/run.sh "$status"
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
  echo "ci: scripts/run.sh passed in $((SECONDS - start)) s (a display is set: it opened the window)" >&2
else
  # With no display the last line on stdout is the screenshot's path; it must be a PNG file.
  [ "$(head -c 8 "$screenshot" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] ||
    { echo "ci: scripts/run.sh printed '$screenshot', which is not a PNG file" >&2; fail scripts/run.sh 1; }
  echo "ci: scripts/run.sh passed in $((SECONDS - start)) s and wrote $screenshot" >&2
fi

start=$SECONDS
echo "ci: running scripts/test.sh" >&2
scripts/test.sh
status=$?
[ "$status" -eq 0 ] || fail scripts/test.sh "$status"
echo "ci: scripts/test.sh passed in $((SECONDS - start)) s" >&2
