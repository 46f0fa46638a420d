#!/usr/bin/env bash
# Line vectorizer benchmarks, taken side by side in one run (bench/README.md "Lines").
#   1. CPU time (user + sys) of `globe-vectorize lines` vs tippecanoe and vs
#      `ogr2ogr -f MBTILES` on the same lines and zoom range; goal <= 0.5 of the
#      faster peer. Peers get no tile size or feature limits (they drop nothing,
#      like us). tippecanoe reads GeoJSON only: the shapefile -> GeoJSONSeq
#      conversion is timed separately and not charged to it.
#   2. segments written per CPU second, package size.
#   3. memory: peak RSS on efas_rivers vs a synthetic set with 10x its vertices.
# Usage: bench/lines.sh [quick]   (quick: skip ogr2ogr on efas (minutes) and the 10x set)
# Needs: scripts/build.sh done, samples/fetch.sh done. Scratch: bench/scratch/.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=${1:-}
vec=build/tools/vectorize/globe-vectorize
gen=build/bench/make_synthetic_lines
scratch=bench/scratch
data=samples/data
mkdir -p "$scratch"
tippecanoe=$(bench/fetch_tippecanoe.sh)
threads=$(nproc)

cpu() { /usr/bin/time -f "%U %S %e %M" "$@" 2>&1 >/dev/null | tail -1 | awk '{ printf "%.2f %.2f %.0f\n", $1 + $2, $3, $4 / 1024 }'; }  # "cpu_s wall_s rss_mb"

row() { # name input zmax [our options...]
  local name=$1 input=$2 zmax=$3; shift 3
  local ours="$scratch/$name.globe.mbtiles" tip="$scratch/$name.tippecanoe.mbtiles" ogr="$scratch/$name.ogr.mbtiles"
  local geojson="$scratch/$name.geojsons" s_srs=()
  for a in "$@"; do [ "${prev:-}" = --s_srs ] && s_srs=(-s_srs "$a"); prev=$a; done
  read -r c_ours w_ours m_ours <<<"$(cpu "$vec" lines "$input" -o "$ours" --force -q -j "$threads" --min-zoom 0 --max-zoom "$zmax" "$@")"
  rm -f "$geojson"
  read -r c_conv _ _ <<<"$(cpu ogr2ogr -f GeoJSONSeq -t_srs EPSG:4326 "${s_srs[@]}" "$geojson" "$input")"
  read -r c_tip w_tip m_tip <<<"$(cpu "$tippecanoe" -o "$tip" --force -q -P -Z0 -z"$zmax" \
    --no-feature-limit --no-tile-size-limit -l lines "$geojson")"
  local c_ogr=nan w_ogr=nan m_ogr=nan ogr_bytes=0
  if [ "$quick" != quick ] || [ "$name" != efas_rivers ]; then
    rm -f "$ogr"
    read -r c_ogr w_ogr m_ogr <<<"$(cpu ogr2ogr -f MBTILES "${s_srs[@]}" -t_srs EPSG:3857 "$ogr" "$input" -dsco MINZOOM=0 \
      -dsco MAXZOOM="$zmax" -dsco MAX_SIZE=100000000 -dsco MAX_FEATURES=100000000)"
    ogr_bytes=$(stat -c %s "$ogr")
  fi
  local segs
  segs=$("$vec" info "$ours" | awk '/^lines per zoom/ { on = 1; next } on && NF == 6 && $1 ~ /^[0-9]+$/ { s += $2 } END { print s }')
  awk -v n="$name" -v z="$zmax" -v co="$c_ours" -v ct="$c_tip" -v cg="$c_ogr" -v cc="$c_conv" \
      -v wo="$w_ours" -v mo="$m_ours" -v mt="$m_tip" -v s="$segs" \
      -v bo="$(stat -c %s "$ours")" -v bt="$(stat -c %s "$tip")" -v bg="$ogr_bytes" '
    BEGIN {
      best = (cg != "nan" && cg < ct) ? cg : ct
      printf "%-13s z0-%-2d cpu s: ours %7.2f  tippecanoe %7.2f (+%.2f GeoJSON)  ogr2ogr %8s | ratio vs faster peer %.2f (goal <= 0.5)\n",
             n, z, co, ct, cc, cg, co / best
      printf "%-13s       wall %.2f s, %.0f segments/cpu-s, rss ours %d MB tippecanoe %d MB | bytes ours %d tippecanoe %d ogr2ogr %d\n",
             "", wo, s / co, mo, mt, bo, bt, bg
    }'
}

echo "globe-vectorize vs tippecanoe $("$tippecanoe" --version 2>&1 | head -1) vs $(ogr2ogr --version | cut -d, -f1); $threads threads"
row canada_roads "$data/canada_roads.shp" 10 --s_srs EPSG:3978
row ne_admin1 "$data/ne_admin1.shp" 9
row efas_rivers "$data/efas_rivers.shp" 7

if [ "$quick" != quick ]; then
  [ -f "$scratch/synth10x.fgb" ] || "$gen" 1190000 10 "$scratch/synth10x.fgb"
  read -r _ _ m1 <<<"$(cpu "$vec" lines "$data/efas_rivers.shp" -o "$scratch/m1.mbtiles" --force -q --max-zoom 7)"
  read -r _ _ m10 <<<"$(cpu "$vec" lines "$scratch/synth10x.fgb" -o "$scratch/m10.mbtiles" --force -q --max-zoom 7)"
  awk -v a="$m1" -v b="$m10" 'BEGIN { printf "memory: peak RSS efas_rivers (1.19 M vertices) %d MB, synthetic (11.9 M vertices) %d MB: ratio %.2f for 10x the input\n", a, b, b / a }'
fi
