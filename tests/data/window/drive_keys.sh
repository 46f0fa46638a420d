#!/usr/bin/env bash
# Drives globe-view's window with key presses, as a user would, under the X
# server the caller runs (xvfb-run). Usage:
#   drive_keys.sh DIR 'KEYS;KEYS;...' globe-view ARGS...
# Starts the viewer in DIR; for each ';'-separated group of xdotool key names
# it sends the keys, waits until the title reports "waiting 0" twice in a row
# (nothing loading), then presses P, so DIR gets globe-view-1.png, -2.png, ...
# Finally presses Escape; exits with the viewer's status (or 90 on a stall).
# Besides key names: @move:X,Y moves the pointer to window pixel X,Y;
# @shiftwheel:up|down turns the wheel one notch with Shift held.
set -euo pipefail
dir=$1 phases=$2
shift 2
. "$(dirname "$0")/session.sh"
start_viewer "$dir" "$@"
n=0
IFS=';' read -r -a groups <<<"$phases"
for keys in "${groups[@]}"; do
  for k in $keys; do
    case $k in
      @move:*) xy=${k#@move:}; xdotool mousemove --window "$wid" "${xy%,*}" "${xy#*,}" ;;
      @shiftwheel:*)
        [ "${k#@shiftwheel:}" = up ] && b=4 || b=5
        xdotool keydown shift click "$b" keyup shift ;;
      *) xdotool key --window "$wid" "$k" ;;
    esac
  done
  settled 2 || exit 90
  n=$((n + 1))
  xdotool key --window "$wid" p
  for _ in $(seq 100); do [ -s "globe-view-$n.png" ] && break; sleep 0.1; done
  sleep 0.3
done
xdotool key --window "$wid" Escape
trap - EXIT
wait $pid
