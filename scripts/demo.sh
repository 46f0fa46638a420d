#!/usr/bin/env bash
# The main job on real data, from a fresh Debian 12 machine: installs what is
# missing, builds, fetches the sample DEMs, tiles one into a terrain package
# and prints its summary. Output: demo/jacksboro.mbtiles (git-ignored).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
samples/fetch.sh small
mkdir -p demo
build/tools/tiler/globe-tiler terrain samples/data/jacksboro.tif -o demo/jacksboro.mbtiles --force
build/tools/tiler/globe-tiler validate demo/jacksboro.mbtiles
build/tools/tiler/globe-tiler info demo/jacksboro.mbtiles
