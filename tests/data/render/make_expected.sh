#!/usr/bin/env bash
# Regenerates the expected images of the viewer's render tests from the
# current build (review them before committing!). Needs samples/fetch.sh.
set -euo pipefail
cd "$(dirname "$0")/../../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/tools/tiler/globe-tiler terrain -q samples/data/jacksboro.tif -o "$tmp/j.mbtiles"
out=tests/data/render
build/viewer/globe-view "$tmp/j.mbtiles" --snapshot $out/jacksboro_hillshade.png --size 320x180 \
  --camera=-84.30,36.55,2500,30,65
for mode in elevation slope aspect; do
  build/viewer/globe-view "$tmp/j.mbtiles" --snapshot $out/jacksboro_fit_$mode.png --size 320x180 \
    --fit --shading $mode
done
# Analysis (tests/viewer_analysis_test.cpp): sky view, edges and flow of the same DEM.
build/tools/tiler/globe-tiler analyze -q "$tmp/j.mbtiles" \
  --layers slope,aspect,curvature,skyview,flow -o "$tmp/ja.mbtiles"
for mode in skyview edges flow; do
  build/viewer/globe-view "$tmp/j.mbtiles" "$tmp/ja.mbtiles" --snapshot $out/jacksboro_$mode.png \
    --size 480x360 --fit --shading $mode
done
build/viewer/globe-view "$tmp/j.mbtiles" "$tmp/ja.mbtiles" --snapshot \
  $out/jacksboro_slope_colormap.png --size 480x360 --fit --shading slope \
  --colormap tests/data/render/slope_colormap.txt
# Lines (tests/viewer_lines_test.cpp): 50 m contours of the same DEM.
gdal_contour -q -i 50 -a elev samples/data/jacksboro.tif "$tmp/c50.shp"
build/tools/vectorize/globe-vectorize lines -q "$tmp/c50.shp" -o "$tmp/c.mbtiles" \
  --style 'c50:color=#8c2d04,width=1.5px'
build/viewer/globe-view "$tmp/j.mbtiles" "$tmp/c.mbtiles" --snapshot $out/jacksboro_contours.png \
  --size 320x180 --camera=-84.30,36.55,2500,30,65
echo '{"c50": {"color": "#ffd92f", "width": 3, "casing_color": "#303030",
  "casing_width": 1, "dash": [8, 4]}}' >"$tmp/style.json"
build/viewer/globe-view "$tmp/j.mbtiles" "$tmp/c.mbtiles" --style "$tmp/style.json" \
  --snapshot $out/jacksboro_contours_styled.png --size 320x180 --camera=-84.25,36.60,6000,0,0
# Imagery (tests/viewer_imagery_test.cpp): Landsat over the Olinda DEM.
build/tools/tiler/globe-tiler terrain -q samples/data/olinda.tif -o "$tmp/o.mbtiles"
build/tools/tiler/globe-tiler imagery -q samples/data/landsat.tif --bands 3,2,1 -o "$tmp/n.mbtiles"
build/tools/tiler/globe-tiler imagery -q samples/data/landsat.tif --bands 4,3,2 -o "$tmp/f.mbtiles"
oblique="--size 320x180 --camera=-34.88,-8.07,2500,20,70"
build/viewer/globe-view "$tmp/o.mbtiles" "$tmp/n.mbtiles" $oblique \
  --snapshot $out/olinda_landsat_oblique.png
build/viewer/globe-view "$tmp/o.mbtiles" "$tmp/n.mbtiles" "$tmp/f.mbtiles" --image-opacity 1,0.5 \
  $oblique --snapshot $out/olinda_landsat_blended.png
# The globe (tests/viewer_globe_test.cpp): etopo20 in both global schemes.
build/tools/tiler/globe-tiler terrain -q --tiling geodetic samples/data/etopo20.tif -o "$tmp/eg.mbtiles"
build/tools/tiler/globe-tiler terrain -q --tiling webmercator samples/data/etopo20.tif \
  -o "$tmp/em.mbtiles"
build/viewer/globe-view "$tmp/eg.mbtiles" --globe --fit --exaggeration 30 --size 320x180 \
  --snapshot $out/globe_etopo_orbit.png
build/viewer/globe-view "$tmp/eg.mbtiles" --globe --camera=8,40,700000,0,60 --exaggeration 20 \
  --size 320x180 --snapshot $out/globe_etopo_alps.png
build/viewer/globe-view "$tmp/em.mbtiles" --globe --camera=0,90,3000000,0,0 --size 160x120 \
  --snapshot $out/globe_webmercator_north_cap.png
build/tools/tiler/globe-tiler imagery -q --max-zoom 3 samples/data/bluemarble.tif -o "$tmp/bm.mbtiles"
gdal_contour -q -i 1000 -a elev samples/data/etopo20.tif "$tmp/c1000.shp"
build/tools/vectorize/globe-vectorize lines -q --tiling geodetic "$tmp/c1000.shp" \
  -o "$tmp/c1000.mbtiles" --style 'c1000:color=#ffd92f,width=1.5px'
build/viewer/globe-view "$tmp/eg.mbtiles" "$tmp/bm.mbtiles" --globe --fit --size 320x180 \
  --snapshot $out/globe_bluemarble_orbit.png
build/viewer/globe-view "$tmp/eg.mbtiles" "$tmp/bm.mbtiles" "$tmp/c1000.mbtiles" --globe \
  --camera=179.5,60,1500000,90,50 --size 320x180 \
  --snapshot $out/globe_lines_over_imagery_antimeridian.png
# Elevation ramp (tests/viewer_shading_test.cpp): global and the Himalaya.
build/viewer/globe-view "$tmp/eg.mbtiles" --globe --fit --shading elevation --size 320x180 \
  --snapshot $out/globe_etopo_elevation.png
gdal_translate -q -projwin 70 40 100 25 samples/data/etopo20.tif "$tmp/himalaya.tif"
build/tools/tiler/globe-tiler terrain -q "$tmp/himalaya.tif" -o "$tmp/hi.mbtiles"
build/viewer/globe-view "$tmp/hi.mbtiles" --fit --shading elevation --size 320x180 \
  --snapshot $out/himalaya_elevation.png
ls -l $out/*.png
# Charts (tests/viewer_charts_test.cpp): US airports' flights by region over etopo20.
build/tools/tiler/globe-tiler terrain -q samples/data/etopo20.tif --max-zoom 4 -o "$tmp/w4.mbtiles"
build/tools/vectorize/globe-vectorize points -q samples/data/us_airport_flights.csv \
  --xy longitude,latitude --fields west,midwest,south,northeast,other --label-field iata \
  -o "$tmp/flights.mbtiles"
build/viewer/globe-view "$tmp/w4.mbtiles" "$tmp/flights.mbtiles" --size 480x300 \
  --camera=-97,39,3000000,0,0 --snapshot $out/us_flights_pies.png
build/viewer/globe-view "$tmp/w4.mbtiles" "$tmp/flights.mbtiles" --chart column --exaggeration 20 \
  --size 480x300 --camera=-90,27,900000,0,55 --snapshot $out/us_flights_columns.png
# Bundled flows (tests/viewer_bundles_test.cpp): US flights over the FlightGear airways.
build/tools/vectorize/globe-vectorize bundle -q samples/data/us_flights_airport.csv \
  --from-id origin --to-id destination --weight count --locations samples/data/us_airports.csv \
  --id-field iata --network samples/data/airways.geojson -o "$tmp/bundles.mbtiles"
build/viewer/globe-view "$tmp/w4.mbtiles" "$tmp/bundles.mbtiles" --size 480x300 \
  --camera=-97,39,5000000,0,0 --snapshot $out/us_flights_bundled.png
build/viewer/globe-view "$tmp/w4.mbtiles" "$tmp/bundles.mbtiles" --bundles 3d --exaggeration 20 \
  --size 480x300 --camera=-97,25,1500000,0,40 --snapshot $out/us_flights_bundled_3d.png
# CesiumJS (tests/web_cesium_test.cpp): the same DEM, geodetic, exported as
# quantized-mesh, lit by its vertex normals.
build/tools/tiler/globe-tiler terrain -q --tiling geodetic samples/data/jacksboro.tif \
  -o "$tmp/jg.mbtiles"
build/tools/tiler/globe-tiler export -q "$tmp/jg.mbtiles" --format quantized-mesh -o "$tmp/qm"
GLOBE_WEB_CACHE=$(scripts/web-deps.sh) node tests/web/run_page.mjs --viewport 480x320 \
  --mount /data="$tmp" --screenshot $out/cesium_jacksboro_lit.png \
  --query 'terrain=/data/qm&exaggeration=1.5&camera=-84.25,36.45,6000,0,-30&points=-84.2,36.55' \
  tests/web/pages/cesium_terrain.html > /dev/null
# MapLibre GL JS (tests/web_maplibre_test.cpp): the bundled flights above as MVT
# PMTiles drawn with the generated style.
build/tools/vectorize/globe-vectorize export -q "$tmp/bundles.mbtiles" -o "$tmp/flights.pmtiles" \
  --style-json "$tmp/style.json"
GLOBE_WEB_CACHE=$(scripts/web-deps.sh) node tests/web/run_page.mjs --viewport 480x320 \
  --mount /data="$tmp" --screenshot $out/maplibre_us_flights_mvt.png \
  --query 'style=/data/style.json&pmtiles=/data/flights.pmtiles&center=-97,39&zoom=3.5' \
  tests/web/pages/maplibre_mvt.html > /dev/null
# Areas in MapLibre GL JS (tests/web_maplibre_test.cpp): nc's counties as a BIR74
# choropleth served by globe-serve, drawn with the server's own style.
build/tools/vectorize/globe-vectorize areas -q samples/data/nc.gpkg --choropleth BIR74 \
  --classes 4 --max-zoom 7 -o "$tmp/nc.mbtiles"
build/tools/serve/globe-serve -q --port 18931 "$tmp/nc.mbtiles" >/dev/null &
serve=$!
sleep 2
GLOBE_WEB_CACHE=$(scripts/web-deps.sh) node tests/web/run_page.mjs --viewport 640x280 \
  --screenshot $out/maplibre_areas_choropleth.png \
  --query 'style=http://127.0.0.1:18931/nc/style.json&center=-79.890000,35.240000&zoom=5.500000' \
  tests/web/pages/maplibre_mvt.html > /dev/null
kill $serve
# Labels in MapLibre GL JS (tests/web_maplibre_test.cpp): the world's countries named by
# name_long, exported to PMTiles with the style and its glyphs (fonts/ beside it).
build/tools/vectorize/globe-vectorize areas -q samples/data/world.gpkg --label-field name_long \
  --max-zoom 4 -o "$tmp/world.mbtiles"
build/tools/vectorize/globe-vectorize export -q "$tmp/world.mbtiles" -o "$tmp/world.pmtiles" \
  --style-json "$tmp/style.json"
GLOBE_WEB_CACHE=$(scripts/web-deps.sh) node tests/web/run_page.mjs --viewport 512x256 \
  --mount /data="$tmp" --screenshot $out/maplibre_world_labels.png \
  --query 'style=/data/style.json&pmtiles=/data/world.pmtiles&center=15.000000,50.000000&zoom=2.500000' \
  tests/web/pages/maplibre_mvt.html > /dev/null
# The tutorial's pictures (tests/tutorial_test.cpp runs docs/tutorial.md): without expected
# images the test fails and keeps its folder, whose pictures become the expected ones.
rm -f $out/tutorial_*.png
GLOBE_TEST_KEEP=1 build/tests/tutorial_tests >/dev/null 2>&1 || true
kept=$(ls -dt /tmp/globe-test-Tutorial-EveryStepRunsAndMakesItsPictures-* | head -1)
cp "$kept"/tutorial_*.png $out/
rm -rf "$kept"
# Line patterns (tests/viewer_line_patterns_test.cpp writes its own lines): likewise.
rm -f $out/line_patterns.png
GLOBE_TEST_KEEP=1 build/tests/viewer_lines_tests --gtest_filter='*FourPatternsMatchExpected' \
  >/dev/null 2>&1 || true
kept=$(ls -dt /tmp/globe-test-ViewerLinePatterns-FourPatternsMatchExpected-* | head -1)
cp "$kept"/p.png $out/line_patterns.png
rm -rf "$kept"
# Contours coloured by slope (the same test file): likewise.
rm -f $out/line_colour_by_slope.png
GLOBE_TEST_KEEP=1 build/tests/viewer_lines_tests \
  --gtest_filter='*ContoursColouredBySlopeMatchExpected' >/dev/null 2>&1 || true
kept=$(ls -dt /tmp/globe-test-ViewerLineColours-ContoursColouredBySlopeMatchExpected-* | head -1)
cp "$kept"/s.png $out/line_colour_by_slope.png
rm -rf "$kept"
# Areas (tests/viewer_areas_test.cpp): North Carolina's SIDS rate (SID74/BIR74), a choropleth.
build/tools/vectorize/globe-vectorize areas -q samples/data/nc.gpkg --choropleth SID74/BIR74 \
  --classes 5 --method quantile --colors YlOrRd -o "$tmp/nc_sids.mbtiles"
build/viewer/globe-view "$tmp/nc_sids.mbtiles" --fit --size 320x200 \
  --snapshot $out/viewer_areas_nc.png
# Labels in many scripts (tests/viewer_label_scripts_test.cpp): the test's own run, kept.
rm -f $out/label_scripts.png
GLOBE_TEST_KEEP=1 build/tests/viewer_labels_tests \
  --gtest_filter='ViewerLabelScripts.EveryScriptDrawsAsExpected' >/dev/null 2>&1 || true
kept=$(ls -dt /tmp/globe-test-ViewerLabelScripts-EveryScriptDrawsAsExpected-* | head -1)
cp "$kept"/scripts.png $out/label_scripts.png
rm -rf "$kept"
