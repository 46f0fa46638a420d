#!/usr/bin/env bash
# Configures and builds the project into build/ (or $BUILD_DIR).
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLOBE_WERROR=$werror "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
