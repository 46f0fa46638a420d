#!/usr/bin/env bash
# Viewer benchmark (issue 4): for fixed oblique cameras on real packages, at
# 1280x720 on whatever GL the machine has (llvmpipe here), in one run:
#   - triangles drawn / triangles of the full-resolution grid of the drawn
#     area (goal <= 0.1), at tau = 1.5 px;
#   - frame time at tau = 1.5 vs a near brute-force draw (tau = 0.01 px);
#   - time to first frame (process start to first complete frame).
# Usage: bench/viewer.sh   (needs scripts/build.sh and samples/fetch.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
view=build/viewer/globe-view
out=bench/scratch/viewer
mkdir -p "$out"
[ -f "$out/jacksboro.mbtiles" ] || $tiler terrain -q samples/data/jacksboro.tif -o "$out/jacksboro.mbtiles"
[ -f "$out/etopo20.mbtiles" ] || $tiler terrain -q --tiling geodetic samples/data/etopo20.tif -o "$out/etopo20.mbtiles"

field() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p"; }
printf "%-10s %-34s %9s %11s %7s %9s %11s %7s %9s\n" package camera triangles full_res ratio frame_ms brute_ms speedup first_ms
run_case() {
  local pkg=$1 cam=$2
  local a b
  a=$($view "$out/$pkg.mbtiles" --stats --frames 5 --size 1280x720 --camera="$cam")
  b=$($view "$out/$pkg.mbtiles" --stats --frames 3 --size 1280x720 --camera="$cam" --max-error-px 0.01)
  local tri full fa fb first
  tri=$(echo "$a" | field triangles); full=$(echo "$a" | field full_res_triangles)
  fa=$(echo "$a" | field frame_ms); fb=$(echo "$b" | field frame_ms); first=$(echo "$a" | field first_frame_ms)
  printf "%-10s %-34s %9s %11s %7.3f %9s %11s %7.1f %9s\n" "$pkg" "$cam" "$tri" "$full" \
    "$(echo "$tri / $full" | bc -l)" "$fa" "$fb" "$(echo "$fb / $fa" | bc -l)" "$first"
}
run_case jacksboro "-84.30,36.55,2500,30,65"
run_case jacksboro "-84.25,36.50,1500,0,75"
run_case jacksboro "-84.20,36.62,6000,200,45"
run_case etopo20 "10,45,400000,0,60"
run_case etopo20 "-70,-20,800000,90,70"
