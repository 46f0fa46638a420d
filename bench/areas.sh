#!/usr/bin/env bash
# Area packages (docs/areas.md) against tippecanoe, side by side in one run
# (bench/README.md "Areas"). Per input, BENCH_RUNS rounds (default 2), the tools
# alternating, the least-CPU run of each counting (timing.sh):
#   ours:       globe-vectorize areas IN -o OUT.mbtiles --max-zoom Z, -j 1 and -j 2
#               (an MBTiles of zstd blobs), then globe-vectorize export OUT.mbtiles
#               -o OUT.pmtiles (MVT, gzip) for bytes like tippecanoe's;
#   tippecanoe: -Z0 -zZ --no-feature-limit --no-tile-size-limit into PMTiles (MVT,
#               gzip), with its default simplification (Douglas-Peucker per ring,
#               borders simplified apart) and with --detect-shared-borders (its own
#               way of keeping neighbours' borders identical).
# Both read the same GeoJSONSeq file. Reported: wall and CPU seconds (user + sys),
# peak RSS, bytes, tiles, ours / tippecanoe; then a verdict per goal of the issue:
# CPU <= 0.5x tippecanoe's, bytes <= 1x, memory flat in the input size; and the
# vertices per zoom of both tools' MVT (decoded by tippecanoe-decode).
# Inputs (made once, deterministic, kept in the scratch folder):
#   world_dense: samples/data/world.gpkg (177 countries, 10.7 k vertices) through
#                `ogr2ogr -segmentize 0.03` (degrees): 309 k vertices;
#   tess:        80 x 60 cells of a jittered lattice (0.2 x 0.15 degrees from 0 E,
#                42 N), each cell's four borders wiggled by midpoint displacement
#                seeded by the border, so neighbours share every vertex: 312 k vertices;
#   tess4x:      the same lattice, 160 x 120 cells (twice the extent each way, the
#                same cells): 1.25 M vertices, for the memory goal.
# Usage: bench/areas.sh [quick]   (quick: skip tess4x, i.e. the memory goal)
# Env: BENCH_RUNS (2: about 7 minutes on 2 cores), AREAS_ZOOM (8: both tools write about the same tiles).
# Needs: the globe-vectorize target built, samples/fetch.sh done; fetches tippecanoe
# (bench/fetch_tippecanoe.sh). Scratch: bench/scratch/areas; the report is also
# written to bench/scratch/areas-latest.txt.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=${1:-}
V=build/tools/vectorize/globe-vectorize
scratch=bench/scratch/areas
latest=bench/scratch/areas-latest.txt
runs=${BENCH_RUNS:-2}
zmax=${AREAS_ZOOM:-8}
mkdir -p "$scratch"
source bench/timing.sh
tippecanoe=$(bench/fetch_tippecanoe.sh)
# tippecanoe-decode from the same trixie package, through the same loader.
troot=bench/scratch/tippecanoe/root
tlibs=$troot/usr/lib/x86_64-linux-gnu
decode() { "$tlibs/ld-linux-x86-64.so.2" --library-path "$tlibs" "$troot/usr/bin/tippecanoe-decode" "$@" 2>/dev/null; }

count_vertices() { # GeoJSON (one FeatureCollection of tiles, or features one per line) on stdin -> vertices
  python3 -c '
import json, sys
n = 0
def walk(c):
    global n
    if c and isinstance(c[0], (int, float)): n += 1
    else:
        for x in c: walk(x)
def feature(f):
    if f.get("type") == "FeatureCollection":
        for g in f["features"]: feature(g)
    elif f.get("geometry"): walk(f["geometry"]["coordinates"])
text = sys.stdin.read()
try: feature(json.loads(text))
except ValueError:
    for line in text.splitlines():
        if line.strip(): feature(json.loads(line))
print(n)'
}

tessellation() { # NX NY OUT.geojsons
  [ -f "$3" ] && return 0
  python3 - "$1" "$2" "$3" <<'PY'
import os, random, sys
nx, ny, path = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
x0, y0, dx, dy, depth = 0.0, 42.0, 0.2, 0.15, 4  # 4 halvings: 16 segments a border
def corner(i, j):  # lattice point, jittered inside; string seeds are stable across runs
    r = random.Random("c%d,%d" % (i, j))
    jx = 0 if i in (0, nx) else r.uniform(-0.2, 0.2)
    jy = 0 if j in (0, ny) else r.uniform(-0.2, 0.2)
    return (x0 + (i + jx) * dx, y0 + (j + jy) * dy)
def border(key, a, b):  # midpoint displacement seeded by the border: both sides get its points
    r, pts, amp = random.Random(key), [a, b], 0.08
    for _ in range(depth):
        out = [pts[0]]
        for p, q in zip(pts, pts[1:]):
            ex, ey = q[0] - p[0], q[1] - p[1]
            o = r.uniform(-amp, amp)
            out += [((p[0] + q[0]) / 2 - ey * o, (p[1] + q[1]) / 2 + ex * o), q]
        pts, amp = out, amp * 0.6
    return pts
with open(path + ".part", "w") as f:
    for j in range(ny):
        for i in range(nx):
            c00, c10, c11, c01 = corner(i, j), corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)
            ring = (border("h%d,%d" % (i, j), c00, c10)[:-1] + border("v%d,%d" % (i + 1, j), c10, c11)[:-1]
                    + border("h%d,%d" % (i, j + 1), c01, c11)[::-1][:-1] + border("v%d,%d" % (i, j), c00, c01)[::-1])
            n = j * nx + i
            f.write('{"type":"Feature","properties":{"id":%d,"value":%d},"geometry":{"type":"Polygon",'
                    '"coordinates":[[%s]]}}\n' % (n, random.Random(n).randint(0, 1000),
                                                  ",".join("[%.6f,%.6f]" % p for p in ring)))
os.rename(path + ".part", path)
PY
}

inputs() {
  local w=$scratch/world_dense.geojsons
  if [ ! -f "$w" ]; then
    ogr2ogr -f GeoJSONSeq -segmentize 0.03 "$w.part.geojsons" samples/data/world.gpkg
    mv "$w.part.geojsons" "$w"
  fi
  tessellation 80 60 "$scratch/tess.geojsons"
  [ "$quick" = quick ] || tessellation 160 120 "$scratch/tess4x.geojsons"
}

tiles_of() { # package -> tiles (PMTiles: addressed tiles in the header)
  case $1 in
    *.pmtiles) od -An -tu8 -j72 -N8 "$1" | tr -d ' ' ;;
    *) "$V" info "$1" | awk '/^total:/ { print $2 }' ;;
  esac
}

measure() { # NAME: BENCH_RUNS rounds of every tool, alternating -> $scratch/NAME.TOOL.times
  local name=$1 in=$scratch/$1.geojsons o=$scratch/$1
  local tip=(-q --force -P -Z0 -z"$zmax" --no-feature-limit --no-tile-size-limit -l "$name")
  rm -f "$o".*.times
  for _ in $(seq "$runs"); do
    usage "$V" areas -q --force -j 1 --max-zoom "$zmax" "$in" -o "$o.j1.mbtiles" >>"$o.j1.times"
    usage "$V" areas -q --force -j 2 --max-zoom "$zmax" "$in" -o "$o.mbtiles" >>"$o.j2.times"
    usage "$V" export -q --force "$o.mbtiles" -o "$o.pmtiles" >>"$o.export.times"
    usage "$tippecanoe" "${tip[@]}" -o "$o.tippecanoe.pmtiles" "$in" >>"$o.tip.times"
    usage "$tippecanoe" "${tip[@]}" --detect-shared-borders -o "$o.tippecanoe-dsb.pmtiles" "$in" >>"$o.dsb.times"
  done
}

report() { # NAME -> table rows; sets the globals the verdicts read
  local name=$1 o=$scratch/$1 vertices
  vertices=$(count_vertices <"$o.geojsons")
  local j1 j2 ex tp ds
  j1=$(fastest_cpu <"$o.j1.times")
  j2=$(fastest_cpu <"$o.j2.times")
  ex=$(fastest_cpu <"$o.export.times")
  tp=$(fastest_cpu <"$o.tip.times")
  ds=$(fastest_cpu <"$o.dsb.times")
  echo "$name: $vertices vertices, zooms 0..$zmax"
  awk -v j1="$j1" -v j2="$j2" -v ex="$ex" -v tp="$tp" -v ds="$ds" \
      -v bj1="$(stat -c %s "$o.j1.mbtiles")" -v bm="$(stat -c %s "$o.mbtiles")" \
      -v bp="$(stat -c %s "$o.pmtiles")" -v bt="$(stat -c %s "$o.tippecanoe.pmtiles")" \
      -v bd="$(stat -c %s "$o.tippecanoe-dsb.pmtiles")" -v tm="$(tiles_of "$o.mbtiles")" \
      -v tpm="$(tiles_of "$o.pmtiles")" -v tt="$(tiles_of "$o.tippecanoe.pmtiles")" \
      -v td="$(tiles_of "$o.tippecanoe-dsb.pmtiles")" '
    function row(label, t, bytes, tiles, rb,   a) {
      split(t, a, " ")
      printf "  %-34s %7.2f %7.2f %7.0f %10d %7d %6.2f %6.2f %s\n", label, a[1], a[3], a[2] / 1024,
             bytes, tiles, a[3] / ct, a[3] / cd, rb
    }
    BEGIN {
      split(tp, t, " "); ct = t[3]; split(ds, d, " "); cd = d[3]
      split(j2, o, " "); split(ex, e, " ")
      both = sprintf("%.2f %.0f %.2f", o[1] + e[1], (o[2] > e[2] ? o[2] : e[2]), o[3] + e[3])
      printf "  %-34s %7s %7s %7s %10s %7s %6s %6s %s\n", "tool", "wall s", "CPU s", "RSS MB", "bytes",
             "tiles", "CPU/tc", "/tc-sb", "bytes/tc (/tc-sb)"
      row("ours -j1 (.mbtiles, zstd)", j1, bj1, tm, sprintf("%.2f (%.2f)", bj1 / bt, bj1 / bd))
      row("ours -j2 (.mbtiles, zstd)", j2, bm, tm, sprintf("%.2f (%.2f)", bm / bt, bm / bd))
      row("ours export -> .pmtiles (MVT gzip)", ex, bp, tpm, "")
      row("ours -j2 + export", both, bp, tpm, sprintf("%.2f (%.2f)", bp / bt, bp / bd))
      row("tippecanoe", tp, bt, tt, "")
      row("tippecanoe --detect-shared-borders", ds, bd, td, "")
    }'
  # name cpu_build/tc cpu_build/tc-sb cpu_with_export/tc pmtiles_bytes/tc mbtiles/tc rss_ours rss_tc
  echo "$j2 $ex $tp $ds $(stat -c %s "$o.pmtiles") $(stat -c %s "$o.mbtiles") $(stat -c %s "$o.tippecanoe.pmtiles")" |
    awk -v n="$name" '{ print n, $3 / $9, $3 / $12, ($3 + $6) / $9, $13 / $15, $14 / $15, $2, $8 }' >>"$scratch/verdicts"
}

per_zoom() { # NAME: vertices per zoom in the MVT of each tool (closing vertices included)
  local o=$scratch/$1
  echo "$1: MVT vertices per zoom (tippecanoe-decode): zoom, ours, tippecanoe, tippecanoe --detect-shared-borders, ours/tippecanoe"
  for z in $(seq 0 "$zmax"); do
    local a b c
    a=$(decode -Z "$z" -z "$z" "$o.pmtiles" | count_vertices)
    b=$(decode -Z "$z" -z "$z" "$o.tippecanoe.pmtiles" | count_vertices)
    c=$(decode -Z "$z" -z "$z" "$o.tippecanoe-dsb.pmtiles" | count_vertices)
    awk -v z="$z" -v a="$a" -v b="$b" -v c="$c" 'BEGIN { printf "  z%-2d %9d %9d %9d %6.1f\n", z, a, b, c, a / (b ? b : 1) }'
  done
}

verdicts() {
  awk -v quick="$quick" '
    { n[NR] = $1; cpu[NR] = $2; dsb[NR] = $3; exp_[NR] = $4; pm[NR] = $5; mb[NR] = $6; rss[$1] = $7; trss[$1] = $8 }
    END {
      ok = 1; s = ""
      for (i = 1; i <= NR; ++i) { if (cpu[i] > 0.5) ok = 0; s = s sprintf("%s %.2f (%.2f vs --detect-shared-borders, %.2f with export); ", n[i], cpu[i], dsb[i], exp_[i]) }
      printf "CPU    (goal <= 0.5x tippecanoe, ours -j2): %s-> %s\n", s, ok ? "MET" : "NOT MET"
      ok = 1; s = ""
      for (i = 1; i <= NR; ++i) { if (pm[i] > 1) ok = 0; s = s sprintf("%s %.2f (zstd package %.2f); ", n[i], pm[i], mb[i]) }
      printf "bytes  (goal <= 1x tippecanoe, MVT PMTiles both): %s-> %s\n", s, ok ? "MET" : "NOT MET"
      if (quick == "quick") print "memory (goal: flat in input size): not measured (quick)"
      else printf "memory (goal: flat in input size): peak RSS tess4x / tess = %.0f / %.0f MB = %.2f (tippecanoe %.2f) -> %s\n",
                  rss["tess4x"] / 1024, rss["tess"] / 1024, rss["tess4x"] / rss["tess"], trss["tess4x"] / trss["tess"],
                  rss["tess4x"] / rss["tess"] <= 1.1 ? "MET (<= 1.10)" : "NOT MET (> 1.10)"
    }' "$scratch/verdicts"
}

main() {
  echo "bench/areas.sh $(date -u +%Y-%m-%dT%H:%MZ), commit $(git rev-parse --short HEAD 2>/dev/null || echo ?)," \
    "$(nproc) threads, fastest (least CPU) of $runs, $("$tippecanoe" --version 2>&1 | head -1)"
  inputs
  rm -f "$scratch/verdicts"
  local names=(world_dense tess)
  [ "$quick" = quick ] || names+=(tess4x)
  for n in "${names[@]}"; do
    measure "$n"
    report "$n"
  done
  echo "CPU/tc, /tc-sb: CPU seconds / tippecanoe's, / tippecanoe --detect-shared-borders'; RSS: peak of the runs"
  verdicts
  for n in world_dense tess; do per_zoom "$n"; done
}

main 2>&1 | tee "$latest.part"
mv "$latest.part" "$latest"
