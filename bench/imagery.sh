#!/usr/bin/env bash
# Imagery tiler benchmarks, taken side by side in one run (bench/README.md "Imagery").
#   CPU time (user + sys, all processes) of `globe-tiler imagery` vs gdal2tiles.py
#   and vs `gdal_translate -of MBTILES` + `gdaladdo`, on the same input, zoom range
#   and tile format (PNG, lossless; bilinear at the finest zoom, averaging above).
#   Goal: <= 0.5 of the faster peer. Also wall time, peak RSS and output bytes.
# Usage: bench/imagery.sh
# Needs: scripts/build.sh done, samples/fetch.sh done, gdal2tiles.py (python3-gdal).
# Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
scratch=bench/scratch
data=samples/data
mkdir -p "$scratch"
threads=$(nproc)

cpu() { /usr/bin/time -f "%U %S %e %M" "$@" 2>&1 >/dev/null | tail -1 | awk '{ printf "%.2f %.2f %.0f\n", $1 + $2, $3, $4 / 1024 }'; }  # "cpu_s wall_s rss_mb"
add() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a + b }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", (b > 0 ? a / b : 0) }'; }
bytes() { du -sb "$1" | cut -f1; }

printf '| input | zooms | ours CPU s (wall) | gdal2tiles CPU s (wall) | gdal_translate+gdaladdo CPU s (wall) | ratio to faster peer | bytes ours / g2t / gt+addo | ours RSS MB |\n'
printf '|---|---|---|---|---|---|---|---|\n'

row() { # name input [our options...]   (input already has the bands to tile)
  local name=$1 input=$2; shift 2
  row_from "$name" "$input" "$input" "$@"
}

row_from() { # name input gdal_translate_input [our options...]
  local name=$1 input=$2 gt_input=$3; shift 3
  local ours="$scratch/$name.globe.mbtiles" g2t="$scratch/$name.g2t" gt="$scratch/$name.gt.mbtiles"
  # gdal_translate picks its own finest zoom (the closest to the source
  # resolution); the others are given the same range.
  rm -f "$gt"
  read -r c_gt w_gt _ <<<"$(cpu gdal_translate -q -of MBTILES -co TILE_FORMAT=PNG -co RESAMPLING=BILINEAR "$gt_input" "$gt")"
  local zmax factors=() f=2
  zmax=$(sqlite3 "$gt" "select max(zoom_level) from tiles")
  for ((z = zmax - 1; z >= 0; z--)); do factors+=("$f"); f=$((f * 2)); done
  read -r c_addo w_addo _ <<<"$(cpu gdaladdo -q -r average "$gt" "${factors[@]}")"
  read -r c_ours w_ours m_ours <<<"$(cpu "$tiler" imagery "$input" -o "$ours" --force -q -j "$threads" --min-zoom 0 --max-zoom "$zmax" --resampling bilinear "$@")"
  rm -rf "$g2t"
  read -r c_g2t w_g2t _ <<<"$(cpu gdal2tiles.py -q --xyz -z "0-$zmax" -r bilinear -w none --processes="$threads" "$input" "$g2t")"
  local c_gtall w_gtall best
  c_gtall=$(add "$c_gt" "$c_addo")
  w_gtall=$(add "$w_gt" "$w_addo")
  best=$(awk -v a="$c_g2t" -v b="$c_gtall" 'BEGIN { print (a < b ? a : b) }')
  printf '| %s | 0–%s | %s (%s) | %s (%s) | %s (%s) | **%s** | %s / %s / %s | %s |\n' \
    "$name" "$zmax" "$c_ours" "$w_ours" "$c_g2t" "$w_g2t" "$c_gtall" "$w_gtall" \
    "$(ratio "$c_ours" "$best")" "$(bytes "$ours")" "$(bytes "$g2t")" "$(bytes "$gt")" "$m_ours"
}

# Landsat in true colour (bands 3,2,1) for every tool: a VRT selects the bands.
gdal_translate -q -of VRT -b 3 -b 2 -b 1 "$data/landsat.tif" "$scratch/landsat321.vrt"
row cbers20 "$data/cbers20.tif"
row landsat321 "$scratch/landsat321.vrt"
row bluemarble "$data/bluemarble.tif"
# The same global image at z0-4, the zoom where its pixels are upsampled (our
# default). gdal_translate cannot be asked for z4: it reads a warped VRT on
# the z4 grid instead, so the warp is still charged to it.
gdalwarp -q -overwrite -of VRT -t_srs EPSG:3857 -te -20037508.342789244 -20037508.342789244 \
  20037508.342789244 20037508.342789244 -ts 4096 4096 -r bilinear -dstalpha \
  "$data/bluemarble.tif" "$scratch/bluemarble_z4.vrt" 2>/dev/null
row_from bluemarble_z4 "$data/bluemarble.tif" "$scratch/bluemarble_z4.vrt"
