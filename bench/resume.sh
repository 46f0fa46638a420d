#!/usr/bin/env bash
# What an interruption costs (docs/robustness.md): per workload, the wall
# time of an uninterrupted build, then builds killed (SIGKILL) at 25 %, 50 %
# and 75 % of that time and continued with --resume. Prints the resumed run's
# time and the total cost (time until the kill + resumed run) / uninterrupted
# time: 1.00 is the floor (no work lost, no restart cost), 1 + f means the
# work before the kill was all lost. Each resumed package is compared byte
# for byte with the uninterrupted one.
# Usage: bench/resume.sh [terrain|imagery|lines...]   (after scripts/build.sh and
# samples/fetch.sh; default: all three)
set -euo pipefail
cd "$(dirname "$0")/.."
T=$(pwd)/build/tools/tiler/globe-tiler
V=$(pwd)/build/tools/vectorize/globe-vectorize
S=$(pwd)/samples/data
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp"

now() { date +%s.%N; }

measure() {  # NAME COMMAND... (without -o)
  local name=$1
  shift
  mkdir -p ref
  local t0 t1 full
  t0=$(now)
  (cd ref && "$@" -o out.mbtiles -q)
  t1=$(now)
  full=$(echo "$t1 - $t0" | bc -l)
  printf "%-28s uninterrupted %7.2f s\n" "$name" "$full"
  for f in 0.25 0.50 0.75; do
    rm -rf work && mkdir work
    local at
    at=$(echo "$full * $f" | bc -l)
    (cd work && exec "$@" -o out.mbtiles -q) &
    local pid=$!
    sleep "$at"
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    if [ -e work/out.mbtiles ]; then
      printf "%-28s finished before the kill at %3.0f %%\n" "$name" "$(echo "$f * 100" | bc -l)"
      continue
    fi
    t0=$(now)
    (cd work && "$@" -o out.mbtiles -q --resume)
    t1=$(now)
    local resumed same=identical
    resumed=$(echo "$t1 - $t0" | bc -l)
    cmp -s work/out.mbtiles ref/out.mbtiles || same=DIFFERENT
    printf "%-28s killed at %3.0f %%  resumed %7.2f s  cost %.2f  (%s)\n" "$name" \
      "$(echo "$f * 100" | bc -l)" "$resumed" "$(echo "($at + $resumed) / $full" | bc -l)" "$same"
  done
  rm -rf ref work
}

which=("$@")
[ ${#which[@]} -eq 0 ] && which=(terrain imagery lines)
for w in "${which[@]}"; do
  case $w in
    terrain) measure "terrain etopo20 z5" "$T" terrain "$S/etopo20.tif" --max-zoom 5 ;;
    imagery) measure "imagery bluemarble z5" "$T" imagery "$S/bluemarble.tif" --max-zoom 5 ;;
    lines) measure "lines efas_rivers" "$V" lines "$S/efas_rivers.shp" ;;
    *) echo "resume.sh: unknown workload '$w' (terrain, imagery, lines)" >&2; exit 2 ;;
  esac
done
