// The connections of a bundling (docs/bundles.md "Flows"): one per row of a
// CSV file or feature of any OGR source, its origin and destination given as
// longitude/latitude columns (--from, --to), as ids joined to a locations
// file (--from-id, --to-id, --locations, --id-field), or by a line's first
// and last vertex; its weight from a numeric column (--weight, default 1).
// Rows that cannot be used are counted by reason, never fatal.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "bundle/network_graph.hpp"

namespace globe {

using ColumnPair = std::pair<std::string, std::string>;

struct FlowOptions {
  std::optional<ColumnPair> from_xy, to_xy;  // --from LONCOL,LATCOL, --to LONCOL,LATCOL
  std::string from_id, to_id;                // --from-id COL, --to-id COL
  std::string locations;                     // --locations FILE
  std::string id_field;                      // --id-field COL (of the locations)
  std::optional<ColumnPair> locations_xy;    // --locations-xy LONCOL,LATCOL (CSV)
  std::string weight;                        // --weight COL ("" = 1 per row)
  std::string label_field;                   // --label-field COL of the locations ("" none)
  std::string s_srs;                         // CRS of coordinates without one (lon/lat)
};

struct Connection {
  LonLat from, to;
  double weight = 1;
  std::string origin, destination;  // ids, or the coordinates as text
  uint64_t row = 0;                 // 1-based, in the flows
};

struct FlowInput {
  std::vector<Connection> connections;
  uint64_t rows = 0;
  uint64_t bad_coordinates = 0;  // missing, not numbers, or off the globe
  uint64_t unknown_ids = 0;      // an id the locations do not have
  uint64_t bad_weights = 0;      // missing, not a number, negative
  uint64_t zero_weights = 0;     // weight 0: nothing to draw
  uint64_t locations = 0, duplicate_ids = 0;
  // --label-field: each location id's name (ids without one are absent).
  std::unordered_map<std::string, std::string> names;
  std::vector<std::string> examples;  // the first few bad rows, described
  uint64_t bad_rows() const { return bad_coordinates + unknown_ids + bad_weights; }
};

// Throws UsageError for unknown columns or a missing way to place the ends,
// InputError for unreadable files.
FlowInput read_flows(const std::string& path, const FlowOptions& options);

}  // namespace globe
