#!/usr/bin/env bash
# Self-test of the real-browser harness: its server and driver (harness.mjs), then
# MapLibre GL JS 3D terrain from a generated Terrarium tile set (elevations checked
# against the analytic surface) and a CesiumJS globe, both with WebGL in headless
# chromium. Installs what is missing (scripts/web-deps.sh); works from any directory.
# Usage: tests/web/selftest/run.sh [OUTDIR]   (OUTDIR keeps the JSON results and screenshots)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
web=$(dirname "$here")
GLOBE_WEB_CACHE=$("$web/../../scripts/web-deps.sh")
export GLOBE_WEB_CACHE
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
out=${1:-$tmp}
mkdir -p "$out"

passed=0 failed=0
step() { # name command...: runs and times one step
  local name=$1 t0=$SECONDS; shift
  if "$@"; then passed=$((passed + 1)); echo "selftest: $name ok ($((SECONDS - t0)) s)" >&2
  else failed=$((failed + 1)); echo "selftest: $name FAILED ($((SECONDS - t0)) s)" >&2; fi
}
harness() { node "$here/harness.mjs" >&2; }
maplibre() {
  node "$here/terrarium.mjs" write "$tmp/terrarium" &&
  node "$web/run_page.mjs" --mount "/data=$tmp/terrarium" --timeout 45 \
      --screenshot "$out/maplibre.png" "$here/maplibre.html" > "$out/maplibre.json" &&
  node "$here/terrarium.mjs" check < "$out/maplibre.json" >&2
}
cesium() {
  node "$web/run_page.mjs" --timeout 45 --screenshot "$out/cesium.png" "$here/cesium.html" > "$out/cesium.json"
}

t0=$SECONDS
step harness harness
step maplibre-terrarium maplibre
step cesium-globe cesium
echo "selftest: total $((SECONDS - t0)) s${1:+, results in $out}" >&2
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
