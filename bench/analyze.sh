#!/usr/bin/env bash
# Terrain analytics benchmarks, side by side in one run (docs: bench/README.md):
#   slope,aspect: globe-tiler analyze --layers slope,aspect of the WHOLE pyramid
#     ÷ gdaldem slope + gdaldem aspect (two runs) of the finest zoom only,
#     extracted as a GeoTIFF — the issue's goal is <= 1.0;
#   skyview: wall time of --layers skyview (16 directions, 10 km) alone.
# The fastest of BENCH_RUNS (default 3) alternating runs of each.
# Usage: bench/analyze.sh [SIZE]   (synthetic DEM side, default 4096)
# Needs: scripts/build.sh done, samples/fetch.sh done. Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
gen=build/bench/make_synthetic_dem
scratch=bench/scratch
mkdir -p "$scratch"
size=${1:-4096}
runs=${BENCH_RUNS:-3}
threads=$(nproc)

source bench/timing.sh

row() { # name dem
  local name=$1 dem=$2
  local pkg="$scratch/$name.terrain.mbtiles" out="$scratch/$name.analysis.mbtiles"
  local fin="$scratch/$name.finest.tif" zmax ours="" peer="" sky=""
  "$tiler" terrain -q --force --tiling local "$dem" -o "$pkg"
  zmax=$(sqlite3 "$pkg" "select value from metadata where name='maxzoom'")
  "$tiler" extract --force "$pkg" --zoom "$zmax" -o "$fin" 2>/dev/null
  for ((i = 0; i < runs; i++)); do
    ours+="$(seconds "$tiler" analyze -q --force -j "$threads" --layers slope,aspect "$pkg" -o "$out")"$'\n'
    local a b
    read -r a _ <<<"$(seconds gdaldem slope -q -compute_edges "$fin" "$scratch/$name.slope.tif")"
    read -r b _ <<<"$(seconds gdaldem aspect -q -compute_edges "$fin" "$scratch/$name.aspect.tif")"
    peer+="$(awk -v a="$a" -v b="$b" 'BEGIN { print a + b, 0 }')"$'\n'
  done
  sky="$(seconds "$tiler" analyze -q --force -j "$threads" --layers skyview "$pkg" -o "$out")"
  local t_ours rss t_peer t_sky sky_rss tiles
  read -r t_ours rss <<<"$(printf '%s' "$ours" | fastest)"
  read -r t_peer _ <<<"$(printf '%s' "$peer" | fastest)"
  read -r t_sky sky_rss <<<"$sky"
  tiles=$(sqlite3 "$pkg" "select count(*) from tiles")
  awk -v n="$name" -v z="$zmax" -v t="$tiles" -v o="$t_ours" -v p="$t_peer" -v r="$rss" \
    -v s="$t_sky" -v sr="$sky_rss" 'BEGIN {
      printf "%-22s z0-%s %4d tiles  slope,aspect %6.2f s  gdaldem x2 %6.2f s  ratio %.2f  rss %d MB  skyview %6.2f s (rss %d MB)\n",
        n, z, t, o, p, o / p, r / 1024, s, sr / 1024 }'
}

[ -x "$gen" ] || { echo "build first: scripts/build.sh" >&2; exit 1; }
synthetic="$scratch/synthetic_$size.tif"
[ -f "$synthetic" ] || "$gen" "$size" "$synthetic"
echo "analyze benchmarks: $threads threads, fastest of $runs"
row brasilia samples/data/brasilia.tif
row "synthetic_$size" "$synthetic"
