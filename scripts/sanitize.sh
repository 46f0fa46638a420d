#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/
# and runs the unit and cli tests there (the codec's truncated-prefix and
# corruption tests are the point). Usage: scripts/sanitize.sh [ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=build-asan scripts/build.sh -DGLOBE_SANITIZE=address,undefined
cd build-asan
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j "$(nproc)" -L "unit|cli" "$@"
