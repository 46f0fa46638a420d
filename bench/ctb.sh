#!/usr/bin/env bash
# DEM -> CesiumJS terrain, end to end, against cesium-terrain-builder (the tool
# people use today; bench/fetch_ctb.sh builds its quantized-mesh branch):
#   ours: `globe-tiler terrain --tiling geodetic --block-size 65` (ctb's 65-sample
#         tiles and zooms) + `globe-tiler export --format quantized-mesh --gzip`,
#         at three --finest-error settings;
#   ctb:  `ctb-tile -f Mesh -C -N` (tiles) + `ctb-tile ... -l` (layer.json), at
#         three settings (-g, the mesh quality factor; -r, the warp's resampling).
# Both read the same DEM: a global 5' relief grid (bench/make_global.sh --relief)
# cropped to its pixels inside +-180 / +-90 (ctb makes a wrong extra column and row
# of tiles for a grid whose edge lies on or past the antimeridian or a pole:
# bench/ctb/NOTES.md). Per setting: wall and CPU seconds (fastest of 3, by CPU), peak
# RSS, tiles, bytes (gzipped tiles) and accuracy from bench/terrain_accuracy.py (written
# apart from both tools): p99 / max height error of the finest zoom against a bilinear
# brute force of the source at 4,000 points, cracks between neighbours, zero-area
# triangles.
# Usage: bench/ctb.sh   Needs scripts/build.sh. Scratch: bench/scratch/ctb-vs.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
scratch=bench/scratch/ctb-vs
mkdir -p "$scratch"
source bench/timing.sh
ctb=$(bench/fetch_ctb.sh)
threads=$(nproc)
echo "bench/ctb.sh: $threads threads, $("$ctb" --version 2>&1 | head -1)"

relief=bench/scratch/big/global5r.tif
[ -f "$relief" ] || { mkdir -p bench/scratch/big && bench/make_global.sh --relief "$relief"; }
src="$scratch/global5r_inside.tif"
[ -f "$src" ] || gdal_translate -q -srcwin 1 1 4319 2159 -co TILED=YES -co COMPRESS=DEFLATE \
  "$relief" "$src"

accuracy() { # DIR -> "p99 max cracks zero_area"
  python3 bench/terrain_accuracy.py "$src" "$1" --json | python3 -c '
import json, sys
r = json.load(sys.stdin)
e, c, t = r["error"], r["cracks"], r["triangles"]
print(e["p99_abs"], e["max_abs"], c["cracked_vertices"], t["degenerate"])'
}
report() { # NAME "wall rss cpu" DIR
  local tiles bytes
  tiles=$(find "$3" -name '*.terrain' | wc -l)
  bytes=$(find "$3" -name '*.terrain' -printf '%s\n' | awk '{ s += $1 } END { print s }')
  echo "$2 $tiles $bytes $(accuracy "$3")" | awk -v n="$1" '{
    printf "  %-34s wall %6.2f s, CPU %6.2f s, %4.0f MB RSS, %6d tiles, %10d bytes, p99 %7.1f m, max %7.1f m, cracks %s, zero-area %s\n",
      n, $1, $3, $2 / 1024, $4, $5, $6, $7, $8, $9 }'
}
add() { # "w r c" "w r c" -> sums of wall and CPU, max of rss
  echo "$1 $2" | awk '{ print $1 + $4, ($2 > $5 ? $2 : $5), $3 + $6 }'
}

pkg="$scratch/ours.mbtiles"
build=$(best $T terrain -q --force -j "$threads" --tiling geodetic --block-size 65 "$src" -o "$pkg")
echo "ours: terrain build $(echo "$build" | awk '{ printf "wall %.2f s, CPU %.2f s, %.0f MB RSS", $1, $3, $2 / 1024 }')"
for finest in 2 30 300; do
  out="$scratch/ours-$finest"
  export=$(best $T export -q --force -j "$threads" "$pkg" --format quantized-mesh --gzip \
    --finest-error "$finest" -o "$out")
  report "ours --finest-error $finest" "$(add "$build" "$export")" "$out"
done

for setting in "-g 1 -r average" "-g 0.1 -r bilinear" "-g 0.01 -r bilinear"; do
  out="$scratch/ctb${setting// /}"
  rm -rf "$out" && mkdir -p "$out"
  # shellcheck disable=SC2086 # the setting is several options
  tiles=$(best "$ctb" -q -f Mesh -C -N -c "$threads" $setting -o "$out" "$src")
  # shellcheck disable=SC2086
  layer=$(best "$ctb" -q -f Mesh -C -N -l -c "$threads" $setting -o "$out" "$src")
  report "ctb $setting" "$(add "$tiles" "$layer")" "$out"
done
