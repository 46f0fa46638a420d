#!/usr/bin/env bash
# Flow benchmarks, side by side in one run (docs: bench/README.md):
#   ratio rows: CPU seconds of globe-tiler analyze --layers flow, with
#     --flow-method fill and with carve (the whole
#     finest zoom solved, then every zoom written) ÷ CPU seconds of GRASS
#     r.watershed -s on the finest zoom extracted as a GeoTIFF (the import
#     into GRASS not counted) — the issue's goal is <= 0.5;
#   --large: wall time and peak RSS of --layers flow --memory-mb 512 on a
#     SIZE^2 synthetic DEM (default 32768: 1.07 G cells), out of core.
# The fastest of BENCH_RUNS (default 3) alternating runs of each.
# Usage: bench/flow.sh [SIZE]            (synthetic side, default 4096)
#        bench/flow.sh --large [SIZE]    (default 32768)
# Needs: scripts/build.sh done, samples/fetch.sh done, grass-core.
# Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
gen=build/bench/make_synthetic_dem
scratch=bench/scratch
mkdir -p "$scratch"
runs=${BENCH_RUNS:-3}
threads=$(nproc)

source bench/timing.sh

terrain() { # name dem -> the package path
  local pkg="$scratch/$1.terrain.mbtiles"
  [ -f "$pkg" ] || "$tiler" terrain -q -j "$threads" --tiling local "$2" -o "$pkg"
  echo "$pkg"
}

row() { # name dem method
  local name=$1 method=$3 pkg zmax fin ours="" peer=""
  pkg=$(terrain "$name" "$2")
  zmax=$(sqlite3 "$pkg" "select value from metadata where name='maxzoom'")
  fin="$(pwd)/$scratch/$name.finest.tif"
  "$tiler" extract --force "$pkg" --zoom "$zmax" -o "$fin" 2>/dev/null
  local gtime="$(pwd)/$scratch/$name.grass.time"
  for ((i = 0; i < runs; i++)); do
    ours+="$(usage "$tiler" analyze -q --force -j "$threads" --layers flow \
      --flow-method "$method" "$pkg" -o "$scratch/$name.flow-$method.mbtiles")"$'\n'
    grass --tmp-location "$fin" --exec bash -c "r.in.gdal -o --q input=$fin output=dem && \
      g.region raster=dem && /usr/bin/time -o $gtime -f '%e %M %U %S' \
      r.watershed -s --q elevation=dem accumulation=acc drainage=dir" >/dev/null 2>&1
    peer+="$(awk '{ print $1, $2, $3 + $4 }' "$gtime")"$'\n'
  done
  local w_o r_o c_o w_p r_p c_p cells
  read -r w_o r_o c_o <<<"$(printf '%s' "$ours" | fastest_cpu)"
  read -r w_p r_p c_p <<<"$(printf '%s' "$peer" | fastest_cpu)"
  cells=$(gdalinfo "$fin" | awk '/^Size is/ { gsub(",", ""); print $3 * $4 }')
  awk -v n="$name $method" -v cells="$cells" -v wo="$w_o" -v ro="$r_o" -v co="$c_o" -v wp="$w_p" \
    -v rp="$r_p" -v cp="$c_p" 'BEGIN {
      printf "%-20s %9d cells  flow cpu %7.2f s (wall %6.2f, rss %4d MB)  r.watershed -s cpu %7.2f s (wall %6.2f, rss %4d MB)  cpu ratio %.2f\n",
        n, cells, co, wo, ro / 1024, cp, wp, rp / 1024, co / cp }'
}

[ -x "$gen" ] || { echo "build first: scripts/build.sh" >&2; exit 1; }
if [ "${1:-}" = "--large" ]; then
  size=${2:-32768}
  synthetic="$scratch/synthetic_$size.tif"
  [ -f "$synthetic" ] || "$gen" "$size" "$synthetic"
  pkg=$(terrain "synthetic_$size" "$synthetic")
  echo "flow out of core: ${size}^2 cells, --memory-mb 512, $threads threads"
  read -r w r c <<<"$(usage "$tiler" analyze -q --force -j "$threads" --layers flow \
    --memory-mb 512 "$pkg" -o "$scratch/synthetic_$size.flow.mbtiles")"
  awk -v s="$size" -v w="$w" -v r="$r" -v c="$c" 'BEGIN {
    printf "synthetic_%d  wall %.1f s  cpu %.1f s  peak RSS %d MB (budget 512 MB)\n", s, w, c, r / 1024 }'
  exit 0
fi
size=${1:-4096}
synthetic="$scratch/synthetic_$size.tif"
[ -f "$synthetic" ] || "$gen" "$size" "$synthetic"
# South America from etopo20 (20', lowlands and coasts' sea floor), its
# columns moved to 82 W..34 W.
south_america="$scratch/south_america.tif"
[ -f "$south_america" ] || gdal_translate -q -srcwin 774 231 144 207 -a_ullr -82 13 -34 -56 \
  samples/data/etopo20.tif "$south_america"
echo "flow benchmarks: $threads threads, fastest of $runs"
for method in fill carve; do
  row brasilia samples/data/brasilia.tif $method
  row jacksboro samples/data/jacksboro.tif $method
  row south_america "$south_america" $method
  row "synthetic_$size" "$synthetic" $method
done
