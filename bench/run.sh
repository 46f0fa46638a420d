#!/usr/bin/env bash
# Terrain tiler benchmarks, taken side by side in one run (docs: bench/README.md).
#   1. time: globe-tiler terrain  ÷  one gdalwarp of the same DEM onto the finest
#      grid (same resampling, all cores) — the floor is one warp pass; the
#      fastest of BENCH_RUNS (default 3) alternating runs of each;
#   2. size: package (whole pyramid)  ÷  DEFLATE+PREDICTOR GeoTIFF of the finest
#      level at the same precision (Int16 quanta if they fit, else Int32; PREDICTOR=2, ZLEVEL=9);
#   3. memory: peak RSS for a 32768² synthetic DEM  ÷  for a 4096² one.
# Usage: bench/run.sh [quick]   (quick: skip the 32768² input)
# Needs: scripts/build.sh done, samples/fetch.sh done. Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
gen=build/bench/make_synthetic_dem
scratch=bench/scratch
mkdir -p "$scratch"
threads=$(nproc)

source bench/timing.sh
runs=${BENCH_RUNS:-3}

# gdalwarp onto exactly the grid of an extracted zoom (pixel centres on samples).
grid_of() { # tif -> "xmin ymin xmax ymax width height"
  local info w h ox oy px
  info=$(gdalinfo "$1")
  read -r w h <<<"$(sed -n 's/^Size is \([0-9]*\), \([0-9]*\)/\1 \2/p' <<<"$info")"
  read -r ox oy <<<"$(sed -n 's/^Origin = (\([-0-9.e+]*\),\([-0-9.e+]*\))/\1 \2/p' <<<"$info")"
  px=$(sed -n 's/^Pixel Size = (\([-0-9.e+]*\),.*/\1/p' <<<"$info")
  awk -v ox="$ox" -v oy="$oy" -v px="$px" -v w="$w" -v h="$h" \
    'BEGIN { printf "%.10f %.10f %.10f %.10f %d %d\n", ox, oy - h * px, ox + w * px, oy, w, h }'
}

row() { # name dem [tiler options...]
  # BENCH_ROWS=REGEX runs only the rows whose name matches.
  [[ -n "${BENCH_ROWS:-}" && ! "$1" =~ $BENCH_ROWS ]] && return 0
  local name=$1 dem=$2; shift 2
  local pkg="$scratch/$name.mbtiles"
  local t_tiler t_warp zmax grid crs step
  "$tiler" terrain -q --force -j "$threads" "$@" "$dem" -o "$pkg"
  zmax=$(sqlite3 "$pkg" "select value from metadata where name='maxzoom'")
  step=$(sqlite3 "$pkg" "select value from metadata where name='globe:height_step'")
  "$tiler" extract --force "$pkg" --zoom "$zmax" -o "$scratch/$name.finest.tif" 2>/dev/null
  read -r x0 y0 x1 y1 w h <<<"$(grid_of "$scratch/$name.finest.tif")"
  crs=$(sqlite3 "$pkg" "select value from metadata where name='globe:crs'")
  local tiler_runs="" warp_runs=""
  for ((i = 0; i < runs; i++)); do
    tiler_runs+="$(seconds "$tiler" terrain -q --force -j "$threads" "$@" "$dem" -o "$pkg")"$'\n'
    rm -f "$scratch/$name.gdalwarp.tif"
    warp_runs+="$(seconds gdalwarp -q -multi -wo NUM_THREADS=ALL_CPUS -r bilinear -t_srs "$crs" \
      -te "$x0" "$y0" "$x1" "$y1" -ts "$w" "$h" -ot Float32 "$dem" "$scratch/$name.gdalwarp.tif" 2>/dev/null)"$'\n'
  done
  read -r t_tiler rss <<<"$(printf '%s' "$tiler_runs" | fastest)"
  read -r t_warp _ <<<"$(printf '%s' "$warp_runs" | fastest)"
  # The finest level at the package's precision, as integers of `step`.
  rm -f "$scratch/$name.deflate.tif" "$scratch/$name.q.vrt"
  # Int16 when the quanta fit (the smaller, fairer peer), else Int32.
  local range type nodata
  range=$(gdalinfo -mm "$scratch/$name.finest.tif" | sed -n 's/.*Computed Min\/Max=\([-0-9.e+]*\),\([-0-9.e+]*\).*/\1 \2/p')
  type=$(awk -v r="$range" -v s="$step" 'BEGIN { split(r, m, " "); print (m[1] / s > -32767 && m[2] / s < 32767) ? "Int16" : "Int32" }')
  nodata=$([ "$type" = Int16 ] && echo -32768 || echo -2147483648)
  gdal_translate -q -of VRT -ot "$type" -scale 0 1 0 "$(awk -v s="$step" 'BEGIN { print 1 / s }')" -a_nodata "$nodata" \
    "$scratch/$name.finest.tif" "$scratch/$name.q.vrt"
  gdal_translate -q -co TILED=YES -co COMPRESS=DEFLATE -co PREDICTOR=2 -co ZLEVEL=9 \
    "$scratch/$name.q.vrt" "$scratch/$name.deflate.tif"
  local pkg_bytes tif_bytes
  pkg_bytes=$(stat -c %s "$pkg")
  tif_bytes=$(stat -c %s "$scratch/$name.deflate.tif")
  awk -v n="$name" -v tt="$t_tiler" -v tw="$t_warp" -v pb="$pkg_bytes" -v tb="$tif_bytes" -v rss="$rss" \
    'BEGIN { printf "%-22s tiler %7.2f s  gdalwarp %7.2f s  time ratio %5.2f (goal <= 1.5) | package %10d B  deflate %10d B  size ratio %5.2f (goal <= 0.6) | rss %6.0f MB\n",
             n, tt, tw, tt / tw, pb, tb, pb / tb, rss / 1024 }'
}


echo "bench: $(date -u +%FT%TZ), $(nproc) cores, $(gdal-config --version 2>/dev/null || echo GDAL) ($(git rev-parse --short HEAD))"
[ -f "$scratch/synth_4096.tif" ] || "$gen" 4096 "$scratch/synth_4096.tif"
[ -f "$scratch/global_5min.tif" ] || bench/make_global.sh "$scratch/global_5min.tif"
row jacksboro samples/data/jacksboro.tif
row brasilia_local samples/data/brasilia.tif --tiling local
row etopo20_geodetic samples/data/etopo20.tif --tiling geodetic
row synth_4096 "$scratch/synth_4096.tif"
row global_5min_geodetic "$scratch/global_5min.tif" --tiling geodetic
row global_5min_webmercator "$scratch/global_5min.tif"
# The same with real relief's roughness (hundreds of metres between neighbouring
# samples, as a global 5' DEM has in its mountains): bench/make_global.sh --relief.
[ -f "$scratch/global_5min_relief.tif" ] || bench/make_global.sh --relief "$scratch/global_5min_relief.tif"
row global_5min_relief_geodetic "$scratch/global_5min_relief.tif" --tiling geodetic
row global_5min_relief_webmercator "$scratch/global_5min_relief.tif"

if [ "${1:-}" != "quick" ]; then
  [ -f "$scratch/synth_32768.tif" ] || "$gen" 32768 "$scratch/synth_32768.tif"
  read -r t_small rss_small <<<"$(seconds "$tiler" terrain -q --force "$scratch/synth_4096.tif" -o "$scratch/m_small.mbtiles")"
  read -r t_big rss_big <<<"$(seconds "$tiler" terrain -q --force "$scratch/synth_32768.tif" -o "$scratch/m_big.mbtiles")"
  awk -v a="$rss_small" -v b="$rss_big" -v ta="$t_small" -v tb="$t_big" \
    'BEGIN { printf "memory: peak RSS 4096^2 %.0f MB (%.1f s), 32768^2 %.0f MB (%.1f s): ratio %.2f (goal <= 1.2)\n", a / 1024, ta, b / 1024, tb, b / a }'
fi
