#!/usr/bin/env bash
# Regenerates the expected images of tests/viewer_cli_test.cpp from the
# current build (review them before committing!). Needs samples/fetch.sh.
set -euo pipefail
cd "$(dirname "$0")/../../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/tools/tiler/globe-tiler terrain -q samples/data/jacksboro.tif -o "$tmp/j.mbtiles"
out=tests/data/render
build/viewer/globe-view "$tmp/j.mbtiles" --snapshot $out/jacksboro_hillshade.png --size 320x180 \
  --camera=-84.30,36.55,2500,30,65
for mode in elevation slope aspect; do
  build/viewer/globe-view "$tmp/j.mbtiles" --snapshot $out/jacksboro_fit_$mode.png --size 320x180 \
    --fit --shading $mode
done
ls -l $out/*.png
