#!/usr/bin/env bash
# Installs what is missing, builds, fetches the sample data and runs the whole
# test suite (labels: unit, cli, real). Extra arguments go to ctest, e.g.
#   scripts/test.sh -L unit
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
samples/fetch.sh small
cd build
ctest --output-on-failure -j "$(nproc)" "$@"
