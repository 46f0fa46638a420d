#!/usr/bin/env bash
# The main job on real data, from a fresh Debian 12 machine: installs what is
# missing, builds, fetches the sample DEMs, tiles one into a terrain package
# prints its summary and renders a headless snapshot (OSMesa, no display needed),
# then turns a real road network into a line-cluster package with styled classes.
# Output: demo/jacksboro.mbtiles, demo/jacksboro.png, demo/contours.png, demo/globe.png (etopo20
# and Blue Marble on the globe), demo/flights.png (pie charts of US flights on it),
# demo/bundles.png (the US flight routes bundled over the airways, one bundle picked),
# demo/countries.png (the world's population density as a choropleth over the terrain),
# demo/canada_roads.mbtiles, demo/cbers20.mbtiles (git-ignored).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
samples/fetch.sh small
mkdir -p demo
build/tools/tiler/globe-tiler terrain samples/data/jacksboro.tif -o demo/jacksboro.mbtiles --force
build/tools/tiler/globe-tiler validate demo/jacksboro.mbtiles
build/tools/tiler/globe-tiler info demo/jacksboro.mbtiles
build/viewer/globe-view demo/jacksboro.mbtiles --snapshot demo/jacksboro.png --size 1280x720 \
  --camera=-84.30,36.55,2500,30,65 --shading elevation --stats
# Lines: NRCan roads (a shapefile without .prj: its CRS is given), one style class per CLASS.
build/tools/vectorize/globe-vectorize lines samples/data/canada_roads.shp --s_srs EPSG:3978 \
  --class-field CLASS --class-map 1=highway,2=primary,3=secondary,4=minor,200=ferry \
  --style highway:color=#d7301f,width=4px,casing=#3d0c02@1px --style primary:color=#fc8d59,width=3px \
  --style ferry:color=#2b8cbe,width=2px,dash=6+4 -o demo/canada_roads.mbtiles --force
build/tools/vectorize/globe-vectorize validate demo/canada_roads.mbtiles
build/tools/vectorize/globe-vectorize info demo/canada_roads.mbtiles | tail -n 20
# Lines over terrain: 50 m contours of the same DEM, shaded per pixel on the terrain.
rm -f demo/contours50.*
gdal_contour -q -i 50 -a elev samples/data/jacksboro.tif demo/contours50.shp
build/tools/vectorize/globe-vectorize lines -q demo/contours50.shp -o demo/contours.mbtiles --force \
  --style 'contours50:color=#8c2d04,width=1.5px'
build/viewer/globe-view demo/jacksboro.mbtiles demo/contours.mbtiles --snapshot demo/contours.png \
  --size 1280x720 --camera=-84.30,36.55,2500,30,65 --stats
build/tools/tiler/globe-tiler imagery samples/data/cbers20.tif --format jpg \
  -o demo/cbers20.mbtiles --force
build/tools/tiler/globe-tiler validate demo/cbers20.mbtiles
gdalinfo demo/cbers20.mbtiles >/dev/null && echo "demo: GDAL opens demo/cbers20.mbtiles (MBTiles)" >&2
# The whole Earth on the globe: etopo20 relief with Blue Marble draped over it.
build/tools/tiler/globe-tiler terrain -q --tiling geodetic samples/data/etopo20.tif \
  -o demo/etopo20.mbtiles --force
build/tools/tiler/globe-tiler imagery -q samples/data/bluemarble.tif -o demo/bluemarble.mbtiles \
  --force
build/viewer/globe-view demo/etopo20.mbtiles demo/bluemarble.mbtiles --snapshot demo/globe.png \
  --size 1280x720 --fit --stats
# Charts: US airports' flights by the region flown to, as pies on the same globe, each
# airport named by its city beside its chart (the busiest first; docs/labels.md).
build/tools/vectorize/globe-vectorize points samples/data/us_airport_flights.csv \
  --xy longitude,latitude --fields west,midwest,south,northeast,other --label-field city \
  --tiling geodetic -o demo/flights.mbtiles --force
build/tools/vectorize/globe-vectorize validate demo/flights.mbtiles
build/viewer/globe-view demo/etopo20.mbtiles demo/bluemarble.mbtiles demo/flights.mbtiles \
  --snapshot demo/flights.png --size 1280x720 --camera=-97,39,3500000,0,0 --stats
# Bundled flows: the US flight routes routed over FlightGear's airways, bundled and smoothed,
# on the same globe; the busiest transcontinental bundle picked and its connections highlighted.
build/tools/vectorize/globe-vectorize bundle samples/data/us_flights_airport.csv \
  --from-id origin --to-id destination --weight count --locations samples/data/us_airports.csv \
  --id-field iata --network samples/data/airways.geojson --tiling geodetic --label-field city \
  -o demo/bundles.mbtiles --force
build/tools/vectorize/globe-vectorize info demo/bundles.mbtiles | grep -A 12 '^bundled flows'
build/viewer/globe-view demo/etopo20.mbtiles demo/bluemarble.mbtiles demo/bundles.mbtiles \
  --snapshot demo/bundles.png --size 1280x720 --camera=-97,39,4500000,0,0 --pick 800,400
# Areas: the world's countries as a choropleth of population density (quantile classes,
# ColorBrewer YlOrRd), filled per pixel over the relief, named at their poles of
# inaccessibility.
build/tools/vectorize/globe-vectorize areas samples/data/world.gpkg --choropleth pop/area_km2 \
  --classes 5 --method quantile --colors YlOrRd --label-field name_long \
  -o demo/countries.mbtiles --force
build/tools/vectorize/globe-vectorize info demo/countries.mbtiles | grep -A 7 '^choropleth'
build/viewer/globe-view demo/etopo20.mbtiles demo/countries.mbtiles --snapshot demo/countries.png \
  --size 1280x720 --camera=15,30,12000000,0,0
echo "demo: wrote demo/jacksboro.png, demo/contours.png, demo/globe.png, demo/flights.png," \
  "demo/bundles.png, demo/countries.png, demo/canada_roads.mbtiles and demo/cbers20.mbtiles" >&2
