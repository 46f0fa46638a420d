#!/usr/bin/env bash
# Configures and builds the project into build/ (or $BUILD_DIR), through the
# compiler cache where ccache is installed (scripts/lib/ccache.sh).
# Usage: scripts/build.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/lib/ccache.sh
build=${BUILD_DIR:-build}
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGLOBE_WERROR=$werror \
  "${GLOBE_CCACHE_ARGS[@]}" "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
