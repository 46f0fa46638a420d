#!/usr/bin/env bash
# Builds with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/
# and runs the whole test suite there (every label: unit, cli, real, render,
# slow). Leaks are reported, except Mesa's own (scripts/lsan.supp says why).
# Needs the samples (scripts/test.sh fetches them).
# Usage: scripts/sanitize.sh [ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=build-asan scripts/build.sh -DGLOBE_SANITIZE=address,undefined
supp=$(pwd)/scripts/lsan.supp
cd build-asan
ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$supp:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j "$(nproc)" --timeout 1500 "$@"
