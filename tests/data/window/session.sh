# Sourced by the window scripts (drive_keys.sh, hover_title.sh, idle_cpu.sh):
# the viewer started under the caller's X server, and waiting for it to settle.

# start_viewer DIR globe-view ARGS...: runs it in DIR (stderr to
# viewer.stderr); sets pid and wid (its window), kills it on exit.
start_viewer() {
  cd "$1"
  shift
  "$@" 2>viewer.stderr &
  pid=$!
  trap 'kill $pid 2>/dev/null || true' EXIT
  wid=$(timeout 30 xdotool search --sync --onlyvisible --name '^globe-view' | head -1)
}

# settled [CALM]: true once the title reports "waiting 0" (nothing loading)
# CALM times in a row (default 1), half a second apart; false after 60 s.
settled() {
  local calm=0 need=${1:-1}
  for _ in $(seq 120); do
    sleep 0.5
    if xdotool getwindowname "$wid" | grep -q 'waiting 0\b'; then
      calm=$((calm + 1))
      [ $calm -ge "$need" ] && return 0
    else
      calm=0
    fi
  done
  echo "the viewer never settled: $(xdotool getwindowname "$wid")" >&2
  return 1
}
