#!/usr/bin/env bash
# Writes the hostile-input corpus (docs/robustness.md "Hostile inputs") into
# OUT: rasters and vectors that break the usual assumptions, and packages whose
# tiles are random bytes (made from the valid packages given). Needs python3,
# gdal-bin and sqlite3. Deterministic: the same files every run.
# Usage: make_hostile.sh OUT TERRAIN.mbtiles LINES.mbtiles
set -euo pipefail
out=$1
terrain=$(realpath "$2")
lines=$(realpath "$3")
mkdir -p "$out"
cd "$out"

python3 - <<'PY'
import json, math, random, struct

def envi(name, w, h, values, dtype=4, geo=(-10.0, 10.0, 0.01, 0.01), data_bytes=None):
    """ENVI raster: NAME.raw + NAME.hdr (dtype 4 = float32, 2 = int16)."""
    fmt = {4: "<f", 2: "<h"}[dtype]
    with open(name + ".raw", "wb") as f:
        if data_bytes is not None:
            f.write(data_bytes)
        else:
            for v in values:
                f.write(struct.pack(fmt, v))
    x0, y0, dx, dy = geo
    with open(name + ".hdr", "w") as f:
        f.write("ENVI\nsamples = %d\nlines = %d\nbands = 1\nheader offset = 0\n"
                "file type = ENVI Standard\ndata type = %d\ninterleave = bsq\nbyte order = 0\n"
                "map info = {Geographic Lat/Lon, 1, 1, %.10g, %.10g, %.10g, %.10g, WGS-84}\n"
                % (w, h, dtype, x0, y0, dx, dy))

# Headers claiming absurd sizes over a few bytes of data.
envi("absurd_size", 2000000, 1000000, None, dtype=2, geo=(-10, 10, 0.00001, 0.00001),
     data_bytes=b"\x01\x00" * 64)
envi("absurd_pixel", 64, 64, [100.0] * 4096, geo=(-10, 10, 1e-12, 1e-12))
# NaN and infinite heights among valid ones.
vals = []
for y in range(64):
    for x in range(64):
        v = 100.0 + x + y
        if (x + y) % 7 == 0: v = float("nan")
        if (x * y) % 13 == 5: v = float("inf")
        if (x * y) % 17 == 3: v = float("-inf")
        vals.append(v)
envi("nan_inf", 64, 64, vals)
envi("all_nan", 16, 16, [float("nan")] * 256)
envi("one_pixel", 1, 1, [123.0])
# Crossing the antimeridian (170 E to 170 W) and covering both poles.
envi("antimeridian", 200, 100, [(x * 3 + y) % 500 for y in range(100) for x in range(200)],
     geo=(170.0, 10.0, 0.1, 0.1))
envi("poles", 360, 180, [1000 * math.cos(math.radians(y - 90)) for y in range(180) for x in range(360)],
     geo=(-180.0, 90.0, 1.0, 1.0))

# Lines: one with a million vertices; coordinates out of range.
random.seed(7)
x, y, coords = 0.0, 0.0, []
for i in range(1000000):
    x += random.uniform(-1e-4, 1e-4); y += random.uniform(-1e-4, 1e-4)
    coords.append([round(x, 7), round(y, 7)])
def collection(features):
    return {"type": "FeatureCollection", "features": [
        {"type": "Feature", "properties": {"id": i}, "geometry": g} for i, g in enumerate(features)]}
json.dump(collection([{"type": "LineString", "coordinates": coords}]), open("million_vertices.geojson", "w"))
json.dump(collection([
    {"type": "LineString", "coordinates": [[500, 10], [600, 20]]},
    {"type": "LineString", "coordinates": [[10, 95], [20, 120]]},
    {"type": "LineString", "coordinates": [[1e300, 1], [-1e300, 2]]},
    {"type": "LineString", "coordinates": [[5, 5], [6, 6]]},
]), open("out_of_range.geojson", "w"))
json.dump(collection([
    {"type": "LineString", "coordinates": [[500, 10], [600, 20]]},
    {"type": "LineString", "coordinates": [[10, 95], [20, 120]]},
]), open("only_out_of_range.geojson", "w"))
json.dump(collection([{"type": "LineString", "coordinates": [[i * 0.1, (i % 3) * 0.1] for i in range(20)]}
                      for _ in range(50)]), open("small_lines.geojson", "w"))
PY

# Shapefiles whose .shx index is broken: garbage, cut short, or missing.
for kind in garbage truncated missing; do
  ogr2ogr -q -f "ESRI Shapefile" "shx_$kind.shp" small_lines.geojson
done
python3 - <<'PY'
import os
with open("shx_garbage.shx", "r+b") as f:
    f.seek(100)
    f.write(bytes((i * 37 + 11) % 256 for i in range(400)))
size = os.path.getsize("shx_truncated.shx")
with open("shx_truncated.shx", "r+b") as f:
    f.truncate(size // 2 + 3)
os.remove("shx_missing.shx")
PY

# Packages whose tiles are random bytes (deterministic: a seeded generator).
for kind in terrain lines; do
  src=$terrain
  [ $kind = lines ] && src=$lines
  cp "$src" "random_${kind}.mbtiles"
  python3 - "random_${kind}.mbtiles" <<'PY'
import random, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
rng = random.Random(42)
ids = [r[0] for r in db.execute("SELECT blob_id FROM blobs ORDER BY blob_id")]
for i in ids:
    n = rng.randint(0, 3000)
    db.execute("UPDATE blobs SET tile_data = ? WHERE blob_id = ?", (bytes(rng.getrandbits(8) for _ in range(n)), i))
db.commit()
PY
done
# A file that is not a package at all, and one cut in half.
head -c 5000 /dev/zero | tr '\0' 'x' > not_a_package.mbtiles
head -c $(( $(stat -c %s "$terrain") / 2 )) "$terrain" > truncated.mbtiles
echo "make_hostile: corpus in $out" >&2
