#!/usr/bin/env bash
# The area fill pass against the line pass, per pixel, side by side in the same
# frames (issue 56: the fill pass's cost per pixel at most the line pass's):
# the world's countries (samples/data/world.gpkg) as an area package (a
# choropleth) and the same polygons' outlines as a line package, drawn
# together at 1280 x 720 without terrain, so both passes read the same
# G-buffer and the same number of pixels; three views (the whole disc, an
# oblique view over Europe, a close view of the Alps). Prints, per view, the
# median areas_ms and lines_ms of --stats and their ratio. On llvmpipe the
# GPU times are CPU times of the rasterizer threads.
# Usage: bench/areas_view.sh [FRAMES]   (default 10 frames a view)
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-10}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
B=build
$B/tools/vectorize/globe-vectorize areas -q samples/data/world.gpkg --max-zoom 6 \
  --choropleth pop/area_km2 -o "$tmp/areas.mbtiles"
$B/tools/vectorize/globe-vectorize lines -q samples/data/world.gpkg --max-zoom 6 \
  -o "$tmp/lines.mbtiles"
printf "%-8s %10s %10s %8s\n" view areas_ms lines_ms ratio
for view in "disc 15,20,15000000,0,0" "europe 10,40,3000000,0,55" "alps 9,46.5,400000,0,40"; do
  set -- $view
  stats=$($B/viewer/globe-view "$tmp/areas.mbtiles" "$tmp/lines.mbtiles" --globe --size 1280x720 \
    --camera="$2" --stats --frames "$frames" 2>/dev/null)
  a=$(echo "$stats" | grep -o '"areas_ms": [0-9.]*' | awk '{print $2}')
  l=$(echo "$stats" | grep -o '"lines_ms": [0-9.]*' | awk '{print $2}')
  awk -v n="$1" -v a="$a" -v l="$l" 'BEGIN { printf "%-8s %10.2f %10.2f %8.2f\n", n, a, l, a / l }'
done
