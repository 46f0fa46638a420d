#!/usr/bin/env bash
# Point packages and charts (docs/points.md, docs/viewer.md "Charts"), side by
# side in one run:
#   build:  globe-vectorize points of PLACES synthetic places (Gaussian
#           clusters over Europe, 5 integer fields) against globe-vectorize
#           lines of as many vertices (make_synthetic_lines: PLACES/10 walks of
#           10 vertices), CPU seconds (user + system) and peak RSS; and
#           against tippecanoe (bench/fetch_tippecanoe.sh) clustering the
#           same CSV at the same distance and zooms, values summed;
#   memory: the same build of POINTS_SCALE (default 4) times the places,
#           peak RSS against the first (flat: near 1);
#   charts: the chart pass (GPU time of the instanced draw) for 10 k, 100 k
#           and 1 M places on screen at 1280 x 720 (uniform over 2 x 2
#           degrees, --merge-px 0 so every zoom holds every place, 4-8 px
#           pies), straight down over a flat terrain, and the terrain pass of
#           the same frame: charts_ms, terrain_ms, their ratio.
# Usage: bench/points.sh [PLACES] [CHART_COUNTS...]  (default 1000000; 10000 100000 1000000)
# Needs: scripts/build.sh done; fetches tippecanoe (bench/fetch_tippecanoe.sh).
# Scratch: bench/scratch/points (kept for reruns).
set -euo pipefail
cd "$(dirname "$0")/.."
places=${1:-1000000}
shift || true
counts=("$@")
[ ${#counts[@]} -eq 0 ] && counts=(10000 100000 1000000)
B=build
scratch=bench/scratch/points
mkdir -p "$scratch"
source bench/timing.sh

synthetic() { # N OUT.csv [uniform]: places (name, lon, lat, a..e)
  [ -f "$2" ] && return 0
  python3 - "$1" "$2" "${3:-clusters}" <<'PY'
import random, sys
n, path, mode = int(sys.argv[1]), sys.argv[2], sys.argv[3]
random.seed(7)
centres = [(random.uniform(-9, 30), random.uniform(36, 60), random.uniform(0.05, 1.5))
           for _ in range(400)]
with open(path + ".part", "w") as out:
    out.write("name,lon,lat,a,b,c,d,e\n")
    for i in range(n):
        if mode == "uniform":
            x, y = 6 + random.random() * 2, 44 + random.random() * 2
        else:
            cx, cy, s = random.choice(centres)
            x, y = random.gauss(cx, s), random.gauss(cy, s * 0.7)
        v = [random.randint(0, 1000) for _ in range(5)]
        out.write("p%d,%.6f,%.6f,%d,%d,%d,%d,%d\n" % (i, x, y, *v))
import os
os.rename(path + ".part", path)
PY
}

echo "bench/points.sh: $places places, $(nproc) threads"
synthetic "$places" "$scratch/places$places.csv"
lines="$scratch/lines$places.fgb"
[ -f "$lines" ] || $B/bench/make_synthetic_lines $((places / 10)) 10 "$lines" >/dev/null
pts=$(usage $B/tools/vectorize/globe-vectorize points -q --force "$scratch/places$places.csv" \
  --xy lon,lat --fields a,b,c,d,e -o "$scratch/points.mbtiles")
lns=$(usage $B/tools/vectorize/globe-vectorize lines -q --force "$lines" -o "$scratch/lines.mbtiles")
echo "$pts $lns" | awk -v n="$places" '{
  printf "build  %d places: points %.2f s CPU (%.2f wall), peak RSS %.0f MB; lines of %d vertices: %.2f s CPU (%.2f wall), peak RSS %.0f MB; ratio %.2f\n",
    n, $3, $1, $2 / 1024, n, $6, $4, $5 / 1024, $3 / $6 }'
# tippecanoe on the same CSV, the same zooms, its clustering at the same
# distance (pixels of a 256 px tile: -r1 keeps every place until clustered),
# the values summed: the issue's goal is points <= 0.5 x its CPU.
zmax=$(sqlite3 "$scratch/points.mbtiles" "select value from metadata where name = 'maxzoom'")
tip=$(usage "$(bench/fetch_tippecanoe.sh)" -q -f -o "$scratch/tippecanoe.mbtiles" -Z0 -z"$zmax" \
  -r1 --cluster-distance=40 -l places --accumulate-attribute=a:sum \
  --accumulate-attribute=b:sum --accumulate-attribute=c:sum --accumulate-attribute=d:sum \
  --accumulate-attribute=e:sum "$scratch/places$places.csv")
echo "$pts $tip" | awk -v z="$zmax" '{
  printf "       same places, z0-%d: tippecanoe --cluster-distance=40 %.2f s CPU (%.2f wall), peak RSS %.0f MB; points / tippecanoe CPU %.2f (goal <= 0.5)\n",
    z, $6, $4, $5 / 1024, $3 / $6 }'
$B/tools/vectorize/globe-vectorize info "$scratch/points.mbtiles" | sed -n '/places per zoom/,$p'
# Memory flat: POINTS_SCALE (default 4) times the places, the same clusters
# and zooms: peak RSS against the run above (0 skips it).
scale=${POINTS_SCALE:-4}
if [ "$scale" -gt 0 ]; then
  big=$((places * scale))
  synthetic "$big" "$scratch/places$big.csv"
  pbig=$(usage $B/tools/vectorize/globe-vectorize points -q --force "$scratch/places$big.csv" \
    --xy lon,lat --fields a,b,c,d,e --max-zoom "$zmax" -o "$scratch/points_big.mbtiles")
  echo "$pts $pbig" | awk -v n="$places" -v b="$big" '{
    printf "memory %d places: points %.2f s CPU (%.2f wall), peak RSS %.0f MB; peak RSS ÷ %d places: %.2f\n",
      b, $6, $4, $5 / 1024, n, $5 / $2 }'
fi

# Charts: a flat 2 x 2 degree terrain, N uniform places, one view over all.
gdal_create -q -of GTiff -outsize 200 200 -bands 1 -ot Float32 -burn 200 -a_srs EPSG:4326 \
  -a_ullr 6 46 8 44 "$scratch/flat.tif" 2>/dev/null || gdal_create -of GTiff -outsize 200 200 \
  -bands 1 -ot Float32 -burn 200 -a_srs EPSG:4326 -a_ullr 6 46 8 44 "$scratch/flat.tif" >/dev/null
$B/tools/tiler/globe-tiler terrain -q --force "$scratch/flat.tif" -o "$scratch/flat.mbtiles"
echo '{"min_px": 4, "max_px": 8, "legend": false}' >"$scratch/small.json"
# llvmpipe's timer queries see little of its deferred rasterization: the
# chart pass is also measured as frame time with charts minus without.
frame() { # extra args -> the stats JSON
  $B/viewer/globe-view "$scratch/flat.mbtiles" "$@" --size 1280x720 --camera=7,45,260000,0,0 \
    --stats --frames 5
}
bare=$(frame | python3 -c "import json, sys; print(json.load(sys.stdin)['frame_ms'])")
printf "%-9s %8s %7s %11s %11s %13s %13s %10s\n" places charts tiles charts_ms terrain_ms \
  frame_ms bare_frame_ms chart_cost
for n in "${counts[@]}"; do
  synthetic "$n" "$scratch/uniform$n.csv" uniform
  $B/tools/vectorize/globe-vectorize points -q --force "$scratch/uniform$n.csv" --xy lon,lat \
    --fields a,b,c,d,e --merge-px 0 --max-zoom 12 -o "$scratch/uniform$n.mbtiles"
  frame "$scratch/uniform$n.mbtiles" --chart-style "$scratch/small.json" | python3 -c "
import json, sys
s = json.load(sys.stdin)
print('%-9d %8d %7d %11.2f %11.2f %13.1f %13.1f %10.1f' % ($n, s['charts'], s['chart_tiles'],
      s['charts_ms'], s['terrain_ms'], s['frame_ms'], $bare, s['frame_ms'] - $bare))"
done
echo "chart_cost = frame_ms - bare_frame_ms (ms): the chart pass with its CPU side (instances are built once per tile set)"
