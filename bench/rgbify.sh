#!/usr/bin/env bash
# DEM -> Terrain-RGB tiles for MapLibre, end to end, against rio-rgbify (mapbox's tool;
# bench/fetch_rio_rgbify.sh runs it with Debian's rasterio):
#   ours: `globe-tiler terrain --tiling webmercator` + `globe-tiler export --format
#         terrain-rgb` (256-pixel tiles), into MBTiles as rio-rgbify writes;
#   rio-rgbify: `rio rgbify -b -10000 -i 0.1 --format png -j THREADS` (512-pixel tiles
#         only), zooms 0..(ours - 1): the same finest pixels.
# Same DEM for both: a 2048^2 synthetic relief (10 m, UTM; bench/make_synthetic_dem).
# Per tool: wall and CPU seconds (fastest of 3 by CPU; rio-rgbify's pool workers are
# counted, it waits for them), peak RSS of the largest process, tiles, bytes, and
# accuracy from bench/terrain_accuracy.py (written apart from both tools): p50 / p99
# / max height error of the finest zoom's pixels against a bilinear brute force of the
# source at their centres.
# Usage: bench/rgbify.sh   Needs scripts/build.sh. Scratch: bench/scratch/rgbify.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
scratch=bench/scratch/rgbify
mkdir -p "$scratch"
source bench/timing.sh
rio=$(bench/fetch_rio_rgbify.sh)
threads=$(nproc)
echo "bench/rgbify.sh: $threads threads"

src="$scratch/synthetic-2048.tif"
[ -f "$src" ] || $B/bench/make_synthetic_dem 2048 "$src" >/dev/null

accuracy() { # TILESET -> "p50 p99 max"
  python3 bench/terrain_accuracy.py "$src" "$1" --format terrain-rgb --json | python3 -c '
import json, sys
e = json.load(sys.stdin)["error"]
print(e["p50_abs"], e["p99_abs"], e["max_abs"])'
}
report() { # NAME "wall rss cpu" MBTILES
  local tiles
  tiles=$(sqlite3 "$3" 'SELECT COUNT(*) FROM tiles')
  echo "$2 $tiles $(stat -c %s "$3") $(accuracy "$3")" | awk -v n="$1" '{
    printf "  %-12s wall %6.2f s, CPU %6.2f s, %4.0f MB RSS, %5d tiles, %10d bytes, error p50 %.3f m, p99 %.3f m, max %.3f m\n",
      n, $1, $3, $2 / 1024, $4, $5, $6, $7, $8 }'
}

pkg="$scratch/ours-terrain.mbtiles"
ours="$scratch/ours.mbtiles"
build=$(best $T terrain -q --force -j "$threads" --tiling webmercator "$src" -o "$pkg")
export=$(best $T export -q --force -j "$threads" "$pkg" --format terrain-rgb -o "$ours")
total=$(echo "$build $export" | awk '{ print $1 + $4, ($2 > $5 ? $2 : $5), $3 + $6 }')
max_zoom=$(sqlite3 "$ours" 'SELECT MAX(zoom_level) FROM tiles')
report "ours" "$total" "$ours"
echo "$build $export" | awk '{ printf "    (terrain build CPU %.2f s + export CPU %.2f s)\n", $3, $6 }'

theirs="$scratch/rio-rgbify.mbtiles"
# A fresh file each run (rio-rgbify adds to an existing one); its per-tile warnings
# (NotGeoreferencedWarning) dropped.
rio_run="rm -f '$theirs' && '$rio' -b -10000 -i 0.1 --min-z 0 --max-z $((max_zoom - 1)) \
  -j $threads --format png '$src' '$theirs' 2>/dev/null"
rio_usage=$(best bash -c "$rio_run")
report "rio-rgbify" "$rio_usage" "$theirs"
echo "$total $rio_usage" | awk '{ printf "ours / rio-rgbify: CPU %.3fx, wall %.3fx\n", $3 / $6, $1 / $4 }'
