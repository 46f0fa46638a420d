#!/usr/bin/env bash
# Measures the CPU an idle globe-view window uses, under the X server the
# caller runs (xvfb-run). Usage:
#   idle_cpu.sh DIR SECONDS globe-view ARGS...
# Starts the viewer in DIR, waits until nothing is loading ("waiting 0" in
# the title), then reads the viewer's user+system CPU time (/proc) before and
# after SECONDS without any input, moves the pointer over the window and
# checks that the title is refreshed (it still draws when asked), and prints
# "cpu_seconds C wall_seconds S". Presses Escape; exits 90 on a stall.
set -euo pipefail
dir=$1 seconds=$2
shift 2
. "$(dirname "$0")/session.sh"
start_viewer "$dir" "$@"
settled || exit 90
sleep 1  # the last frames after loading
ticks() { awk '{print $14 + $15}' "/proc/$pid/stat"; }
hz=$(getconf CLK_TCK)
t0=$(ticks)
sleep "$seconds"
t1=$(ticks)
echo "cpu_seconds $(awk -v a="$t0" -v b="$t1" -v hz="$hz" 'BEGIN { print (b - a) / hz }') wall_seconds $seconds"
# Still drawn on demand: a key press redraws and a screenshot is written.
xdotool key --window "$wid" p
for _ in $(seq 100); do [ -s globe-view-1.png ] && break; sleep 0.1; done
[ -s globe-view-1.png ] || { echo "idle_cpu: no screenshot after P" >&2; exit 91; }
xdotool key --window "$wid" Escape
trap - EXIT
wait $pid
