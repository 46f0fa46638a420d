#!/usr/bin/env bash
# The deferred map's per-pixel extras (issue 37): frame time at 1280x720 with
# isolines, a magic lens and a heatmap, each divided by the plain frame of
# the same view, in one run, on whatever GL the machine has (llvmpipe here),
# and the extra cost per pixel. Views: jacksboro (10 m, oblique) and etopo20
# (global, the Alps) with the world airports as places.
# Usage: bench/deferred_extras.sh   (needs scripts/build.sh and samples/fetch.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
vectorize=build/tools/vectorize/globe-vectorize
view=build/viewer/globe-view
out=bench/scratch/deferred
mkdir -p "$out"
[ -f "$out/jacksboro.mbtiles" ] || $tiler terrain -q samples/data/jacksboro.tif -o "$out/jacksboro.mbtiles"
[ -f "$out/etopo20.mbtiles" ] || $tiler terrain -q --tiling geodetic samples/data/etopo20.tif -o "$out/etopo20.mbtiles"
[ -f "$out/airports.mbtiles" ] || $vectorize points -q samples/data/world_airports.csv --xy lon,lat \
  --fields ils_runway_ends -o "$out/airports.mbtiles"

field() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p"; }
frame_ms() { $view "$@" --stats --frames 7 --size 1280x720 | field frame_ms; }
printf "%-10s %-10s %10s %10s %8s %12s\n" package extra plain_ms extra_ms ratio ns_per_px
run_case() {
  local pkg=$1 cam=$2 name=$3
  shift 3
  local plain extra
  plain=$(frame_ms "$out/$pkg.mbtiles" --camera="$cam")
  extra=$(frame_ms "$out/$pkg.mbtiles" --camera="$cam" "$@")
  printf "%-10s %-10s %10.1f %10.1f %8.2f %12.2f\n" "$pkg" "$name" "$plain" "$extra" \
    "$(echo "$extra / $plain" | bc -l)" "$(echo "($extra - $plain) * 1000000 / (1280 * 720)" | bc -l)"
}
cam_j="-84.30,36.55,2500,30,65"
cam_e="10,45,1500000,0,20"
run_case jacksboro "$cam_j" isolines --isolines 20,5
run_case jacksboro "$cam_j" lens --lens 640,360,250:slope
run_case etopo20 "$cam_e" isolines --isolines 500,4
run_case etopo20 "$cam_e" lens --lens 640,360,250:slope
run_case etopo20 "$cam_e" heatmap "$out/airports.mbtiles" --heatmap count --heatmap-radius 40px
run_case etopo20 "$cam_e" heat_150km "$out/airports.mbtiles" --heatmap count --heatmap-radius 150km
