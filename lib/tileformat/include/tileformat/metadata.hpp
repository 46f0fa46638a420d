// Package metadata, typed (docs/tileformat.md §3.2, §7.4, §8): what every
// package says about itself, and what each kind adds. The one writer
// (to_metadata) and the one reader (read_*_metadata) of the keys: builders
// fill these structs, inspection tools and the viewer read them back.
//
// Numbers are written as before this module existed, so packages stay byte
// for byte the same: 10 significant digits, bounds clamped to the tiling's
// lon/lat limits after rounding (readers such as GDAL reject
// -180.00000000000003), exact shortest text where a value must round-trip.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tileformat/analysis_block.hpp"
#include "tileformat/image_tile.hpp"
#include "tileformat/package_kinds.hpp"
#include "tileformat/tiling.hpp"

namespace tileformat {

using MetadataMap = std::map<std::string, std::string>;

struct InputFile {
  std::string name;  // as given on the command line
  uint64_t bytes = 0;
};

// The keys every package carries (§3.2).
struct CommonMetadata {
  std::string name;         // MBTiles `name` (the output's file stem)
  std::string format;       // MBTiles `format`
  std::string type;         // `baselayer` or `overlay`
  std::string description;  // free text
  Bounds lonlat;            // `bounds`, degrees
  bool has_bounds = true;   // false when read from a package without valid `bounds`
  int bounds_digits = 10;   // significant digits of `bounds` when written (0: exact)
  int center_zoom = 0;      // the zoom of `center` (its lon/lat is the middle of `bounds`)
  int min_zoom = 0, max_zoom = 0;
  Tiling tiling;                  // globe:scheme … globe:roots (absent from other tools' MBTiles)
  bool has_tiling = true;         // false for MBTiles made by other tools
  std::string generator;          // globe:generator
  std::string command_line;       // globe:command_line
  std::vector<InputFile> inputs;  // globe:inputs
  std::string left_out;           // globe:left_out: what the tiling could not hold ("" if none)
};

// Terrain (§5): the common keys, and
struct TerrainMetadata {
  CommonMetadata common;
  std::string resampling;  // globe:resampling
  int block_size = 0;      // globe:block_size (2^k + 1)
  int lattice = 0;         // globe:kpatch_lattice
  double height_step = 0;  // globe:height_step, metres
  double fill_height = 0;  // globe:fill_height, metres
};

// Imagery (§8).
struct ImageMetadata {
  CommonMetadata common;
  ImageFormat format = ImageFormat::kPng;
  std::string resampling;        // globe:resampling
  int tile_size = 256;           // globe:tile_size (0 when read from another tool's MBTiles)
  int colour_bands = 3;          // globe:colour_bands, 1 or 3 (0 when unknown, as tile_size)
  std::optional<int> quality;    // globe:quality (JPEG/WebP)
  std::optional<int> png_level;  // globe:png_level (when PNG tiles were written)
  std::optional<std::pair<double, double>> scale;  // globe:scale: source values -> 0..255
};

// Line clusters (§7.4).
struct LineLayerInfo {
  std::string name, source;
  uint64_t features = 0;
};
struct LineMetadata {
  CommonMetadata common;
  int extent = 0;                     // globe:extent
  int cluster_grid = 0;               // globe:cluster_grid
  double simplify_px = 0;             // globe:simplify_px
  double tile_px = 0;                 // globe:tile_px
  uint64_t features = 0;              // globe:features
  std::string classes_json;           // globe:classes: the classes and their styles, JSON (§7.4)
  std::vector<LineLayerInfo> layers;  // globe:layers
  std::string bundle_json;            // globe:bundle (bundled flows, §7.5): "" for none
};

// Terrain analytics (§9): the terrain's tiling, zooms and block size.
struct AnalysisMetadata {
  CommonMetadata common;
  int block_size = 0;                 // globe:block_size, as the terrain's
  std::vector<AnalysisLayer> layers;  // globe:analysis_layers, names comma-separated, id order
  std::string terrain;                // globe:terrain: the terrain package's file name
  double height_step = 0;             // globe:height_step of that terrain
  int skyview_directions = 0;         // globe:skyview_directions (with the skyview layer)
  double skyview_radius_m = 0;        // globe:skyview_radius_m
  // globe:skyview_radius_by_zoom, "Z:METRES,...": per zoom, the radius every
  // sample's rays reach (skyview_radius_m, or less where the zooms above run
  // out); geodetic tilings: rows within 80 degrees of the equator. Empty in
  // packages made before 2026-11-28.
  std::vector<std::pair<int, double>> skyview_radius_by_zoom;
  std::string flow_method;  // globe:flow_method (with the flow layers): "fill", "carve"
};

// Points for charts (§11.4).
enum class PointAggregate { kSum, kMean };
struct PointZoomStats {
  int zoom = 0;
  uint64_t places = 0;   // places of the zoom (aggregates count once)
  double max_total = 0;  // largest sum of a place's values (signed: of their magnitudes)
  double max_value = 0;  // largest magnitude of one value
};
struct PointMetadata {
  CommonMetadata common;
  int extent = 0;                   // globe:extent
  int cluster_grid = 0;             // globe:cluster_grid
  double tile_px = 0;               // globe:tile_px
  double chart_max_px = 0;          // globe:chart_max_px: chart size the grids were built for
  std::vector<std::string> fields;  // globe:fields (JSON array), by value index
  PointAggregate aggregate = PointAggregate::kSum;  // globe:aggregate: "sum" or "mean"
  double merge_px = 0;                              // globe:merge_px
  bool signed_values = false;         // globe:signed: negative values occur ("1") or not ("0")
  std::string label_field;            // globe:label_field ("" for none)
  uint64_t features = 0;              // globe:features: source places (features table rows)
  std::vector<PointZoomStats> zooms;  // globe:zoom_stats (JSON array), min..max zoom
};

// Areas (§12.3).
struct ChoroplethClass {
  double min = 0, max = 0;  // class i holds [min, max), the last one [min, max]
  std::string color;        // "#rrggbb"
};
struct Choropleth {
  std::string field, denominator;  // the value is field, or field / denominator
  std::string method;              // quantile, equal, jenks, pretty
  std::string ramp;                // the ColorBrewer ramp's name
  std::vector<ChoroplethClass> classes;
  std::string no_data_color;  // features without a value (class id 0)
  uint64_t no_data = 0;       // how many
};
struct AreaMetadata {
  CommonMetadata common;
  int extent = 0;                        // globe:extent
  int buffer = 0;                        // globe:buffer: units the polygons reach past a tile
  double simplify_px = 0;                // globe:simplify_px: the snapping grid of a zoom, in px
  double tile_px = 0;                    // globe:tile_px
  uint64_t features = 0;                 // globe:features
  std::string classes_json;              // globe:classes: style classes, JSON (as §7.4)
  std::vector<LineLayerInfo> layers;     // globe:layers
  std::optional<Choropleth> choropleth;  // globe:choropleth (JSON)
  uint64_t repaired = 0;  // globe:repaired: features whose geometry GEOS MakeValid repaired
};

// The package's keys; kind-specific keys absent from the struct (optionals)
// are not written.
MetadataMap to_metadata(const TerrainMetadata& m);
MetadataMap to_metadata(const ImageMetadata& m);
MetadataMap to_metadata(const LineMetadata& m);
MetadataMap to_metadata(const AnalysisMetadata& m);
MetadataMap to_metadata(const PointMetadata& m);
MetadataMap to_metadata(const AreaMetadata& m);

// Read back; throw FormatError (§3.2, §7.4, §8) naming the missing or bad
// key. read_common_metadata reads what any MBTiles has (other tools'
// packages have no tiling: has_tiling = false, webmercator assumed).
CommonMetadata read_common_metadata(const MetadataMap& meta);
TerrainMetadata read_terrain_metadata(const MetadataMap& meta);
ImageMetadata read_image_metadata(const MetadataMap& meta);
LineMetadata read_line_metadata(const MetadataMap& meta);
AnalysisMetadata read_analysis_metadata(const MetadataMap& meta);
PointMetadata read_point_metadata(const MetadataMap& meta);
AreaMetadata read_area_metadata(const MetadataMap& meta);

// The `description` our tools write: "WHAT built by PROGRAM from FIRST
// (and N more)", FIRST being the first input's file name.
std::string build_description(const std::string& what, const std::string& program,
                              const std::vector<InputFile>& inputs);

// `v` with `digits` significant digits; digits = 0: the shortest text that
// reads back as exactly `v`.
std::string metadata_number(double v, int digits = 10);

}  // namespace tileformat
