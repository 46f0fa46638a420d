#!/usr/bin/env bash
# globe-view as a web client (docs/viewer.md "Remote sources", issue 59): the
# time to a complete frame (a headless snapshot, 1280 x 720, that waits for
# every tile of the view) of etopo20 terrain (zooms 0-6) with Blue Marble
# imagery over the globe, from
#   - the local packages (the floor),
#   - globe-serve over loopback (its TileJSON: the packages' own tiles),
#   - a static server with 50 and 150 ms added to every answer
#     (tests/support/fault_server over a folder of the same tiles),
#   - a warm disk cache (the tiles fresh: no request at all),
# each as a ratio to the local run, with the requests and bytes the frame
# took. Goals: <= 1.5x at 50 ms, <= 1.2x from a warm cache. Fastest of RUNS.
# GLOBE_REMOTE_ARGS adds options to every globe-view run (e.g.
# "--max-connections 16"). Usage: bench/remote.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
B=${BUILD_DIR:-build}
tmp=$(mktemp -d)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null || true; rm -rf "$tmp"' EXIT
$B/tools/tiler/globe-tiler terrain -q samples/data/etopo20.tif --max-zoom 6 -o "$tmp/terrain.mbtiles"
$B/tools/tiler/globe-tiler imagery -q samples/data/bluemarble.tif --max-zoom 6 -o "$tmp/image.mbtiles"
$B/tools/tiler/globe-tiler export -q "$tmp/image.mbtiles" -o "$tmp/www/xyz"
# The terrain's own tiles in a folder with a TileJSON, for the static server.
mkdir -p "$tmp/www/terrain"
(cd "$tmp/www/terrain" && sqlite3 "$tmp/terrain.mbtiles" "select writefile(zoom_level || '/' ||
  tile_column || '/' || ((1 << zoom_level) - 1 - tile_row) || '.globe', tile_data) from tiles" >/dev/null)
python3 - "$tmp/terrain.mbtiles" "$tmp/www/terrain.json" <<'PY'
import json, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
meta = dict(db.execute("select name, value from metadata"))
zooms = [list(r) for r in db.execute(
    "select zoom_level, min(tile_column), max(tile_column), min((1 << zoom_level) - 1 - tile_row),"
    " max((1 << zoom_level) - 1 - tile_row) from tiles group by zoom_level")]
json.dump({"tilejson": "3.0.0", "tiles": [], "globe": {
    "tiles": ["terrain/{z}/{x}/{y}.globe"], "zooms": zooms, "metadata": meta}},
    open(sys.argv[2], "w"))
PY
start() {  # start NAME COMMAND...: runs it, waits for its port on stdout
  "${@:2}" >"$tmp/$1.out" 2>"$tmp/$1.err" &
  pids+=($!)
  for _ in $(seq 100); do
    grep -qo '127.0.0.1:[0-9]*' "$tmp/$1.out" 2>/dev/null && break
    sleep 0.1
  done
  grep -o '127.0.0.1:[0-9]*' "$tmp/$1.out" | head -n 1
}
serve=$(start serve $B/tools/serve/globe-serve "$tmp/terrain.mbtiles" "$tmp/image.mbtiles" --port 0 -q)
fs=$B/tests/fault_server
s50=$(start s50 $fs --root "$tmp/www" --port 0 --latency 50:50 --max-age 3600)
s150=$(start s150 $fs --root "$tmp/www" --port 0 --latency 150:150 --max-age 3600)
view=(--globe --camera 10,40,6000000,0,20 --size 1280x720 --frames 1 ${GLOBE_REMOTE_ARGS:-})
# time_of LABEL SOURCES... : the fastest wall time of RUNS snapshots (a fresh
# cache each run unless LABEL is "warm"), and the last run's --stats network.
time_of() {
  local label=$1 best=999999 t0 t1 out
  shift
  for _ in $(seq "$runs"); do
    [ "$label" = warm ] || rm -rf "$tmp/cache"
    t0=$(date +%s.%N)
    out=$($B/viewer/globe-view "$@" "${view[@]}" --cache-dir "$tmp/cache" --stats \
      --snapshot "$tmp/$label.png" 2>"$tmp/$label.err")
    t1=$(date +%s.%N)
    best=$(echo "if ($t1 - $t0 < $best) $t1 - $t0 else $best" | bc -l)
  done
  local req bytes
  req=$(echo "$out" | grep -o '"requests": [0-9]*' | awk '{print $2}')
  bytes=$(echo "$out" | grep -o '"network": {"requests": [0-9]*, "bytes": [0-9]*' |
    grep -o '[0-9]*$')
  echo "$label $best ${req:-0} ${bytes:-0}"
}
local_line=$(time_of local "$tmp/terrain.mbtiles" "$tmp/image.mbtiles")
floor=$(echo "$local_line" | awk '{print $2}')
printf "%-22s %8s %7s %9s %11s\n" source seconds ratio requests bytes
for line in "$local_line" \
  "$(time_of globe-serve "http://$serve/terrain.json" "http://$serve/image.json")" \
  "$(time_of static-50ms "http://$s50/terrain.json" "http://$s50/xyz/{z}/{x}/{y}.png" --source-zooms 0-6)" \
  "$(time_of static-150ms "http://$s150/terrain.json" "http://$s150/xyz/{z}/{x}/{y}.png" --source-zooms 0-6)"; do
  read -r label t req bytes <<<"$line"
  printf "%-22s %8.2f %7.2f %9s %11s\n" "$label" "$t" "$(echo "$t / $floor" | bc -l)" "$req" "$bytes"
done
# A warm cache: the 50 ms server's tiles are fresh for an hour.
rm -rf "$tmp/cache"
$B/viewer/globe-view "http://$s50/terrain.json" "http://$s50/xyz/{z}/{x}/{y}.png" --source-zooms 0-6 \
  "${view[@]}" --cache-dir "$tmp/cache" --snapshot "$tmp/fill.png" 2>/dev/null
read -r label t req bytes <<<"$(time_of warm "http://$s50/terrain.json" "http://$s50/xyz/{z}/{x}/{y}.png" --source-zooms 0-6)"
printf "%-22s %8.2f %7.2f %9s %11s\n" "warm cache (50 ms)" "$t" "$(echo "$t / $floor" | bc -l)" "$req" "$bytes"
for f in globe-serve static-50ms static-150ms warm; do
  cmp -s "$tmp/local.png" "$tmp/$f.png" || echo "note: $f drew another picture than the local packages"
done
