#!/usr/bin/env python3
"""Flights per US airport by the census region they fly to (a multi-valued
point set for `globe-vectorize points`), from vega-datasets' airports.csv and
flights-airport.csv (origin, destination, count).

Usage: us_flights_by_region.py AIRPORTS.csv FLIGHTS.csv > OUT.csv
Writes iata,name,city,state,longitude,latitude,west,midwest,south,northeast,other
for every airport with departures; `other` is territories (PR, VI) and codes
without a state."""
import csv
import sys

REGIONS = {
    "west": "AK AZ CA CO HI ID MT NM NV OR UT WA WY",
    "midwest": "IA IL IN KS MI MN MO ND NE OH SD WI",
    "south": "AL AR DC DE FL GA KY LA MD MS NC OK SC TN TX VA WV",
    "northeast": "CT MA ME NH NJ NY PA RI VT",
}
REGION_OF = {state: region for region, states in REGIONS.items() for state in states.split()}
COLUMNS = ["west", "midwest", "south", "northeast", "other"]


def main(airports_path, flights_path):
    with open(airports_path, newline="") as f:
        airports = {row["iata"]: row for row in csv.DictReader(f)}
    counts = {}
    with open(flights_path, newline="") as f:
        for row in csv.DictReader(f):
            origin, dest = row["origin"], row["destination"]
            if origin not in airports or dest not in airports:
                sys.exit(f"{flights_path}: airport {origin if origin not in airports else dest} "
                         f"is not in {airports_path}")
            region = REGION_OF.get(airports[dest]["state"], "other")
            per = counts.setdefault(origin, dict.fromkeys(COLUMNS, 0))
            per[region] += int(row["count"])
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["iata", "name", "city", "state", "longitude", "latitude"] + COLUMNS)
    for iata in sorted(counts):
        a = airports[iata]
        out.writerow([iata, a["name"], a["city"], a["state"], a["longitude"], a["latitude"]] +
                     [counts[iata][c] for c in COLUMNS])


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
