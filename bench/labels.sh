#!/usr/bin/env bash
# Labels (docs/labels.md, issue 57): for 1k, 10k and 100k named places in
# view (a point package over the contiguous US on etopo20, names in Latin,
# Cyrillic, Greek, Arabic and Devanagari), at 1280 x 720 over the globe:
#  - place_ms: the CPU's placement per frame (layout, occlusion decisions,
#    collision grid, glyph quads) - the goal is 2 ms on one core for what a
#    view holds (MapLibre's budget);
#  - probe_ms: the GPU passes that place the anchors on the terrain and read
#    the terrain's depth under the labels, with their read-backs;
#  - frame ratio: the median frame with labels over the same frame with
#    --labels off (llvmpipe here: its GPU work runs on the same 2 cores);
#  - first frame extra: first_frame_ms with labels minus without (reading
#    the labels, shaping the text and filling the SDF atlas).
# Medians of --stats over FRAMES frames. Usage: bench/labels.sh [FRAMES]
set -euo pipefail
cd "$(dirname "$0")/.."
frames=${1:-7}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
B=build
$B/tools/tiler/globe-tiler terrain -q samples/data/etopo20.tif --tiling geodetic -o "$tmp/t.mbtiles"
stat() { echo "$1" | grep -o "\"$2\": [0-9.e+-]*" | head -n 1 | awk '{print $2}'; }
printf "%8s %8s %6s %9s %9s %11s %12s\n" places cand shown place_ms probe_ms frame_ratio first_extra
for n in 1000 10000 100000; do
  python3 - "$n" >"$tmp/p.csv" <<'PY'
import random, sys
n = int(sys.argv[1])
rng = random.Random(57)
stems = ["Spring", "Oak", "Cedar", "River", "Lake", "Hill", "Bay", "Rock", "Elm", "Pine",
         "Новый", "Большой", "Κάτω", "Άνω", "القرية", "الجديدة", "नया", "पुराना"]
print("name,lon,lat,v")
for i in range(n):
    name = f"{rng.choice(stems)} {rng.choice(stems)} {i}"
    print(f'"{name}",{rng.uniform(-124, -67):.5f},{rng.uniform(25, 49):.5f},{rng.randint(1, 1000)}')
PY
  $B/tools/vectorize/globe-vectorize points -q "$tmp/p.csv" --xy lon,lat --fields v \
    --label-field name --priority-field v --tiling geodetic -o "$tmp/p.mbtiles" --force
  on=$($B/viewer/globe-view "$tmp/t.mbtiles" "$tmp/p.mbtiles" --size 1280x720 \
    --camera=-96,38,4500000,0,0 --stats --frames "$frames" 2>/dev/null)
  off=$($B/viewer/globe-view "$tmp/t.mbtiles" "$tmp/p.mbtiles" --size 1280x720 \
    --camera=-96,38,4500000,0,0 --stats --frames "$frames" --labels off 2>/dev/null)
  labels=$(echo "$on" | grep -o '"labels": {[^}]*}')
  awk -v n="$n" -v c="$(stat "$labels" candidates)" -v s="$(stat "$labels" shown)" \
    -v p="$(stat "$labels" place_ms)" -v g="$(stat "$labels" probe_ms)" \
    -v fon="$(stat "$on" frame_ms)" -v foff="$(stat "$off" frame_ms)" \
    -v lon="$(stat "$on" first_frame_ms)" -v loff="$(stat "$off" first_frame_ms)" \
    'BEGIN { printf "%8d %8d %6d %9.2f %9.2f %11.2f %10.0f ms\n", n, c, s, p, g, fon / foff, lon - loff }'
done
