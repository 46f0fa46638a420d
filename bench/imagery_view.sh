#!/usr/bin/env bash
# Imagery draping cost in the viewer (issue 17): frame time with one and
# with three image layers ÷ the same view of the terrain alone, 1280x720,
# oblique cameras, on whatever GL the machine has (llvmpipe here). Each
# configuration runs BENCH_RUNS times (default 3), interleaved; the fastest
# counts. Goals: <= 1.3 (one layer) and <= 1.6 (three).
# Usage: bench/imagery_view.sh   (needs scripts/build.sh and samples/fetch.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
view=build/viewer/globe-view
out=bench/scratch/imagery_view
runs=${BENCH_RUNS:-3}
mkdir -p "$out"
make() { [ -f "$out/$1.mbtiles" ] || $tiler "${@:2}" -q -o "$out/$1.mbtiles"; }
make olinda terrain samples/data/olinda.tif
make l321 imagery samples/data/landsat.tif --bands 3,2,1
make l432 imagery samples/data/landsat.tif --bands 4,3,2
make l543 imagery samples/data/landsat.tif --bands 5,4,3
make etopo20 terrain samples/data/etopo20.tif --tiling geodetic
make bm_merc imagery samples/data/bluemarble.tif
make bm_geo imagery samples/data/bluemarble.tif --tiling geodetic
make bm_merc2 imagery samples/data/bluemarble.tif --max-zoom 3 --format jpg

frame_ms() {  # fastest frame_ms over $runs runs
  local best=1e30 v
  for _ in $(seq "$runs"); do
    v=$($view "$@" --stats --frames 5 --size 1280x720 | sed -n 's/.*"frame_ms": \([0-9.]*\).*/\1/p')
    best=$(awk -v a="$v" -v b="$best" 'BEGIN { print (a + 0 < b + 0) ? a : b }')
  done
  echo "$best"
}
printf "%-9s %-32s %10s %10s %10s %7s %7s\n" terrain camera alone_ms one_ms three_ms one three
run_case() {
  local terrain=$1 cam=$2 one=$3 two=$4 three=$5
  local a b c
  a=$(frame_ms "$out/$terrain.mbtiles" --camera="$cam")
  b=$(frame_ms "$out/$terrain.mbtiles" "$out/$one.mbtiles" --camera="$cam")
  c=$(frame_ms "$out/$terrain.mbtiles" "$out/$one.mbtiles" "$out/$two.mbtiles" \
    "$out/$three.mbtiles" --image-opacity 1,0.5,0.3 --camera="$cam")
  printf "%-9s %-32s %10.1f %10.1f %10.1f %7.2f %7.2f\n" "$terrain" "$cam" "$a" "$b" "$c" \
    "$(echo "$b / $a" | bc -l)" "$(echo "$c / $a" | bc -l)"
}
run_case olinda "-34.88,-8.07,2500,20,70" l321 l432 l543
run_case olinda "-34.85,-7.95,1500,180,60" l321 l432 l543
run_case etopo20 "10,45,400000,0,60" bm_merc bm_geo bm_merc2
run_case etopo20 "-70,-20,800000,90,70" bm_merc bm_geo bm_merc2
