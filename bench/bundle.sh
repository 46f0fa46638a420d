#!/usr/bin/env bash
# Constrained path bundling (docs/bundles.md), side by side in one run:
#   roads:   the thesis's Table 5.1 road case at scale: a synthetic road
#            network of ~975 k vertices (bench/make_synthetic_roads.cpp) and
#            31,608 connections between 2,500 towns; `globe-vectorize bundle`
#            wall and CPU seconds, peak RSS, the seconds of each stage; next
#            to it `globe-vectorize lines` of the same network (tiling the
#            network alone: what the bundle's package costs at least);
#   flights: the vega-datasets US flights (5,366 routes) over FlightGear's
#            airways (70,291 segments), the thesis's airline case;
#   global:  20,000 connections between the world's 2,385 ILS airports
#            (samples/data/world_airports.csv), pairs drawn with probability
#            proportional to runway ends (fixed seed), over the same airways:
#            transoceanic and antimeridian routes at airline scale (issue 33).
# Usage: bench/bundle.sh [VERTICES] [CONNECTIONS] [TOWNS]  (default 975491 31608 2500)
# Needs: scripts/build.sh and samples/fetch.sh done. Scratch: bench/scratch/bundle.
set -euo pipefail
cd "$(dirname "$0")/.."
vertices=${1:-975491}
connections=${2:-31608}
towns=${3:-2500}
B=build
V=$B/tools/vectorize/globe-vectorize
scratch=bench/scratch/bundle
mkdir -p "$scratch"
source bench/timing.sh

roads="$scratch/roads-$vertices.fgb" flows="$scratch/flows-$vertices-$connections-$towns.csv"
if [ ! -f "$roads" ] || [ ! -f "$flows" ]; then
  $B/bench/make_synthetic_roads "$vertices" "$connections" "$towns" "$roads.part.fgb" \
    "$flows.part"
  mv "$roads.part.fgb" "$roads"
  mv "$flows.part" "$flows"
fi
echo "bench/bundle.sh: $(nproc) threads"

# stages RUN...: the bundle command, then its summary's stage seconds.
bundle() { # OUT ARGS... -> "wall rss cpu" then the stage line on the next line
  local out=$1
  shift
  /usr/bin/time -f "%e %M %U %S" $V bundle "$@" -o "$out" --force 2>"$scratch/err.txt" >/dev/null
  tail -1 "$scratch/err.txt" | awk '{ print $1, $2, $3 + $4 }'
  grep -o 'bytes, [0-9.]* s (.*)' "$scratch/err.txt" | sed 's/^bytes, [0-9.]* s (//; s/)$//'
}

report() { # NAME RESULT (two lines)
  local name=$1 usage stages
  usage=$(echo "$2" | sed -n 1p)
  stages=$(echo "$2" | sed -n 2p)
  echo "$usage" | awk -v n="$name" '{ printf "%-8s wall %6.2f s, CPU %6.2f s, peak RSS %5.0f MB\n", n, $1, $3, $2 / 1024 }'
  echo "         stages (s): $stages"
}

r=$(bundle "$scratch/roads.mbtiles" "$flows" --from olon,olat --to dlon,dlat --weight trips \
  --network "$roads")
report roads "$r"
grep -o 'wrote.*bundles ([^)]*), mean detour [0-9.]*, ink ratio [0-9.]*; network [^;]*' "$scratch/err.txt" |
  sed 's/^/         /'
l=$(usage $V lines -q --force "$roads" -o "$scratch/roads-lines.mbtiles")
echo "$l" | awk '{ printf "lines    wall %6.2f s, CPU %6.2f s, peak RSS %5.0f MB (the network alone as a line package)\n", $1, $3, $2 / 1024 }'

f=$(bundle "$scratch/flights.mbtiles" samples/data/us_flights_airport.csv --from-id origin \
  --to-id destination --weight count --locations samples/data/us_airports.csv --id-field iata \
  --network samples/data/airways.geojson)
report flights "$f"
grep -o 'wrote.*bundles ([^)]*), mean detour [0-9.]*, ink ratio [0-9.]*; network [^;]*' "$scratch/err.txt" |
  sed 's/^/         /'

global="$scratch/global-20000.csv"
if [ ! -f "$global" ]; then
  python3 - samples/data/world_airports.csv >"$global.part" <<'PY'
import csv, random, sys
rows = list(csv.DictReader(open(sys.argv[1])))
rng = random.Random(33)
weights = [int(r["ils_runway_ends"]) for r in rows]
print("origin,olon,olat,destination,dlon,dlat,weight")
n = 0
while n < 20000:
    a, b = rng.choices(rows, weights, k=2)
    if a is b:
        continue
    print(",".join([a["icao"], a["lon"], a["lat"], b["icao"], b["lon"], b["lat"],
                    str(int(a["ils_runway_ends"]) + int(b["ils_runway_ends"]))]))
    n += 1
PY
  mv "$global.part" "$global"
fi
g=$(bundle "$scratch/global.mbtiles" "$global" --from olon,olat --to dlon,dlat --weight weight \
  --network samples/data/airways.geojson)
report global "$g"
grep -o 'wrote.*bundles ([^)]*), mean detour [0-9.]*, ink ratio [0-9.]*; network [^;]*' "$scratch/err.txt" |
  sed 's/^/         /'
grep -o '[0-9]* routed, [0-9]* unrouted[^;]*' "$scratch/err.txt" | head -1 | sed 's/^/         /'

# The US flights in the viewer at 1280 x 720 over the etopo20 globe (llvmpipe
# here): median frame and line-pass times of 5 frames, flat (deferred) and
# lifted (--bundles 3d) at the continental view of the readability test, and
# lifted at an oblique one.
world="$scratch/etopo20-z4.mbtiles"
[ -f "$world" ] || $B/tools/tiler/globe-tiler terrain -q samples/data/etopo20.tif --max-zoom 4 -o "$world"
view() { # NAME ARGS...
  local name=$1
  shift
  $B/viewer/globe-view "$world" "$scratch/flights.mbtiles" --size 1280x720 --stats "$@" |
    tr -d '{}"' | tr ',' '\n' | awk -v n="$name" -F': ' '
      $1 ~ /^ *frame_ms$/ { f = $2 } $1 ~ /^ *lines_ms$/ { l = $2 }
      END { printf "%-8s frame %7.1f ms, line pass %7.1f ms\n", n, f, l }'
}
view "2d" --camera=-97,39,5000000,0,0
view "3d" --camera=-97,39,5000000,0,0 --bundles 3d --exaggeration 20
view "3d tilt" --camera=-97,25,1500000,0,40 --bundles 3d --exaggeration 20
