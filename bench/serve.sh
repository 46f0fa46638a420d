#!/usr/bin/env bash
# globe-serve under load (docs/serve.md), side by side in one run, C
# concurrent clients (curl processes of 50 requests each, one connection):
#   * quantized-mesh cut on the fly: every tile of a package, twice (cold: the
#     server cuts each tile; warm: its tile cache answers), and Terrarium PNG
#     of the finest web mercator zoom, cold;
#   * the issue's load test: 200 clients, 20,000 random tiles of the finest
#     zoom (quantized-mesh, Terrarium) from a fresh server;
#   * stored tiles (the image package's tiles, the line package's MVT);
# each against the floor: the same tiles exported to a folder and served by
# Debian's nginx (installed here if missing). Tiles per second, p50 / p99 /
# max latency, answers other than 200, the server's peak RSS.
#   synthetic: the 4096^2 DEM (bench/make_synthetic_dem.cpp), webmercator
#   bluemarble: samples/data/bluemarble.tif as JPEG image tiles
#   airways: samples/data/airways.geojson as a line package, zooms 0..8
#   * memory: 100 clients asking every tile of the two finest zooms once from
#     a fresh server with --cache-mb 256: peak RSS against the bound of issue
#     55, --cache-mb + 256 MB;
# Usage: bench/serve.sh [CLIENTS]   (default 8). Needs scripts/build.sh and samples/fetch.sh.
# GLOBE_SERVE=PATH benchmarks another globe-serve build (e.g. an older one
# side by side).
set -euo pipefail
cd "$(dirname "$0")/.."
B=build
T=$B/tools/tiler/globe-tiler
V=$B/tools/vectorize/globe-vectorize
S=${GLOBE_SERVE:-$B/tools/serve/globe-serve}
clients=${1:-8}
scratch=$(realpath -m bench/scratch/serve)
mkdir -p "$scratch"
command -v nginx >/dev/null || DEBIAN_FRONTEND=noninteractive apt-get install -y \
  --no-install-recommends nginx-light >/dev/null
echo "bench/serve.sh: $(nproc) threads, $clients clients, $(nginx -v 2>&1)"
synthetic="$scratch/synthetic-4096.tif"
[ -f "$synthetic" ] || $B/bench/make_synthetic_dem 4096 "$synthetic" >/dev/null

# load URLS_FILE -> "tiles/s, p50, p99, max, errors"
load() {
  local start end per
  per=$(($(wc -l < "$1") / clients))  # URLs per curl: every client busy, at most 50
  per=$((3 * (per < 1 ? 1 : per > 50 ? 50 : per)))  # three arguments each: -o /dev/null URL
  start=$(date +%s.%N)
  # (-o /dev/null before every URL: curl applies one -o to one URL only)
  sed 's|^|-o /dev/null |' "$1" |
    xargs -P "$clients" -n "$per" curl -s -w '%{http_code} %{time_total}\n' > "$scratch/times.txt"
  end=$(date +%s.%N)
  sort -g -k2 "$scratch/times.txt" > "$scratch/sorted.txt"
  awk -v s="$start" -v e="$end" '{ n++; if ($1 != 200) bad++; t[n] = $2 * 1000 }
    END { printf "%7.0f tiles/s, p50 %6.1f ms, p99 %7.1f ms, max %7.1f ms, %d not 200",
          n / (e - s), t[int(n * 0.5) + 1], t[int(n * 0.99) + 1], t[n], bad + 0 }' \
    "$scratch/sorted.txt"
}
start_serve() { # PACKAGES... -> sets url, pid
  rm -f "$scratch/url.txt"
  $S "$@" --port 0 -q > "$scratch/url.txt" 2> "$scratch/serve.log" &
  pid=$!
  for _ in $(seq 100); do [ -s "$scratch/url.txt" ] && break; sleep 0.1; done
  url=$(head -1 "$scratch/url.txt")
}
stop_serve() {
  echo "  globe-serve peak RSS $(awk '/VmHWM/ { print int($2 / 1024) " MB" }' /proc/$pid/status)"
  kill $pid; wait $pid 2>/dev/null || true
}
# nginx serving DIR on a free port -> sets nurl
start_nginx() {
  local port=$((20000 + RANDOM % 20000))
  mkdir -p "$scratch/nginx"
  cat > "$scratch/nginx/nginx.conf" <<CONF
worker_processes $(nproc);
pid $scratch/nginx/nginx.pid;
error_log $scratch/nginx/error.log;
events { worker_connections 1024; }
http {
  access_log off;
  types { application/octet-stream terrain pbf; image/png png; image/jpeg jpg; }
  client_body_temp_path $scratch/nginx; proxy_temp_path $scratch/nginx;
  fastcgi_temp_path $scratch/nginx; uwsgi_temp_path $scratch/nginx; scgi_temp_path $scratch/nginx;
  server { listen 127.0.0.1:$port; root $1; }
}
CONF
  nginx -e "$scratch/nginx/error.log" -c "$scratch/nginx/nginx.conf"
  nurl="http://127.0.0.1:$port/"
}
stop_nginx() { nginx -e "$scratch/nginx/error.log" -c "$scratch/nginx/nginx.conf" -s stop; sleep 0.5; }
urls() { # DIR EXT BASE SUFFIX -> the tiles of DIR as URLs
  (cd "$1" && find . -name "*.$2" | sort | sed "s|^\./|$3|; s|\$|$4|")
}

# Terrain: quantized-mesh and Terrarium cut on the fly.
pkg="$scratch/synthetic.mbtiles"
$T terrain -q --force "$synthetic" -o "$pkg"
rm -rf "$scratch/qm" "$scratch/terrarium"
t0=$(date +%s.%N)
$T export -q --force "$pkg" --format quantized-mesh -o "$scratch/qm"
t1=$(date +%s.%N)
$T export -q --force "$pkg" --format terrarium -o "$scratch/terrarium"
max=$(ls "$scratch/terrarium" | grep -v json | sort -n | tail -1)
start_serve "$pkg"
urls "$scratch/qm" terrain "${url}synthetic/" "?extensions=octvertexnormals" > "$scratch/u.txt"
echo "synthetic 4096², quantized-mesh on the fly ($(wc -l < "$scratch/u.txt") tiles):"
echo "  globe-serve cold   $(load "$scratch/u.txt")"
echo "  globe-serve warm   $(load "$scratch/u.txt")"
echo "  (the export cutting the same tiles on all cores, no HTTP: $(awk -v n="$(wc -l < "$scratch/u.txt")" \
  -v a="$t0" -v b="$t1" 'BEGIN { printf "%.0f tiles/s", n / (b - a) }'))"
urls "$scratch/terrarium/$max" png "${url}synthetic/$max/" "?encoding=terrarium" > "$scratch/p.txt"
echo "synthetic 4096², Terrarium PNG on the fly, zoom $max ($(wc -l < "$scratch/p.txt") tiles):"
echo "  globe-serve cold   $(load "$scratch/p.txt")"
stop_serve
# The issue's load test: 200 clients asking 20,000 random tiles of the finest
# zoom (repeats included, as a map's users ask), from a fresh server.
zq=$(ls "$scratch/qm" | grep -v json | sort -n | tail -1)
random_urls() { # LIST -> 20,000 lines drawn from it (seeded, reproducible)
  awk 'BEGIN { srand(42) } { u[n++] = $0 } END { for (i = 0; i < 20000; i++) print u[int(rand() * n)] }' "$1"
}
urls "$scratch/qm/$zq" terrain "${url}synthetic/$zq/" "?extensions=octvertexnormals" > "$scratch/zq.txt"
random_urls "$scratch/zq.txt" > "$scratch/rq.txt"
urls "$scratch/terrarium/$max" png "${url}synthetic/$max/" "?encoding=terrarium" > "$scratch/zp.txt"
random_urls "$scratch/zp.txt" > "$scratch/rp.txt"
for kind in rq rp; do
  start_serve "$pkg"
  sed -i "s|^http://[^/]*/|$url|" "$scratch/$kind.txt"
  [ $kind = rq ] && what="quantized-mesh, zoom $zq ($(wc -l < "$scratch/zq.txt") tiles)" ||
    what="Terrarium, zoom $max ($(wc -l < "$scratch/zp.txt") tiles)"
  echo "load test, 200 clients, 20,000 random tiles, fresh server: $what"
  echo "  globe-serve        $(clients=200 load "$scratch/$kind.txt")"
  stop_serve
done
# Memory: 100 clients at once, each tile of the two finest zooms asked once
# (every one cut anew), --cache-mb 256.
start_serve "$pkg" --cache-mb 256
(cd "$scratch/qm" && find "$zq" "$((zq - 1))" -name "*.terrain" | sort |
  sed "s|^|${url}synthetic/|; s|\$|?extensions=octvertexnormals|") > "$scratch/m.txt"
echo "memory, 100 clients, every tile of zooms $((zq - 1))..$zq new ($(wc -l < "$scratch/m.txt")), --cache-mb 256 (bound 512 MB):"
echo "  globe-serve        $(clients=100 load "$scratch/m.txt")"
stop_serve
start_nginx "$scratch/qm"
urls "$scratch/qm" terrain "$nurl" "" > "$scratch/n.txt"
echo "  nginx, exported .terrain files  $(load "$scratch/n.txt")"
stop_nginx

# Stored tiles: images and MVT.
$T imagery -q --force samples/data/bluemarble.tif --format jpg -o "$scratch/bluemarble.mbtiles"
$V lines -q --force --max-zoom 8 samples/data/airways.geojson -o "$scratch/airways.mbtiles"
rm -rf "$scratch/img" "$scratch/mvt"
$T export -q --force "$scratch/bluemarble.mbtiles" -o "$scratch/img"
$V export -q --force "$scratch/airways.mbtiles" -o "$scratch/mvt"
start_serve "$scratch/bluemarble.mbtiles" "$scratch/airways.mbtiles"
for kind in img mvt; do
  [ $kind = img ] && ext=jpg name=bluemarble || ext=pbf name=airways
  urls "$scratch/$kind" $ext "${url}$name/" "" > "$scratch/s.txt"
  echo "$name, stored .$ext tiles ($(wc -l < "$scratch/s.txt")):"
  echo "  globe-serve        $(load "$scratch/s.txt")"
  load "$scratch/s.txt" > /dev/null
  echo "  globe-serve again  $(load "$scratch/s.txt")"
  start_nginx "$scratch/$kind"
  urls "$scratch/$kind" $ext "$nurl" "" > "$scratch/n.txt"
  echo "  nginx              $(load "$scratch/n.txt")"
  stop_nginx
done
stop_serve
