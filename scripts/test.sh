#!/usr/bin/env bash
# Installs what is missing, builds, fetches the sample data and runs the test
# suite but the tests labelled slow (kill-and-resume, browsers, Slurm, windows
# under xvfb, the largest real datasets, sharded merges: docs/ci.md), which
# CI runs as a stage of its own (.ci/run). Usage:
#   scripts/test.sh            # the suite without the slow label
#   scripts/test.sh --all      # every test
#   scripts/test.sh -L unit    # other arguments go to ctest instead
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/stage.sh
. scripts/lib/ctest_costs.sh
selection=(-LE slow)
if [ "${1:-}" = "--all" ]; then
  selection=()
  shift
elif [ $# -gt 0 ]; then
  selection=()
fi
stage "install" scripts/install-deps.sh
stage "build (build/)" scripts/build.sh
stage "samples" samples/fetch.sh small
seed_ctest_costs build
cd build
stage "tests (build/)" ctest --output-on-failure -j "$(nproc)" "${selection[@]}" "$@"
