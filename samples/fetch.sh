#!/usr/bin/env bash
# Fetches the real sample datasets (see samples/README.md) from Debian packages
# with `apt-get download`, without installing those packages. The downloads are
# cached in ~/.cache/globe-samples ($GLOBE_SAMPLES_CACHE), the files under
# samples/data/ (git-ignored), checked against samples/checksums.sha256.
# Formats GDAL cannot read directly are described by GDAL VRTs and converted to
# GeoTIFF (jacksboro .npz, brasilia raw Float32).
#
# Usage: samples/fetch.sh [small|all]    (default: small, used by the tests)
#   small: lux, olinda, jacksboro, brasilia, etopo20 (DEMs, ~3 MB of packages) and
#          ne_admin1, canada_roads, os_wales, efas_rivers (lines, ~35 MB of packages) and
#          landsat, cbers20, bluemarble (imagery, +15 MB) and
#          world, nc (polygons: countries and counties, +4 MB of packages) and
#          us_flights (npm vega-datasets: airports, routes; points per airport, +18 MB) and
#          airways and world_airports (FlightGear's airway network and navaids, two
#          files of 1.7 and 0.7 MB streamed out of flightgear-data-base, converted to
#          GeoJSON lines and a CSV of the airports with an ILS)
#   all:   small + nothing else yet (the benchmarks synthesize larger DEMs)
# Exit codes: 0 ok, 1 a download/checksum/conversion failed, 2 usage error.
set -euo pipefail

tier=${1:-small}
case "$tier" in small|all) ;; *) echo "usage: $0 [small|all]" >&2; exit 2;; esac

here=$(cd "$(dirname "$0")" && pwd)
data="$here/data"
# What is downloaded (packages, npm tarballs, members streamed out of a
# package) is kept outside the clone: a second clone on the same machine
# extracts and converts again without downloading (docs/ci.md, "Warm").
debs="${GLOBE_SAMPLES_CACHE:-${HOME:-/tmp}/.cache/globe-samples}"
mkdir -p "$data" "$debs"

# id | package | path inside the package | output name
small_sets=(
  "lux|r-cran-terra|usr/lib/R/site-library/terra/ex/elev.tif|lux.tif"
  "olinda|r-cran-stars|usr/lib/R/site-library/stars/tif/olinda_dem_utm25s.tif|olinda.tif"
  "jacksboro|python-matplotlib-data|usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz|jacksboro.npz"
  "brasilia|libterralib-doc|usr/share/doc/libterralib-dev/examples/data/elevation.raw|brasilia.raw"
  "etopo20|ferret-datasets|usr/share/ferret-vis/data/etopo20.cdf|etopo20.cdf"
)

# Line data (shapefiles: every part is its own entry).
ne=usr/share/magics/10m/ne_10m_admin_1_states_provinces_lines
roads=usr/share/doc/mapnik-doc/examples/data/roads
contours=usr/share/plplot5.15.0/ss/ss64ne_Height_Contours
efas=usr/share/magics/efas/ExtendedDomain/lines
line_sets=()
for ext in shp shx dbf; do
  line_sets+=("canada_roads|mapnik-doc|$roads.$ext|canada_roads.$ext")
done
for ext in shp shx dbf prj; do
  line_sets+=("ne_admin1|libmagics++-data|$ne.$ext|ne_admin1.$ext")
  line_sets+=("os_wales|libplplot-data|$contours.$ext|os_wales_contours.$ext"
              "efas_rivers|libmagics++-data|$efas.$ext|efas_rivers.$ext")
done
small_sets+=("${line_sets[@]}")
# Polygons (areas, choropleths): the world's countries (spData, CC0) and North
# Carolina's counties (sf's nc.gpkg, NAD27).
small_sets+=(
  "world|r-cran-spdata|usr/lib/R/site-library/spData/shapes/world.gpkg|world.gpkg"
  "nc|r-cran-sf|usr/lib/R/site-library/sf/gpkg/nc.gpkg|nc.gpkg"
)
# Imagery.
small_sets+=(
  "landsat|r-cran-stars|usr/lib/R/site-library/stars/tif/L7_ETMs.tif|landsat.tif"
  "cbers20|libterralib-doc|usr/share/doc/libterralib-dev/examples/image_processing/resources/cbers_rgb342_crop1.tif|cbers20.tif"
  "bluemarble|marble-qt-data|usr/share/marble/data/maps/earth/bluemarble/bluemarble.jpg|bluemarble.jpg"
)

apt_updated=0
fetch_package() { # package -> path of the .deb in $debs
  local pkg=$1 deb
  deb=$(ls "$debs/${pkg}"_*.deb 2>/dev/null | head -n 1 || true)
  if [ -z "$deb" ]; then
    if [ $apt_updated = 0 ] && [ -z "$(ls /var/lib/apt/lists/ 2>/dev/null | grep -v lock | head -n 1)" ]; then
      apt-get update -qq; apt_updated=1
    fi
    echo "fetch: downloading $pkg" >&2
    (cd "$debs" && apt-get download -qq "$pkg" 2>/dev/null) || {
      if [ $apt_updated = 0 ]; then apt-get update -qq; apt_updated=1; (cd "$debs" && apt-get download -qq "$pkg" 2>/dev/null); else return 1; fi
    }
    deb=$(ls "$debs/${pkg}"_*.deb | head -n 1)
  fi
  echo "$deb"
}

extract_file() { # package, inner path, output name
  local pkg=$1 inner=$2 out=$3 deb tmp
  [ -f "$data/$out" ] && return 0
  deb=$(fetch_package "$pkg")
  tmp=$(mktemp -d)
  dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$tmp" "./$inner"
  mv "$tmp/$inner" "$data/$out.part" && mv "$data/$out.part" "$data/$out"
  rm -rf "$tmp"
}

for entry in "${small_sets[@]}"; do
  IFS='|' read -r id pkg inner out <<<"$entry"
  extract_file "$pkg" "$inner" "$out"
done

# npm packages: the registry's tarball (https://registry.npmjs.org), members
# taken out of it like those of the Debian packages.
npm_member() { # package version inner output
  local pkg=$1 ver=$2 inner=$3 out=$4 tgz
  [ -f "$data/$out" ] && return 0
  tgz="$debs/$pkg-$ver.tgz"
  if [ ! -f "$tgz" ]; then
    echo "fetch: downloading npm $pkg@$ver" >&2
    curl -fsSL --retry 3 -o "$tgz.part" "https://registry.npmjs.org/$pkg/-/$pkg-$ver.tgz"
    mv "$tgz.part" "$tgz"
  fi
  tar -xzf "$tgz" -O "package/$inner" >"$data/$out.part"
  mv "$data/$out.part" "$data/$out"
}
npm_member vega-datasets 3.2.1 data/airports.csv us_airports.csv
npm_member vega-datasets 3.2.1 data/flights-airport.csv us_flights_airport.csv

# us_airport_flights: departures per airport by the census region flown to
# (a multi-valued point set for charts).
if [ ! -f "$data/us_airport_flights.csv" ]; then
  python3 "$here/us_flights_by_region.py" "$data/us_airports.csv" "$data/us_flights_airport.csv" \
    >"$data/us_airport_flights.csv.part"
  mv "$data/us_airport_flights.csv.part" "$data/us_airport_flights.csv"
fi

# airways: FlightGear's airway segments (Navaids/awy.dat.gz) and navaids
# (Navaids/nav.dat.gz, whose ILS entries place the world's larger airports)
# out of flightgear-data-base, a package of about 1 GB: its data.tar.xz is
# streamed until tar has found both files (the first part of it), not
# downloaded whole.
stream_deb_members() { # package inner-path:output...
  local pkg=$1 uri tmp spec missing=() inners=()
  shift
  for spec in "$@"; do
    [ -f "$data/${spec#*:}" ] && continue
    if [ -s "$debs/${spec#*:}" ]; then
      cp "$debs/${spec#*:}" "$data/${spec#*:}"
    else
      missing+=("$spec")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ $apt_updated = 0 ] && [ -z "$(ls /var/lib/apt/lists/ 2>/dev/null | grep -v lock | head -n 1)" ]; then
    apt-get update -qq; apt_updated=1
  fi
  uri=$(apt-get download --print-uris "$pkg" 2>/dev/null | awk '{print $1}' | tr -d "'")
  [ -n "$uri" ] || { echo "fetch: no download address for $pkg (apt-get update?)" >&2; return 1; }
  for spec in "${missing[@]}"; do inners+=("./${spec%%:*}"); done
  echo "fetch: streaming ${inners[*]} out of $pkg" >&2
  tmp=$(mktemp -d)
  # The pipeline ends early on purpose (tar stops once it has every file):
  # judge it by its output, not its status.
  (set +o pipefail; curl -fsL --retry 3 "$uri" | python3 "$here/deb_member.py" data.tar.xz |
    xz -dc 2>/dev/null | tar -x -C "$tmp" --occurrence=1 "${inners[@]}" 2>/dev/null) || true
  for spec in "${missing[@]}"; do
    [ -s "$tmp/${spec%%:*}" ] || { echo "fetch: could not take ${spec%%:*} out of $pkg" >&2; rm -rf "$tmp"; return 1; }
    cp "$tmp/${spec%%:*}" "$debs/${spec#*:}"
    mv "$tmp/${spec%%:*}" "$data/${spec#*:}"
  done
  rm -rf "$tmp"
}
stream_deb_members flightgear-data-base \
  usr/share/games/flightgear/Navaids/awy.dat.gz:flightgear_awy.dat.gz \
  usr/share/games/flightgear/Navaids/nav.dat.gz:flightgear_nav.dat.gz
if [ ! -f "$data/airways.geojson" ]; then
  python3 "$here/airways_geojson.py" "$data/flightgear_awy.dat.gz" >"$data/airways.geojson.part"
  mv "$data/airways.geojson.part" "$data/airways.geojson"
fi
# world_airports: the airports with instrument landing systems, one row each
# (ICAO code, the mean position of its ILS localizers, how many runways have one).
if [ ! -f "$data/world_airports.csv" ]; then
  python3 "$here/ils_airports.py" "$data/flightgear_nav.dat.gz" >"$data/world_airports.csv.part"
  mv "$data/world_airports.csv.part" "$data/world_airports.csv"
fi

# Writes a GDAL VRT describing a headerless raster file.
# raw_vrt OUT.vrt FILE COLS ROWS TYPE BYTES_PER_PIXEL OFFSET SRS "GEOTRANSFORM"
raw_vrt() {
  cat > "$1" <<VRT
<VRTDataset rasterXSize="$3" rasterYSize="$4">
  <SRS>$8</SRS>
  <GeoTransform>$9</GeoTransform>
  <VRTRasterBand dataType="$5" band="1" subClass="VRTRawRasterBand">
    <SourceFilename relativeToVRT="0">$2</SourceFilename>
    <ImageOffset>$7</ImageOffset><PixelOffset>$6</PixelOffset><LineOffset>$(($3 * $6))</LineOffset>
    <ByteOrder>LSB</ByteOrder>
  </VRTRasterBand>
</VRTDataset>
VRT
}

# jacksboro: .npz is a zip holding elevation.npy (Int16, C order). GDAL reads the
# extracted .npy through a raw VRT; the .npy header length gives the offset.
if [ ! -f "$data/jacksboro.tif" ]; then
  npy=elevation.npy
  unzip -o -q "$data/jacksboro.npz" "$npy" -d "$data/jacksboro.d"
  raw="$data/jacksboro.d/$npy"
  hdr=$(od -An -tu1 -N2 -j8 "$raw" | awk '{print $1 + 256*$2 + 10}')
  shape=$(head -c "$hdr" "$raw" | LC_ALL=C tr -d "\000" | LC_ALL=C sed -n "s/.*'shape': *(\([0-9]*\), *\([0-9]*\)).*/\1 \2/p")
  read -r rows cols <<<"$shape"
  raw_vrt "$data/jacksboro.vrt" "$raw" "$cols" "$rows" Int16 2 "$hdr" EPSG:4269 \
    "-84.41375, 0.000833333333333333, 0, 36.73292, 0, -0.000833333333333333"
  gdal_translate -q -co COMPRESS=DEFLATE "$data/jacksboro.vrt" "$data/jacksboro.tif.part.tif"
  mv "$data/jacksboro.tif.part.tif" "$data/jacksboro.tif"
fi

# brasilia: 382 x 422 little-endian Float32, north-up rows, 30 m pixels,
# UTM 23S on SAD69 (EPSG:29193), lower-left corner 183557 E, 8246277 N.
if [ ! -f "$data/brasilia.tif" ]; then
  cols=382 rows=422
  raw_vrt "$data/brasilia.vrt" "$data/brasilia.raw" "$cols" "$rows" Float32 4 0 EPSG:29193 \
    "183557, 30, 0, $((8246277 + rows * 30)), 0, -30"
  gdal_translate -q -co COMPRESS=DEFLATE "$data/brasilia.vrt" "$data/brasilia.tif.part.tif"
  mv "$data/brasilia.tif.part.tif" "$data/brasilia.tif"
fi

# etopo20: netCDF (lon 0..360). GeoTIFF keeps the georeferencing explicit.
if [ ! -f "$data/etopo20.tif" ]; then
  gdal_translate -q -a_srs EPSG:4326 -co COMPRESS=DEFLATE "$data/etopo20.cdf" "$data/etopo20.tif.part.tif"
  mv "$data/etopo20.tif.part.tif" "$data/etopo20.tif"
fi

# bluemarble: a plate carree JPEG without georeference; it spans the globe.
if [ ! -f "$data/bluemarble.tif" ]; then
  gdal_translate -q -a_srs EPSG:4326 -a_ullr -180 90 180 -90 -co COMPRESS=DEFLATE -co TILED=YES \
    "$data/bluemarble.jpg" "$data/bluemarble.tif.part.tif"
  mv "$data/bluemarble.tif.part.tif" "$data/bluemarble.tif"
fi

# Checksums of the fetched originals (the converted files are derived).
if [ -f "$here/checksums.sha256" ]; then
  (cd "$data" && sha256sum --quiet -c "$here/checksums.sha256") || {
    echo "fetch: checksum mismatch in $data; delete it and run again" >&2; exit 1; }
fi
echo "fetch: samples ready in $data ($tier tier)" >&2
