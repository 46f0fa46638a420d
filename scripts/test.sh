#!/usr/bin/env bash
# Installs what is missing, builds, fetches the sample data and runs the whole
# test suite (labels: unit, cli, real). Extra arguments go to ctest, e.g.
#   scripts/test.sh -L unit
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/stage.sh
stage "install" scripts/install-deps.sh
stage "build (build/)" scripts/build.sh
stage "samples" samples/fetch.sh small
cd build
stage "tests (build/)" ctest --output-on-failure -j "$(nproc)" "$@"
