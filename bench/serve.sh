#!/usr/bin/env bash
# globe-serve under load (docs/serve.md), side by side in one run: every
# quantized-mesh tile of a package requested by C concurrent clients (curl),
# twice (cold: the server cuts each tile first; warm: its caches hold the
# neighbourhoods), against the floor: the same tiles exported to a folder and
# served as static files by tests/web/serve.mjs (node). Tiles per second,
# p50 / p95 / max latency, non-200 answers, the server's peak RSS.
#   synthetic: the 4096^2 DEM (bench/make_synthetic_dem.cpp), webmercator, 933 tiles
#   jacksboro: the 403 x 344 3" sample DEM, geodetic
# Usage: bench/serve.sh [CLIENTS]   (default 8). Needs scripts/build.sh and samples/fetch.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
S=$B/tools/serve/globe-serve
clients=${1:-8}
scratch=bench/scratch/serve
mkdir -p "$scratch"
echo "bench/serve.sh: $(nproc) threads, $clients clients"
synthetic="$scratch/synthetic-4096.tif"
[ -f "$synthetic" ] || $B/bench/make_synthetic_dem 4096 "$synthetic" >/dev/null

# load URLS_FILE -> "tiles/s p50_ms p95_ms max_ms errors"
load() {
  local start end
  start=$(date +%s.%N)
  xargs -P "$clients" -n 50 curl -s -o /dev/null -w '%{http_code} %{time_total}\n' < "$1" \
    > "$scratch/times.txt"
  end=$(date +%s.%N)
  awk -v s="$start" -v e="$end" '{ n++; if ($1 != 200) bad++; t[n] = $2 * 1000 }
    END { asort(t); printf "%7.0f tiles/s, p50 %6.1f ms, p95 %6.1f ms, max %7.1f ms, %d not 200",
          n / (e - s), t[int(n * 0.5) + 1], t[int(n * 0.95) + 1], t[n], bad }' "$scratch/times.txt"
}

for case in synthetic jacksboro; do
  case $case in
    synthetic) src=$synthetic tiling=webmercator ;;
    jacksboro) src=samples/data/jacksboro.tif tiling=geodetic ;;
  esac
  pkg="$scratch/$case.mbtiles"
  $T terrain -q --force --tiling $tiling "$src" -o "$pkg"
  $T export -q --force "$pkg" --format quantized-mesh -o "$scratch/$case-qm"
  # globe-serve
  $S "$pkg" --port 0 -q > "$scratch/url.txt" 2> "$scratch/serve.log" &
  pid=$!
  for _ in $(seq 50); do [ -s "$scratch/url.txt" ] && break; sleep 0.1; done
  url=$(head -1 "$scratch/url.txt")
  (cd "$scratch/$case-qm" && find . -name '*.terrain' | sed "s|^\./|${url}$case/|; s|\$|?extensions=octvertexnormals|") \
    > "$scratch/urls.txt"
  tiles=$(wc -l < "$scratch/urls.txt")
  echo "$case ($tiling, $tiles tiles):"
  echo "  globe-serve cold   $(load "$scratch/urls.txt")"
  echo "  globe-serve warm   $(load "$scratch/urls.txt")"
  echo "  globe-serve peak RSS $(awk '/VmHWM/ { print int($2 / 1024) " MB" }' /proc/$pid/status)"
  kill $pid; wait $pid 2>/dev/null || true
  # the floor: static files
  node tests/web/serve.mjs --mount "/$case=$scratch/$case-qm" --gzip-ext '' > "$scratch/url.txt" &
  pid=$!
  for _ in $(seq 50); do [ -s "$scratch/url.txt" ] && break; sleep 0.1; done
  static=$(head -1 "$scratch/url.txt")
  sed "s|^${url%/}|$static|" "$scratch/urls.txt" > "$scratch/static.txt"
  echo "  static files       $(load "$scratch/static.txt")"
  kill $pid; wait $pid 2>/dev/null || true
done
