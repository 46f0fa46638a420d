#!/usr/bin/env bash
# A global 5' relief grid, grid-registered like ETOPO5/GEBCO (4321 x 2161
# samples on -180..180, -90..90; pixel areas half a pixel past both): etopo20
# (lon 0..360) mosaicked with its copy shifted by -360 degrees, resampled.
# Usage: bench/make_global.sh OUT.tif   (from the repository root)
set -euo pipefail
out=$1
west="${out%.tif}_etopo20_west.vrt"
gdal_translate -q -of VRT samples/data/etopo20.tif "$west"
gt=$(gdalinfo samples/data/etopo20.tif | sed -n 's/^Origin = (\([-0-9.e+]*\),\([-0-9.e+]*\))/\1 \2/p')
read -r ox oy <<<"$gt"
px=$(gdalinfo samples/data/etopo20.tif | sed -n 's/^Pixel Size = (\([-0-9.e+]*\),.*/\1/p')
sed -i "s|<GeoTransform>.*</GeoTransform>|<GeoTransform>$(awk -v x="$ox" 'BEGIN { printf "%.17g", x - 360 }'), $px, 0, $oy, 0, -$px</GeoTransform>|" "$west"
gdalwarp -q -overwrite -r cubic -ot Int16 -te -180.041666666666667 -90.041666666666667 \
  180.041666666666667 90.041666666666667 -ts 4321 2161 "$west" samples/data/etopo20.tif "$out"
