#!/usr/bin/env bash
# A global 5' relief grid, grid-registered like ETOPO5/GEBCO (4321 x 2161
# samples on -180..180, -90..90; pixel areas half a pixel past both): etopo20
# (lon 0..360) mosaicked with its copy shifted by -360 degrees, resampled.
# --relief: plus ridged noise of hundreds of metres between neighbouring
# samples (build/bench/make_synthetic_dem, STRETCH 16, centred on 0), the
# roughness of a real global 5' DEM's mountains that the smooth resampled
# grid lacks: a tiled 256 x 256 Int16 GeoTIFF, as such DEMs come.
# Usage: bench/make_global.sh [--relief] OUT.tif   (from the repository root)
set -euo pipefail
relief=0
if [ "${1:-}" = --relief ]; then relief=1; shift; fi
out=$1
if ((relief)); then
  smooth="${out%.tif}_smooth.tif" noise="${out%.tif}_noise.tif"
  [ -f "$smooth" ] || "$0" "$smooth"
  [ -f "$noise" ] || build/bench/make_synthetic_dem 4321 "$noise" 16
  cat >"${out%.tif}.vrt" <<VRT
<VRTDataset rasterXSize="4321" rasterYSize="2161">
  <SRS>EPSG:4326</SRS>
  <GeoTransform>-180.041666666666667, 0.0833333333333333, 0, 90.041666666666667, 0, -0.0833333333333333</GeoTransform>
  <VRTRasterBand dataType="Int16" band="1" subClass="VRTDerivedRasterBand">
    <PixelFunctionType>sum</PixelFunctionType>
    <ComplexSource><SourceFilename relativeToVRT="0">$(realpath "$smooth")</SourceFilename><SourceBand>1</SourceBand>
      <SrcRect xOff="0" yOff="0" xSize="4321" ySize="2161"/><DstRect xOff="0" yOff="0" xSize="4321" ySize="2161"/></ComplexSource>
    <ComplexSource><SourceFilename relativeToVRT="0">$(realpath "$noise")</SourceFilename><SourceBand>1</SourceBand>
      <SrcRect xOff="0" yOff="0" xSize="4321" ySize="2161"/><DstRect xOff="0" yOff="0" xSize="4321" ySize="2161"/>
      <ScaleOffset>-1200</ScaleOffset><ScaleRatio>1</ScaleRatio></ComplexSource>
  </VRTRasterBand>
</VRTDataset>
VRT
  gdal_translate -q -ot Int16 -co TILED=YES -co COMPRESS=DEFLATE "${out%.tif}.vrt" "$out"
  exit 0
fi
west="${out%.tif}_etopo20_west.vrt"
gdal_translate -q -of VRT samples/data/etopo20.tif "$west"
gt=$(gdalinfo samples/data/etopo20.tif | sed -n 's/^Origin = (\([-0-9.e+]*\),\([-0-9.e+]*\))/\1 \2/p')
read -r ox oy <<<"$gt"
px=$(gdalinfo samples/data/etopo20.tif | sed -n 's/^Pixel Size = (\([-0-9.e+]*\),.*/\1/p')
sed -i "s|<GeoTransform>.*</GeoTransform>|<GeoTransform>$(awk -v x="$ox" 'BEGIN { printf "%.17g", x - 360 }'), $px, 0, $oy, 0, -$px</GeoTransform>|" "$west"
gdalwarp -q -overwrite -r cubic -ot Int16 -te -180.041666666666667 -90.041666666666667 \
  180.041666666666667 90.041666666666667 -ts 4321 2161 "$west" samples/data/etopo20.tif "$out"
