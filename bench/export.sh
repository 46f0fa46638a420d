#!/usr/bin/env bash
# Web exports (docs/web.md), side by side in one run: per package, the
# terrain build's time, then `globe-tiler export --format terrarium` into each
# container (PMTiles, MBTiles, folder), Terrain-RGB into PMTiles and
# quantized-mesh (folder, gzipped folder, MBTiles): wall and
# CPU seconds, peak RSS, the export's time / the build's, bytes (and bytes per
# tile), fastest of 3 runs.
#   jacksboro: the 403 x 344 3" sample DEM, webmercator (tiles kept)
#   etopo20:   the global 20' grid, geodetic (resampled to web mercator)
#   synthetic: a 4096^2 DEM (bench/make_synthetic_dem.cpp), webmercator
# Usage: bench/export.sh   Needs scripts/build.sh and samples/fetch.sh. Scratch: bench/scratch/export.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
scratch=bench/scratch/export
mkdir -p "$scratch"
source bench/timing.sh
echo "bench/export.sh: $(nproc) threads"

synthetic="$scratch/synthetic-4096.tif"
[ -f "$synthetic" ] || $B/bench/make_synthetic_dem 4096 "$synthetic" >/dev/null

row() { # NAME BUILD_WALL OUT ARGS...
  local name=$1 build=$2 out=$3
  shift 3
  local r bytes tiles
  r=$(best $T export -q --force "$@" -o "$out")
  bytes=$(du -sb "$out" | cut -f1)
  tiles=$( (sqlite3 "$out" 'SELECT COUNT(*) FROM tiles' 2>/dev/null) ||
    find "$out" -name '*.png' -o -name '*.terrain' 2>/dev/null | wc -l)
  [[ "$out" == *.pmtiles ]] && tiles=$(od -An -tu8 -j72 -N8 "$out" | tr -d ' ')
  echo "$r $build $bytes $tiles" | awk -v n="$name" '{ printf "  %-22s wall %6.2f s, CPU %6.2f s, %5.0f MB RSS, %5.2fx the build, %9d bytes (%d tiles, %d B/tile)\n", n, $1, $3, $2 / 1024, $1 / $4, $5, $6, $5 / ($6 ? $6 : 1) }'
}
for case in ${EXPORT_CASES:-jacksboro etopo20 synthetic}; do
  case $case in
    jacksboro) src=samples/data/jacksboro.tif tiling=webmercator ;;
    etopo20) src=samples/data/etopo20.tif tiling=geodetic ;;
    synthetic) src=$synthetic tiling=webmercator ;;
  esac
  pkg="$scratch/$case.mbtiles"
  b=$(best $T terrain -q --force --tiling $tiling "$src" -o "$pkg")
  build=$(echo "$b" | cut -d' ' -f1)
  echo "$case ($tiling): terrain build wall $build s, package $(stat -c %s "$pkg") bytes"
  row "terrarium .pmtiles" "$build" "$scratch/$case.pmtiles" "$pkg" --format terrarium
  row "terrarium .mbtiles" "$build" "$scratch/$case-t.mbtiles" "$pkg" --format terrarium
  row "terrarium folder" "$build" "$scratch/$case-dir" "$pkg" --format terrarium
  row "terrain-rgb .pmtiles" "$build" "$scratch/$case-rgb.pmtiles" "$pkg" --format terrain-rgb
  row "quantized-mesh folder" "$build" "$scratch/$case-qm" "$pkg" --format quantized-mesh
  row "quantized-mesh gzip" "$build" "$scratch/$case-qmz" "$pkg" --format quantized-mesh --gzip
  row "quantized-mesh .mbtiles" "$build" "$scratch/$case-qm.mbtiles" "$pkg" --format quantized-mesh
done

# Vector tiles: the FlightGear airways (70,291 segments, samples/data/airways.geojson) to MVT
# PMTiles, zooms 0..8: `globe-vectorize lines` then `globe-vectorize export`, against
# tippecanoe (bench/fetch_tippecanoe.sh) from the same GeoJSON, -Z0 -z8, no limits on features
# or tile size (as bench/lines.sh runs it). CPU seconds, peak RSS, bytes.
V=$B/tools/vectorize/globe-vectorize
tippecanoe=$(bench/fetch_tippecanoe.sh)
airways=samples/data/airways.geojson
lines=$(best $V lines -q --force --max-zoom 8 "$airways" -o "$scratch/airways.mbtiles")
mvt=$(best $V export -q --force "$scratch/airways.mbtiles" -o "$scratch/airways.pmtiles")
tip=$(best "$tippecanoe" -o "$scratch/airways.tippecanoe.pmtiles" --force -q -P -Z0 -z8 \
  --no-feature-limit --no-tile-size-limit -l airways "$airways")
echo "airways to MVT PMTiles, zooms 0..8 (tippecanoe $("$tippecanoe" --version 2>&1 | head -1)):"
echo "$lines $mvt $(stat -c %s "$scratch/airways.pmtiles")" | awk '{ printf "  ours        CPU %6.2f s (lines %.2f + export %.2f), %4.0f MB RSS, %9d bytes\n", $3 + $6, $3, $6, ($2 > $5 ? $2 : $5) / 1024, $7 }'
echo "$tip $(stat -c %s "$scratch/airways.tippecanoe.pmtiles")" | awk '{ printf "  tippecanoe  CPU %6.2f s, %4.0f MB RSS, %9d bytes\n", $3, $2 / 1024, $4 }'
