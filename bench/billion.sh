#!/usr/bin/env bash
# A billion pixels on one machine (bench/README.md "A billion pixels"): a 32768^2
# synthetic relief (1.07 Gpx, tiled DEFLATE Int16 GeoTIFF from
# bench/make_synthetic_dem) and an 8192^2 one (67 Mpx) through `terrain`,
# `analyze` (slope, aspect) and every terrain export (quantized-mesh gzipped into a
# folder, Terrarium and Terrain-RGB into PMTiles), one run each (each takes minutes):
# wall and CPU seconds, peak RSS, and the time per pixel of the large run over
# the small one's. docs/scale-out.md plans a planet from these per-core rates.
# Usage: bench/billion.sh [SMALL LARGE]   (sizes; default 8192 32768)
# Needs scripts/build.sh. Scratch: bench/scratch/big (about 2.5 GB for the defaults).
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
scratch=bench/scratch/big
mkdir -p "$scratch"
source bench/timing.sh
small=${1:-8192} large=${2:-32768}
echo "bench/billion.sh: $(nproc) threads, $small^2 and $large^2"

declare -A seconds
step() { # SIZE NAME CMD... -> prints one row, remembers the wall time
  local size=$1 name=$2 r
  shift 2
  r=$(usage "$@")
  seconds[$size.$name]=$(echo "$r" | cut -d' ' -f1)
  echo "$r" | awk -v n="$name" -v s="$size" '{ px = s * s;
    printf "  %-22s wall %8.1f s, CPU %8.1f s, %5.0f MB RSS, %6.2f ns CPU / pixel\n", n, $1, $3, $2 / 1024, $3 / px * 1e9 }'
}
for size in $small $large; do
  dem="$scratch/syn$size.tif"
  [ -f "$dem" ] || $B/bench/make_synthetic_dem "$size" "$dem" >/dev/null
  pkg="$scratch/syn$size.mbtiles"
  echo "$size^2 ($(awk -v s="$size" 'BEGIN { printf "%.0f Mpx", s * s / 1e6 }'), $(stat -L -c %s "$dem") bytes of GeoTIFF):"
  step "$size" terrain $T terrain -q --force --tiling webmercator "$dem" -o "$pkg"
  echo "    package $(stat -c %s "$pkg") bytes"
  step "$size" analyze $T analyze -q --force "$pkg" -o "$scratch/syn$size-analysis.mbtiles"
  step "$size" quantized-mesh $T export -q --force "$pkg" --format quantized-mesh --gzip \
    -o "$scratch/syn$size-qm"
  step "$size" terrarium $T export -q --force "$pkg" --format terrarium -o "$scratch/syn$size.pmtiles"
  step "$size" terrain-rgb $T export -q --force "$pkg" --format terrain-rgb \
    -o "$scratch/syn$size-rgb.pmtiles"
done
echo "time per pixel, $large^2 over $small^2:"
for name in terrain analyze quantized-mesh terrarium terrain-rgb; do
  awk -v n="$name" -v a="${seconds[$small.$name]}" -v b="${seconds[$large.$name]}" \
    -v s="$small" -v l="$large" 'BEGIN { printf "  %-22s %.2fx\n", n, (b / (l * l)) / (a / (s * s)) }'
done
