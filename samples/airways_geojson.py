#!/usr/bin/env python3
"""FlightGear's airway segments (Navaids/awy.dat.gz, X-Plane 640 format) as GeoJSON lines.

Usage: samples/airways_geojson.py awy.dat.gz > airways.geojson

Each data line is one segment: FIX LAT LON FIX LAT LON TYPE BASE TOP NAMES
(TYPE 1 low, 2 high airway; BASE and TOP in hundreds of feet; NAMES joined by
'-'). Every segment becomes one LineString from its first fix to its second,
with its names, fixes, level, base and top; coordinates are kept as they are
(a segment across the antimeridian spans it; the tools take the short way).
"""
import gzip
import json
import sys


def kind_of(field):
    return {"1": "low", "2": "high"}.get(field)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: airways_geojson.py awy.dat.gz > airways.geojson")
    out = sys.stdout
    out.write('{"type":"FeatureCollection","name":"airways",'
              '"crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:OGC:1.3:CRS84"}},'
              '"features":[\n')
    first = True
    count = 0
    with gzip.open(sys.argv[1], "rt", encoding="latin-1") as f:
        for line in f:
            parts = line.split()
            if len(parts) < 10 or kind_of(parts[6]) is None:
                continue  # header, blank lines, the closing 99
            a, lat1, lon1, b, lat2, lon2, kind, base, top, names = parts[:10]
            feature = {
                "type": "Feature",
                "properties": {"name": names, "from": a, "to": b,
                               "level": kind_of(kind),
                               "base": int(base), "top": int(top)},
                "geometry": {"type": "LineString",
                             "coordinates": [[float(lon1), float(lat1)],
                                             [float(lon2), float(lat2)]]},
            }
            out.write(("" if first else ",\n") + json.dumps(feature, separators=(",", ":")))
            first = False
            count += 1
    out.write("\n]}\n")
    if count == 0:
        sys.exit("airways_geojson.py: no airway segment in " + sys.argv[1])


if __name__ == "__main__":
    main()
