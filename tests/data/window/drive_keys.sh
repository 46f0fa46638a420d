#!/usr/bin/env bash
# Drives globe-view's window with key presses, as a user would, under the X
# server the caller runs (xvfb-run). Usage:
#   drive_keys.sh DIR 'KEYS;KEYS;...' globe-view ARGS...
# Starts the viewer in DIR; for each ';'-separated group of xdotool key names
# it sends the keys, waits until the title reports "waiting 0" twice in a row
# (nothing loading), then presses P, so DIR gets globe-view-1.png, -2.png, ...
# Finally presses Escape; exits with the viewer's status (or 90 on a stall).
set -euo pipefail
dir=$1 phases=$2
shift 2
cd "$dir"
"$@" 2>viewer.stderr &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
wid=$(timeout 30 xdotool search --sync --onlyvisible --name '^globe-view' | head -1)
settled() {
  local calm=0
  for _ in $(seq 120); do
    sleep 0.5
    if xdotool getwindowname "$wid" | grep -q 'waiting 0\b'; then
      calm=$((calm + 1))
      [ $calm -ge 2 ] && return 0
    else
      calm=0
    fi
  done
  echo "drive_keys: the viewer never settled: $(xdotool getwindowname "$wid")" >&2
  return 1
}
n=0
IFS=';' read -r -a groups <<<"$phases"
for keys in "${groups[@]}"; do
  for k in $keys; do xdotool key --window "$wid" "$k"; done
  settled || exit 90
  n=$((n + 1))
  xdotool key --window "$wid" p
  for _ in $(seq 100); do [ -s "globe-view-$n.png" ] && break; sleep 0.1; done
  sleep 0.3
done
xdotool key --window "$wid" Escape
trap - EXIT
wait $pid
