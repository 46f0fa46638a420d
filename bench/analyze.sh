#!/usr/bin/env bash
# Terrain analytics benchmarks, side by side in one run (docs: bench/README.md):
#   slope,aspect: globe-tiler analyze --layers slope,aspect of the WHOLE pyramid
#     ÷ gdaldem slope + gdaldem aspect (two runs) of the finest zoom only,
#     extracted as a GeoTIFF — the issue's goal is <= 1.0;
#   skyview: --layers skyview (16 directions, 10 km) of the WHOLE pyramid, CPU
#     seconds ÷ SAGA's Sky View Factor (saga_cmd ta_lighting 3, the same radius
#     and directions, METHOD 0: every cell along the ray) of the finest zoom
#     only — the issue's goal is <= 0.05. SAGA runs on rows of at most 4 M
#     samples (the synthetic 4096² would take it an hour).
# The fastest of BENCH_RUNS (default 3) alternating runs of each.
# Usage: bench/analyze.sh [SIZE]   (synthetic DEM side, default 4096)
# Needs: scripts/build.sh done, samples/fetch.sh done; installs saga (Debian)
# if missing. Scratch: bench/scratch/.
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
  local fin="$scratch/$name.finest.tif" zmax ours="" peer=""
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
  local sky="" saga="" cells
  cells=$(gdalinfo "$fin" | awk '/^Size is/ { gsub(",", ""); print $3 * $4 }')
  for ((i = 0; i < runs; i++)); do
    sky+="$(usage "$tiler" analyze -q --force -j "$threads" --layers skyview "$pkg" -o "$out")"$'\n'
    if ((cells <= 4000000)); then
      saga+="$(usage saga_cmd -c="$threads" ta_lighting 3 -DEM "$fin" -SVF "$scratch/$name.svf.sdat" \
        -VISIBLE "$scratch/$name.visible.sdat" -RADIUS 10000 -NDIRS 16 -METHOD 0)"$'\n'
    fi
  done
  local t_ours rss t_peer sky_w sky_rss sky_cpu saga_w saga_cpu tiles
  read -r t_ours rss <<<"$(printf '%s' "$ours" | fastest)"
  read -r t_peer _ <<<"$(printf '%s' "$peer" | fastest)"
  read -r sky_w sky_rss sky_cpu <<<"$(printf '%s' "$sky" | fastest_cpu)"
  read -r saga_w _ saga_cpu <<<"$(printf '%s' "${saga:-0 0 0}" | fastest_cpu)"
  tiles=$(sqlite3 "$pkg" "select count(*) from tiles")
  awk -v n="$name" -v z="$zmax" -v t="$tiles" -v o="$t_ours" -v p="$t_peer" -v r="$rss" \
    -v sw="$sky_w" -v sr="$sky_rss" -v sc="$sky_cpu" -v gw="$saga_w" -v gc="$saga_cpu" 'BEGIN {
      printf "%-22s z0-%s %4d tiles  slope,aspect %6.2f s  gdaldem x2 %6.2f s  ratio %.2f  rss %d MB\n",
        n, z, t, o, p, o / p, r / 1024
      printf "%-22s skyview cpu %7.2f s (wall %6.2f, rss %d MB)", "", sc, sw, sr / 1024
      if (gc > 0) printf "  SAGA svf cpu %7.2f s (wall %6.2f)  cpu ratio %.3f", gc, gw, sc / gc
      printf "\n" }'
}

[ -x "$gen" ] || { echo "build first: scripts/build.sh" >&2; exit 1; }
synthetic="$scratch/synthetic_$size.tif"
[ -f "$synthetic" ] || "$gen" "$size" "$synthetic"
command -v saga_cmd >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y \
  --no-install-recommends saga >/dev/null
# Real relief at 30 m: Jacksboro's ridges and valleys in UTM (as tests/skyview_test.cpp).
jacksboro="$scratch/jacksboro_utm30.tif"
[ -f "$jacksboro" ] || gdalwarp -q -t_srs EPSG:32617 -tr 30 30 -r bilinear -dstnodata -9999 \
  samples/data/jacksboro.tif "$jacksboro"
echo "analyze benchmarks: $threads threads, fastest of $runs"
row brasilia samples/data/brasilia.tif
row jacksboro_utm30 "$jacksboro"
row "synthetic_$size" "$synthetic"
