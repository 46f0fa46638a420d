#!/usr/bin/env bash
# Builds cesium-terrain-builder's ctb-tile (the quantized-mesh peer of our terrain
# tiler) into bench/scratch/ctb/.
#
# Quantized-mesh output (`ctb-tile -f Mesh`) exists only in ahuarte47's fork, branch
# master-quantized-mesh; geo-data/cesium-terrain-builder makes heightmap tiles only.
# Neither Debian nor npm packages it, so we build it from source with Debian 12's
# GDAL 3.6, which needs bench/ctb/gdal36.patch (two GDAL API changes, see its header).
# The source comes from the local snapshot git dir (/work/.mirror/..., or $CTB_GITDIR)
# when there is one, else from a shallow clone of the branch. The build is cmake
# Release at -O2; libctb.so stays in the build tree and a wrapper script points
# LD_LIBRARY_PATH at it. Notes on options and defaults: bench/ctb/NOTES.md.
#
# Usage: bench/fetch_ctb.sh        prints the absolute path of a runnable ctb-tile wrapper
#   env: CTB_GITDIR (snapshot git dir), CTB_REF (commit or branch to build)
set -euo pipefail
cd "$(dirname "$0")/.."
dir=bench/scratch/ctb
wrapper="$dir/ctb-tile"
if [ -x "$wrapper" ] && "$wrapper" --version >/dev/null 2>&1; then
  echo "fetch_ctb: already built ($(cat "$dir/COMMIT" 2>/dev/null || echo '?'))" >&2
  echo "$(pwd)/$wrapper"; exit 0
fi

branch=master-quantized-mesh
ref=${CTB_REF:-7006484800d57dae846d0bcf139b6c1a7a1a8f1e}   # tip of $branch, 2023-03-05
gitdir=${CTB_GITDIR:-/work/.mirror/ahuarte47+cesium-terrain-builder/repo}
patchfile=bench/ctb/gdal36.patch

# Build dependencies, installed only when missing.
missing=()
for pkg in g++ make cmake libgdal-dev zlib1g-dev git patch ca-certificates; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo=; [ "$(id -u)" -eq 0 ] || sudo=sudo
  echo "fetch_ctb: installing ${missing[*]}" >&2
  $sudo apt-get update >&2
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y --no-install-recommends "${missing[@]}" >&2
fi

# Source, fresh each time the wrapper is missing, then patched.
rm -rf "$dir/src" "$dir/src.part"
mkdir -p "$dir/src.part"
if git --git-dir="$gitdir" rev-parse --verify -q "$ref^{commit}" >/dev/null 2>&1; then
  commit=$(git --git-dir="$gitdir" rev-parse "$ref^{commit}")
  echo "fetch_ctb: source $commit from $gitdir" >&2
  git --git-dir="$gitdir" archive "$commit" | tar -x -C "$dir/src.part"
else
  echo "fetch_ctb: no $ref in ${gitdir}; cloning $branch" >&2
  rm -rf "$dir/src.part"
  git clone -q --depth 1 -b "$branch" https://github.com/ahuarte47/cesium-terrain-builder "$dir/src.part" >&2
  commit=$(git -C "$dir/src.part" rev-parse HEAD)
  [ "$commit" = "$ref" ] || echo "fetch_ctb: warning: cloned $commit, not $ref; the patch may not apply" >&2
fi
patch -d "$dir/src.part" -p1 --forward -s < "$patchfile" >&2
mv "$dir/src.part" "$dir/src"

# Build (Release at -O2, as our own benchmarks are built).
cmake -S "$dir/src" -B "$dir/build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O2 -DNDEBUG" -DCMAKE_C_FLAGS_RELEASE="-O2 -DNDEBUG" >&2
cmake --build "$dir/build" -j"$(nproc)" >&2
echo "$commit" > "$dir/COMMIT"

# libctb.so lives in build/src; the wrapper finds it relative to itself.
cat > "$wrapper" <<'WRAP'
#!/bin/sh
# ctb-tile from cesium-terrain-builder (ahuarte47, master-quantized-mesh), built by bench/fetch_ctb.sh.
here=$(dirname "$(readlink -f "$0")")
LD_LIBRARY_PATH="$here/build/src${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/build/tools/ctb-tile" "$@"
WRAP
chmod +x "$wrapper"
echo "fetch_ctb: built ctb-tile $("$wrapper" --version) from $commit" >&2
echo "$(pwd)/$wrapper"
