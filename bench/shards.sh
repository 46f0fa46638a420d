#!/usr/bin/env bash
# Sharded terrain and line builds (docs/scale-out.md), side by side in one run:
#   balance:  max ÷ mean CPU seconds of the N shards (goal <= 1.25);
#   overhead: (sum of the shards' CPU + the merge's CPU) ÷ the one-machine
#             build's CPU (goal <= 1.1);
#   merge:    merge wall time ÷ one-machine wall time (goal <= 0.1).
# On a real sample (etopo20, the whole world, web mercator to --max-zoom 6)
# and on a half-empty DEM (a SIZE^2 synthetic DEM whose east 40 % is nodata
# inside the file's extent: the footprint alone would mislead the estimate);
# lines: efas_rivers (595 k river segments over Europe, zooms 0-7).
# Shards run one after the other with all cores each, as on cluster nodes.
# Usage: bench/shards.sh [N] [SIZE] [all|terrain|lines]   (default 8 shards, SIZE 8192, all)
# Needs: scripts/build.sh done, samples/fetch.sh done. Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
vectorize=build/tools/vectorize/globe-vectorize
gen=build/bench/make_synthetic_dem
scratch=bench/scratch/shards
mkdir -p "$scratch"
n=${1:-8}
size=${2:-8192}
which=${3:-all}
threads=$(nproc)

source bench/timing.sh

half_empty() { # -> the DEM path
  local full="$scratch/syn$size.tif" half="$scratch/half$size.tif" out="$scratch/halfempty$size.tif"
  [ -f "$out" ] && { echo "$out"; return; }
  [ -f "$full" ] || "$gen" "$size" "$full" >/dev/null
  gdal_translate -q -srcwin 0 0 $((size * 6 / 10)) "$size" "$full" "$half"
  local ext
  ext=$(gdalinfo -json "$full" | python3 -c "import json,sys; c=json.load(sys.stdin)['cornerCoordinates']; print(c['upperLeft'][0], c['lowerRight'][1], c['lowerRight'][0], c['upperLeft'][1])")
  gdalwarp -q -overwrite -te $ext -tr 10 10 -dstnodata -32768 -co TILED=YES -co COMPRESS=DEFLATE \
    "$half" "$out"
  rm -f "$half"
  echo "$out"
}

row() { # name program command input [options]
  local name=$1 program=$2 command=$3 input=$4
  shift 4
  local one shard merge shards=() cpus=()
  one=$(usage "$program" "$command" -q --force -j "$threads" "$input" "$@" -o "$scratch/$name.one.mbtiles")
  for ((i = 0; i < n; i++)); do
    shard=$(usage "$program" "$command" -q --force -j "$threads" "$input" "$@" --shard "$i/$n" \
      -o "$scratch/$name.s$i.mbtiles")
    cpus+=("$(echo "$shard" | awk '{ print $3 }')")
    shards+=("$scratch/$name.s$i.mbtiles")
  done
  merge=$(usage "$program" merge -q --force -j "$threads" "${shards[@]}" -o "$scratch/$name.merged.mbtiles")
  printf '%s\n' "${cpus[@]}" | awk -v name="$name" -v n="$n" -v one="$one" -v merge="$merge" '
    { c[NR] = $1; s += $1; if ($1 > m) m = $1 }
    END {
      split(one, o, " "); split(merge, g, " ");
      printf "%-22s N=%d  shard CPU s:", name, n; for (i = 1; i <= NR; i++) printf " %.2f", c[i];
      printf "\n%-22s balance max/mean %.2f   overhead (shards+merge)/one %.2f   merge wall/one wall %.3f (one: %.2f s wall %.2f s CPU; merge %.2f s wall %.2f s CPU)\n",
        name, m / (s / NR), (s + g[3]) / o[3], g[1] / o[1], o[1], o[3], g[1], g[3] }'
}

echo "bench/shards.sh: $n shards, $threads threads each"
if [ "$which" != lines ]; then
  row etopo20_z6 "$tiler" terrain samples/data/etopo20.tif --max-zoom 6
  row "halfempty_$size" "$tiler" terrain "$(half_empty)"
fi
if [ "$which" != terrain ]; then
  row efas_rivers "$vectorize" lines samples/data/efas_rivers.shp
fi
