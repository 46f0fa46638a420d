#!/usr/bin/env bash
# Line pass cost against data size and against the geometry baseline
# (DESIGN §9): synthetic road-like random walks at constant density over an
# area that grows with the segment count (100 k, 1 M, 10 M segments), one
# fixed oblique view at the centre, over a flat terrain. Prints, per size,
# lines_ms of the deferred pass and of --lines geometry, and terrain_ms.
# Usage: bench/lines_view.sh [SEGMENTS...]   (default: 100000 1000000 10000000)
set -euo pipefail
cd "$(dirname "$0")/.."
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(100000 1000000 10000000)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
B=build
# Flat terrain around the view (1 km cells, 2 x 2 degrees at 45 N).
gdal_create -of GTiff -outsize 200 200 -bands 1 -ot Float32 -burn 200 -a_srs EPSG:4326 \
  -a_ullr 6 46 8 44 "$tmp/flat.tif"
$B/tools/tiler/globe-tiler terrain -q "$tmp/flat.tif" -o "$tmp/flat.mbtiles"
printf "%-10s %12s %12s %12s %10s\n" segments deferred_ms geometry_ms terrain_ms ratio
for n in "${sizes[@]}"; do
  python3 - "$n" "$tmp/walks.geojson" <<'PY'
import json, math, random, sys
n, path = int(sys.argv[1]), sys.argv[2]
random.seed(1)
# 2,000 segments per 0.01 square degree; walks of 100 steps of ~30 m.
half = math.sqrt(n / 2000 * 0.01) / 2
with open(path, "w") as out:
    out.write('{"type":"FeatureCollection","features":[')
    for w in range(n // 100):
        x, y = 7 + random.uniform(-half, half), 45 + random.uniform(-half, half)
        a = random.uniform(0, 2 * math.pi)
        pts = [[round(x, 7), round(y, 7)]]
        for _ in range(100):
            a += random.gauss(0, 0.3)
            x += 0.0004 * math.cos(a); y += 0.0003 * math.sin(a)
            pts.append([round(x, 7), round(y, 7)])
        out.write(("," if w else "") + json.dumps(
            {"type": "Feature", "properties": {}, "geometry": {"type": "LineString", "coordinates": pts}}))
    out.write("]}")
PY
  $B/tools/vectorize/globe-vectorize lines -q "$tmp/walks.geojson" -o "$tmp/walks.mbtiles" --force
  view="$tmp/flat.mbtiles $tmp/walks.mbtiles --size 1280x720 --camera=7,44.99,1500,0,60 --stats --frames 5"
  d=$($B/viewer/globe-view $view | python3 -c 'import json,sys; j=json.load(sys.stdin); print(j["lines_ms"], j["terrain_ms"])')
  g=$($B/viewer/globe-view $view --lines geometry | python3 -c 'import json,sys; print(json.load(sys.stdin)["lines_ms"])')
  set -- $d
  printf "%-10s %12.1f %12.1f %12.1f %10.2f\n" "$n" "$1" "$g" "$2" "$(echo "$1 / $g" | bc -l)"
  rm -f "$tmp/walks.geojson"
done
