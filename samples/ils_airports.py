#!/usr/bin/env python3
"""The airports of FlightGear's navaids (Navaids/nav.dat.gz, X-Plane 810 format) that have an
instrument landing system, as CSV: icao,lon,lat,ils_runway_ends.

Usage: samples/ils_airports.py nav.dat.gz > world_airports.csv

Rows of type 4 (ILS localizer) and 5 (localizer only) name their airport (ICAO code) and
runway: TYPE LAT LON ELEV FREQ RANGE BEARING IDENT AIRPORT RUNWAY NAME. An airport is placed at
the mean position of its localizers (within a few km of its runways) and counted by its
runway ends with one (09L and 27R are two): a world-wide set of larger airports, weighted by their size, for
origin-destination tests and benchmarks (tests/bundle_global_test.cpp, bench/bundle.sh).
Rows come sorted by ICAO code.
"""
import gzip
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: ils_airports.py nav.dat.gz > world_airports.csv")
    airports = {}  # icao -> [sum lon, sum lat, count, runways]
    with gzip.open(sys.argv[1], "rt", encoding="latin-1") as f:
        for line in f:
            parts = line.split()
            if len(parts) < 10 or parts[0] not in ("4", "5"):
                continue
            lat, lon, icao, runway = float(parts[1]), float(parts[2]), parts[8], parts[9]
            a = airports.setdefault(icao, [0.0, 0.0, 0, set()])
            a[0] += lon
            a[1] += lat
            a[2] += 1
            a[3].add(runway)
    out = sys.stdout
    out.write("icao,lon,lat,ils_runway_ends\n")
    for icao in sorted(airports):
        lon, lat, n, runways = airports[icao]
        out.write("%s,%.6f,%.6f,%d\n" % (icao, lon / n, lat / n, len(runways)))


if __name__ == "__main__":
    main()
