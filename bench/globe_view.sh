#!/usr/bin/env bash
# The globe in the viewer (issue 17), on a global 5' relief grid (4321 x 2161,
# geodetic package, bench/make_global.sh), 1280x720, llvmpipe or a GPU:
#   - triangles drawn for the full-disc view (--fit) and for close oblique
#     views; time to first frame (process start to first complete frame);
#   - frame time on the globe vs the flat frame for the same close views
#     (goal <= 1.1). Fastest of BENCH_RUNS (default 3) runs, interleaved.
# Usage: bench/globe_view.sh   (needs scripts/build.sh and samples/fetch.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
tiler=build/tools/tiler/globe-tiler
view=build/viewer/globe-view
out=bench/scratch/globe_view
runs=${BENCH_RUNS:-3}
mkdir -p "$out"
[ -f "$out/global_5min.tif" ] || bench/make_global.sh "$out/global_5min.tif"
pkg="$out/global_5min_geodetic.mbtiles"
[ -f "$pkg" ] || $tiler terrain -q --tiling geodetic "$out/global_5min.tif" -o "$pkg"

field() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p"; }
best() {  # fastest "frame_ms" of $runs runs; prints "frame_ms triangles first_frame_ms"
  local b=1e30 line v
  for _ in $(seq "$runs"); do
    line=$($view "$pkg" "$@" --stats --frames 5 --size 1280x720)
    v=$(echo "$line" | field frame_ms)
    if awk -v a="$v" -v b="$b" 'BEGIN { exit !(a + 0 < b + 0) }'; then
      b=$v
      keep="$v $(echo "$line" | field triangles) $(echo "$line" | field first_frame_ms)"
    fi
  done
  echo "$keep"
}
printf "%-30s %11s %9s %9s %11s %9s %7s\n" view globe_tris globe_ms first_ms flat_tris flat_ms ratio
read -r ms tris first <<<"$(best --globe --fit)"
printf "%-30s %11s %9s %9s %11s %9s %7s\n" "full disc (--fit)" "$tris" "$ms" "$first" - - -
for cam in "8,45,20000,0,70" "-70,-15,8000,90,75" "86,28,60000,180,60"; do
  read -r gms gtris gfirst <<<"$(best --globe --camera="$cam")"
  read -r fms ftris _ <<<"$(best --camera="$cam")"
  printf "%-30s %11s %9s %9s %11s %9s %7.2f\n" "$cam" "$gtris" "$gms" "$gfirst" "$ftris" "$fms" \
    "$(echo "$gms / $fms" | bc -l)"
done
