#!/usr/bin/env bash
# Installs what the real-browser web tests (tests/web/) need: Debian's chromium
# (and nodejs + npm where node is absent), and pinned npm packages in a cache
# folder outside the repo. Idempotent: a second run does no network work.
# Usage: cache=$(scripts/web-deps.sh)   # the cache path is the last stdout line
# Env:   GLOBE_WEB_CACHE (default ~/.cache/globe-web)
set -euo pipefail

cache="${GLOBE_WEB_CACHE:-$HOME/.cache/globe-web}"
say() { echo "web-deps: $*" >&2; }

# Debian packages, only those missing.
missing=()
[ -x /usr/bin/chromium ] || missing+=(chromium)
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  say "apt-get install ${missing[*]}"
  $sudo apt-get update -qq >&2
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
# playwright-core needs Node >= 20; Debian 12's own nodejs is 18.19.
node_major=$(node -p 'process.versions.node.split(".")[0]')
[ "$node_major" -ge 20 ] || say "warning: node $(node -v) is older than the v20 that playwright-core 1.65 needs"

# npm packages at exact versions. cesium 1.140.0 is the last release whose
# engines field accepts Node 20 (1.141+ require Node >= 22).
mkdir -p "$cache"
manifest='{
  "name": "globe-web-cache",
  "private": true,
  "description": "written by scripts/web-deps.sh; do not edit",
  "dependencies": {
    "playwright-core": "1.65.1",
    "cesium": "1.140.0",
    "maplibre-gl": "6.17.0",
    "pmtiles": "4.5.0"
  }
}'
stamp="$cache/node_modules/.globe-web-stamp"
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$manifest" ] && [ -f "$cache/package-lock.json" ]; then
  say "npm packages up to date in $cache"
else
  printf '%s\n' "$manifest" > "$cache/package.json"
  say "npm install into $cache"
  # The lock file written by the first install is reused from then on.
  (cd "$cache" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm install --no-audit --no-fund \
      --loglevel=error --save-exact >&2)
  printf '%s' "$manifest" > "$stamp"
fi
echo "$cache"
