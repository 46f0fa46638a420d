#!/usr/bin/env bash
# Fetches rio-rgbify (mapbox/rio-rgbify, the peer of `globe-tiler export --format terrain-rgb`)
# into bench/scratch/rio-rgbify/ and prints the path of a wrapper that runs `rio rgbify`.
#
# rio-rgbify is a plugin of rasterio's `rio` CLI (entry point group rasterio.rio_plugins). Debian 12
# packages rasterio 1.3.5 (python3-rasterio; its `rio` CLI is package rasterio's /usr/bin/rasterio,
# renamed for a clash with another `rio`), click and Pillow, but neither rio-rgbify nor its
# pure-Python dependencies mercantile and rio-mucho, and the machines have no PyPI. So we install
# only the Debian packages and take the three pure-Python sources from their GitHub snapshots
# (/work/.mirror/<owner>+<name>/repo when the `fetch` tool has brought them, else
# `git clone --depth 1`), copy the packages into bench/scratch/rio-rgbify/site/ and give each a
# minimal .dist-info (METADATA; rio-rgbify's also its entry_points.txt, taken from its setup.py).
# With site/ first on sys.path, Debian's own `rio` (rasterio.rio.main:main_group, /usr/bin/rasterio)
# finds the plugin through its entry point as after `pip install rio-rgbify`; nothing is
# pip-installed. One patch for rasterio 1.3, see below. (bench/rio_rgbify/NOTES.md)
#
# Usage: bench/fetch_rio_rgbify.sh        prints the path of a runnable wrapper; then
#        WRAPPER SRC.tif OUT.mbtiles -b -10000 -i 0.1 --min-z 0 --max-z 12 -j 2 --format png
#        (the wrapper takes the arguments of `rio rgbify`)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=bench/scratch/rio-rgbify
wrapper="$dir/rio-rgbify"
say() { echo "fetch_rio_rgbify: $*" >&2; }
check() { [ -x "$wrapper" ] && "$wrapper" --help 2>/dev/null | grep -q -- '--base-val'; }
if check; then echo "$(cd "$dir" && pwd)/rio-rgbify"; exit 0; fi

# Debian packages: rasterio (the `rio` CLI, as /usr/bin/rasterio) and python3-rasterio (+ click,
# click-plugins, cligj, affine, snuggs), Pillow (webp output, and decoding tiles in checks); sqlite3
# is in the standard library.
missing=()
for pkg in rasterio python3-rasterio python3-pil python3-click python3-numpy; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  say "installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends "${missing[@]}" >&2 ||
    { apt-get update >&2 && apt-get install -y --no-install-recommends "${missing[@]}" >&2; }
fi

# Sources: owner/name, python package directory, distribution name, version.
mkdir -p "$dir/src" "$dir/site"
: > "$dir/COMMITS.part"
while read -r repo pkgdir dist version; do
  name=${repo#*/}
  src="$dir/src/$name"
  mirror="/work/.mirror/${repo/\//+}/repo"
  if [ -d "$mirror" ]; then
    commit=$(git --git-dir="$mirror" rev-parse HEAD)
    if [ "$(cat "$src/.commit" 2>/dev/null)" != "$commit" ]; then
      say "extracting $repo $commit from $mirror"
      rm -rf "$src" && mkdir -p "$src"
      git --git-dir="$mirror" archive HEAD | tar -x -C "$src"
      echo "$commit" > "$src/.commit"
    fi
  elif [ ! -s "$src/.commit" ]; then
    say "cloning https://github.com/$repo"
    rm -rf "$src" "$src.git"
    git clone -q --depth 1 "https://github.com/$repo" "$src.git" >&2
    commit=$(git -C "$src.git" rev-parse HEAD)
    mkdir -p "$src" && git -C "$src.git" archive HEAD | tar -x -C "$src"
    rm -rf "$src.git"
    echo "$commit" > "$src/.commit"
  fi
  commit=$(cat "$src/.commit")
  echo "$repo $commit" >> "$dir/COMMITS.part"
  rm -rf "$dir/site/$pkgdir" "$dir/site/$dist"-*.dist-info
  cp -r "$src/$pkgdir" "$dir/site/$pkgdir"
  info="$dir/site/$dist-$version.dist-info"
  mkdir -p "$info"
  printf 'Metadata-Version: 2.1\nName: %s\nVersion: %s\nSummary: github.com/%s %s\n' \
    "$dist" "$version" "$repo" "$commit" > "$info/METADATA"
  if [ "$name" = rio-rgbify ]; then
    # the [rasterio.rio_plugins] entry point of its setup.py
    ep=$(sed -n '/\[rasterio.rio_plugins\]/,/"""/p' "$src/setup.py" |
      sed -n 's/^ *\(rgbify *= *[A-Za-z_.:]*\).*/\1/p')
    [ -n "$ep" ] || { say "no rgbify entry point in $src/setup.py"; exit 1; }
    printf '[rasterio.rio_plugins]\n%s\n' "$ep" > "$info/entry_points.txt"
  fi
done <<'LIST'
mapbox/rio-rgbify rio_rgbify rio_rgbify 0.4.0
mapbox/mercantile mercantile mercantile 1.2.1
mapbox/rio-mucho riomucho rio_mucho 1.0.0
LIST
mv "$dir/COMMITS.part" "$dir/COMMITS"

site=$(cd "$dir/site" && pwd)
# The wrapper is Debian's `rio` (/usr/bin/rasterio: rasterio.rio.main:main_group) with site/ first
# on sys.path, so the rgbify entry point is found as if installed, plus one patch: rio-rgbify 0.4.0
# calls transform_bounds(..., densify_pts=0) (rio_rgbify/mbtiler.py:195), which rasterio >= 1.3
# with GDAL >= 3.4 refuses for every input ("densify_pts must be at least 2 if the output is
# geograpic", mapbox/rio-rgbify#39, open); its users patch it to 2, as the issue shows; so do we.
# Same tiles: densifying a lon/lat box into lon/lat moves no corner.
cat > "$wrapper.part" <<WRAP
#!/usr/bin/python3
# \`rio rgbify\` from Debian's rasterio, with rio-rgbify, mercantile and rio-mucho from their GitHub
# sources in $site (bench/fetch_rio_rgbify.sh; commits in $(cd "$dir" && pwd)/COMMITS).
import sys
sys.path.insert(0, "$site")
import rio_rgbify.mbtiler
from rasterio.warp import transform_bounds

def _transform_bounds(*args, **kwargs):  # mapbox/rio-rgbify#39: densify_pts=0 -> 2
    if kwargs.get("densify_pts") == 0:
        kwargs["densify_pts"] = 2
    return transform_bounds(*args, **kwargs)

rio_rgbify.mbtiler.transform_bounds = _transform_bounds
from rasterio.rio.main import main_group
sys.argv[:1] = ["rio", "rgbify"]
sys.exit(main_group())
WRAP
chmod +x "$wrapper.part"
"$wrapper.part" --help >/dev/null || { say "the wrapper does not run: $wrapper.part"; exit 1; }
# smoke test: a 4 x 4 lon/lat grid of heights 0..15 m -> one zoom-0 tile
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -c '
import sys, numpy as np, rasterio
from rasterio.transform import from_origin
with rasterio.open(sys.argv[1], "w", driver="GTiff", width=4, height=4, count=1, dtype="float32",
                   crs="EPSG:4326", transform=from_origin(10, 50, 1, 1)) as d:
    d.write(np.arange(16, dtype="float32").reshape(1, 4, 4))' "$tmp/smoke.tif"
"$wrapper.part" -b -10000 -i 0.1 --min-z 0 --max-z 0 -j 1 "$tmp/smoke.tif" "$tmp/smoke.mbtiles" \
  > "$tmp/log" 2>&1 || { cat "$tmp/log" >&2; say "smoke test failed"; exit 1; }
n=$(/usr/bin/python3 -c 'import sqlite3, sys
db = sqlite3.connect(sys.argv[1])
print(db.execute("select count(*) from tiles").fetchone()[0])' "$tmp/smoke.mbtiles")
[ "$n" = 1 ] || { say "smoke test wrote $n tiles, expected 1"; exit 1; }
mv "$wrapper.part" "$wrapper"
sed 's/^/fetch_rio_rgbify: /' "$dir/COMMITS" >&2
echo "$(cd "$dir" && pwd)/rio-rgbify"
