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
cd "$dir"
"$@" 2>viewer.stderr &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
wid=$(timeout 30 xdotool search --sync --onlyvisible --name '^globe-view' | head -1)
settled=false
for _ in $(seq 120); do
  sleep 0.5
  if xdotool getwindowname "$wid" | grep -q 'waiting 0\b'; then
    settled=true
    break
  fi
done
$settled || { echo "idle_cpu: the viewer never settled" >&2; exit 90; }
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
