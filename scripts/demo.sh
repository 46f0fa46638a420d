#!/usr/bin/env bash
# The main job on real data, from a fresh Debian 12 machine: installs what is
# missing, builds, fetches the sample DEMs, tiles one into a terrain package
# prints its summary and renders a headless snapshot (OSMesa, no display needed).
# Output: demo/jacksboro.mbtiles and demo/jacksboro.png (git-ignored).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
samples/fetch.sh small
mkdir -p demo
build/tools/tiler/globe-tiler terrain samples/data/jacksboro.tif -o demo/jacksboro.mbtiles --force
build/tools/tiler/globe-tiler validate demo/jacksboro.mbtiles
build/tools/tiler/globe-tiler info demo/jacksboro.mbtiles
build/viewer/globe-view demo/jacksboro.mbtiles --snapshot demo/jacksboro.png --size 1280x720 \
  --camera=-84.30,36.55,2500,30,65 --shading elevation --stats
echo "demo: wrote demo/jacksboro.png" >&2
