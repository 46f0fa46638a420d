// Connections of a bundling (see flow_input.hpp).
#include "bundle/flow_input.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <unordered_map>

#include "geo/spatial_ref.hpp"
#include "io/vector_reader.hpp"
#include "runtime/errors.hpp"

namespace globe {

namespace {

constexpr size_t kExamples = 5;

bool is_csv(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".csv" || ext == ".tsv" || ext == ".txt";
}

bool on_the_globe(double lon, double lat) {
  return std::isfinite(lon) && std::isfinite(lat) && std::abs(lat) <= 90 && std::abs(lon) <= 540;
}

// The number a whole field holds (surrounding blanks allowed), else NaN.
double parse_number(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin) return std::nan("");
  while (*end == ' ' || *end == '\t' || *end == '\r')
    ++end;
  return *end == 0 ? v : std::nan("");
}

std::string lonlat_text(double lon, double lat) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f,%.6f", lon, lat);
  return buf;
}

// The locations file: id -> place in longitude/latitude.
std::unordered_map<std::string, LonLat> read_locations(const FlowOptions& o, FlowInput& in) {
  VectorReaderOptions ro;
  ro.properties = false;
  ro.text_fields = {o.id_field};
  ro.field_options[o.id_field] = "--id-field";
  if (!o.label_field.empty() && o.label_field != o.id_field) {
    ro.text_fields.push_back(o.label_field);
    ro.field_options[o.label_field] = "--label-field";
  }
  ro.s_srs = o.s_srs;
  if (is_csv(o.locations)) {
    // CSV: the coordinate columns given, or the usual names.
    ro.xy = o.locations_xy.value_or(ColumnPair{"longitude,lon,lng,long,x", "latitude,lat,y"});
    ro.xy_option = "--locations-xy";
  } else if (o.locations_xy) {
    throw UsageError("--locations-xy: " + o.locations +
                     " is not a CSV file; its point geometry places the ids");
  }
  VectorReader reader({o.locations}, ro);
  const SpatialRef lonlat = SpatialRef::from_user_input("EPSG:4326", "the locations");
  std::vector<std::unique_ptr<CoordTransform>> to_lonlat;
  for (const VectorLayerInfo& l : reader.layers()) {
    if (l.geometry != LayerGeometry::kPoints)
      throw InputError(l.source + " layer '" + l.name +
                       "' holds no points: --locations needs a place (a point, or "
                       "longitude/latitude columns, --locations-xy) for every id");
    to_lonlat.push_back(std::make_unique<CoordTransform>(*l.crs, lonlat));
  }
  std::unordered_map<std::string, LonLat> places;
  VectorFeature f;
  while (reader.next(f)) {
    if (f.points.empty() || f.texts[0].empty()) continue;
    std::vector<double> x{f.points[0].x}, y{f.points[0].y};
    std::vector<int> ok;
    to_lonlat[f.layer]->transform(x, y, ok);
    if (!ok[0] || !on_the_globe(x[0], y[0])) continue;
    if (!places.try_emplace(f.texts[0], LonLat{x[0], y[0]}).second) {
      ++in.duplicate_ids;
      continue;
    }
    if (!o.label_field.empty()) {
      const std::string& name = f.texts.back();
      if (!name.empty()) in.names.emplace(f.texts[0], name);
    }
  }
  if (places.empty())
    throw InputError(o.locations + ": no location with an id (--id-field '" + o.id_field +
                     "') and a place on the globe");
  in.locations = places.size();
  return places;
}

}  // namespace

namespace {

// Refuses inconsistent ways of naming the connections' ends (UsageError).
void check_flow_options(const FlowOptions& o) {
  const bool by_id = !o.from_id.empty() || !o.to_id.empty();
  const bool by_xy = o.from_xy || o.to_xy;
  if (by_id && by_xy)
    throw UsageError(
        "give the ends either as coordinates (--from, --to) or as ids (--from-id, "
        "--to-id), not both");
  if (by_id && (o.from_id.empty() || o.to_id.empty()))
    throw UsageError("--from-id and --to-id go together");
  if (by_xy && (!o.from_xy || !o.to_xy)) throw UsageError("--from and --to go together");
  if (by_id && (o.locations.empty() || o.id_field.empty()))
    throw UsageError(
        "--from-id/--to-id name locations: add --locations FILE --id-field COL (e.g. "
        "--locations airports.csv --id-field iata)");
  if (!by_id && !o.locations.empty())
    throw UsageError("--locations is for ids: add --from-id COL --to-id COL");
  if (!o.label_field.empty() && o.locations.empty())
    throw UsageError(
        "--label-field names the connections' ends from --locations: add --from-id COL "
        "--to-id COL --locations FILE --id-field COL");
}

}  // namespace

FlowInput read_flows(const std::string& path, const FlowOptions& o) {
  check_flow_options(o);
  const bool by_id = !o.from_id.empty() || !o.to_id.empty();
  const bool by_xy = o.from_xy || o.to_xy;

  FlowInput in;
  std::unordered_map<std::string, LonLat> places;
  if (by_id) places = read_locations(o, in);

  VectorReaderOptions ro;
  ro.properties = false;
  ro.crs = VectorReaderOptions::Crs::kNotNeeded;
  ro.s_srs = o.s_srs;
  // Every column is read as text and parsed here, row by row: a column
  // with one "NA" is text to OGR's CSV reader, and a bad value is a bad
  // row, not a bad file.
  auto column = [&](const std::string& name, const char* option) {
    ro.text_fields.push_back(name);
    ro.field_options[name] = option;
  };
  if (by_xy) {
    column(o.from_xy->first, "--from");
    column(o.from_xy->second, "--from");
    column(o.to_xy->first, "--to");
    column(o.to_xy->second, "--to");
  }
  if (by_id) {
    column(o.from_id, "--from-id");
    column(o.to_id, "--to-id");
  }
  if (!o.weight.empty()) column(o.weight, "--weight");
  VectorReader reader({path}, ro);
  // Lines: their ends, in longitude/latitude.
  std::vector<std::unique_ptr<CoordTransform>> to_lonlat;
  if (!by_id && !by_xy) {
    const SpatialRef lonlat = SpatialRef::from_user_input("EPSG:4326", "the flows");
    for (const VectorLayerInfo& l : reader.layers()) {
      if (l.geometry != LayerGeometry::kLines || !l.crs)
        throw UsageError(l.source + " layer '" + l.name +
                         "': say where connections start and end: --from LONCOL,LATCOL --to "
                         "LONCOL,LATCOL, or --from-id COL --to-id COL with --locations (or give "
                         "lines, from origin to destination); its columns are: " +
                         [&] {
                           std::string s;
                           for (const auto& f : l.fields)
                             s += (s.empty() ? "" : ", ") + f;
                           return s.empty() ? std::string("(none)") : s;
                         }());
      to_lonlat.push_back(std::make_unique<CoordTransform>(*l.crs, lonlat));
    }
  }
  auto bad = [&](uint64_t& counter, const std::string& why) {
    ++counter;
    if (in.examples.size() < kExamples)
      in.examples.push_back(path + " row " + std::to_string(in.rows) + ": " + why);
  };
  VectorFeature f;
  while (reader.next(f)) {
    ++in.rows;
    Connection c;
    c.row = in.rows;
    if (by_xy) {
      c.from = {parse_number(f.texts[0]), parse_number(f.texts[1])};
      c.to = {parse_number(f.texts[2]), parse_number(f.texts[3])};
      if (!on_the_globe(c.from.lon, c.from.lat) || !on_the_globe(c.to.lon, c.to.lat)) {
        bad(in.bad_coordinates, "no longitude/latitude in the --from or --to columns");
        continue;
      }
      c.origin = lonlat_text(c.from.lon, c.from.lat);
      c.destination = lonlat_text(c.to.lon, c.to.lat);
    } else if (by_id) {
      c.origin = f.texts[0];
      c.destination = f.texts[1];
      auto a = places.find(c.origin), b = places.find(c.destination);
      if (a == places.end() || b == places.end()) {
        bad(in.unknown_ids,
            "id '" + (a == places.end() ? c.origin : c.destination) + "' is not in " + o.locations);
        continue;
      }
      c.from = a->second;
      c.to = b->second;
    } else {
      std::vector<double> x, y;
      for (const auto& part : f.lines)
        if (!part.empty()) {
          if (x.empty()) x.push_back(part.front().x), y.push_back(part.front().y);
          x.resize(1), y.resize(1);
          x.push_back(part.back().x), y.push_back(part.back().y);
        }
      std::vector<int> ok;
      if (x.size() == 2) to_lonlat[f.layer]->transform(x, y, ok);
      if (x.size() != 2 || !ok[0] || !ok[1] || !on_the_globe(x[0], y[0]) ||
          !on_the_globe(x[1], y[1])) {
        bad(in.bad_coordinates, "no line with two ends on the globe");
        continue;
      }
      c.from = {x[0], y[0]};
      c.to = {x[1], y[1]};
      c.origin = lonlat_text(c.from.lon, c.from.lat);
      c.destination = lonlat_text(c.to.lon, c.to.lat);
    }
    if (!o.weight.empty()) {
      c.weight = parse_number(f.texts.back());
      if (!std::isfinite(c.weight) || c.weight < 0) {
        bad(in.bad_weights, "weight (--weight '" + o.weight + "') missing or negative");
        continue;
      }
      if (c.weight == 0) {
        ++in.zero_weights;
        continue;
      }
    }
    in.connections.push_back(std::move(c));
  }
  return in;
}

}  // namespace globe
