#!/usr/bin/env bash
# Constrained path bundling (docs/bundles.md), side by side in one run:
#   roads:   the thesis's Table 5.1 road case at scale: a synthetic road
#            network of ~975 k vertices (bench/make_synthetic_roads.cpp) and
#            31,608 connections between 2,500 towns; `globe-vectorize bundle`
#            wall and CPU seconds, peak RSS, the seconds of each stage; next
#            to it `globe-vectorize lines` of the same network (tiling the
#            network alone: what the bundle's package costs at least);
#   flights: the vega-datasets US flights (5,366 routes) over FlightGear's
#            airways (70,291 segments), the thesis's airline case.
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
grep -o 'wrote.*bundles, mean detour [0-9.]*, ink ratio [0-9.]*; network [^;]*' "$scratch/err.txt" |
  sed 's/^/         /'
l=$(usage $V lines -q --force "$roads" -o "$scratch/roads-lines.mbtiles")
echo "$l" | awk '{ printf "lines    wall %6.2f s, CPU %6.2f s, peak RSS %5.0f MB (the network alone as a line package)\n", $1, $3, $2 / 1024 }'

f=$(bundle "$scratch/flights.mbtiles" samples/data/us_flights_airport.csv --from-id origin \
  --to-id destination --weight count --locations samples/data/us_airports.csv --id-field iata \
  --network samples/data/airways.geojson)
report flights "$f"
grep -o 'wrote.*bundles, mean detour [0-9.]*, ink ratio [0-9.]*; network [^;]*' "$scratch/err.txt" |
  sed 's/^/         /'
