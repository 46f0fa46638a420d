#!/usr/bin/env bash
# Hovers the mouse over globe-view's window, as a user would, under the X
# server the caller runs (xvfb-run), and prints the window's title once it
# names what is under it. Usage:
#   hover_title.sh [--click] DIR X Y globe-view ARGS...
# Starts the viewer in DIR, waits until nothing is loading ("waiting 0"),
# moves the pointer to window pixel (X, Y) (and clicks there with --click),
# waits until the title changes to name what is there, prints it, then
# presses Escape. Exits 90 on a stall.
set -euo pipefail
click=false
if [ "$1" = --click ]; then
  click=true
  shift
fi
dir=$1 x=$2 y=$3
shift 3
. "$(dirname "$0")/session.sh"
start_viewer "$dir" "$@"
settled || true
xdotool mousemove --window "$wid" "$x" "$y"
if $click; then
  sleep 0.3
  xdotool click 1
fi
title=""
for _ in $(seq 60); do
  sleep 0.5
  title=$(xdotool getwindowname "$wid")
  case "$title" in *": "*) break ;; esac
done
case "$title" in *": "*) ;; *) echo "hover_title.sh: no place named: $title" >&2; exit 90 ;; esac
echo "$title"
xdotool key --window "$wid" Escape
trap - EXIT
wait $pid
