// Where an export's tiles go (docs/web.md "Outputs"), chosen by the output's
// name: OUT.pmtiles (PMTiles v3, one file for static hosting), OUT.mbtiles
// (MBTiles 1.3, TMS rows, for servers) or a folder DIR/{z}/{x}/{y}.EXT (XYZ
// rows, or TMS rows for quantized-mesh). Every kind is written under a
// temporary name and appears under its final name only when finish()
// succeeds; an output abandoned before (an error, a kill) leaves nothing
// there. Tiles come in PMTiles tile id order (tileformat/pmtiles.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "tileformat/package.hpp"
#include "tileformat/pmtiles.hpp"

namespace globe {

enum class OutputKind { kPmtiles, kMbtiles, kDirectory };
OutputKind output_kind(const std::string& path);

// Every tile of a web mercator package's zooms min..max, in the order the
// outputs take them (PMTiles tile ids).
std::vector<tileformat::TileId> tiles_in_output_order(tileformat::PackageReader& reader,
                                                      int min_zoom, int max_zoom);

// What the outputs record about the tiles (PMTiles header and metadata,
// MBTiles metadata, the folder's metadata.json: TileJSON 3.0.0).
struct ExportInfo {
  std::string name, description;
  std::string format;     // "png", "jpg", "webp", "pbf", "quantized-mesh-1.0"
  std::string extension;  // of the folder's tile files: "png", "terrain", ...
  std::string type = "baselayer";
  tileformat::pmtiles::TileType tile_type = tileformat::pmtiles::TileType::kUnknown;
  tileformat::pmtiles::Compression tile_compression = tileformat::pmtiles::Compression::kNone;
  int min_zoom = 0, max_zoom = 0;
  double west = -180, south = -85.0511287798, east = 180, north = 85.0511287798;
  bool tms_rows = false;   // rows count from the south (quantized-mesh): metadata "scheme"
  std::string extra_json;  // more members of the metadata object ("\"encoding\":...")
  // Files beside the tiles (quantized-mesh's layer.json): written into a
  // folder, kept as metadata rows of that name in MBTiles.
  std::vector<std::pair<std::string, std::string>> side_files;
};

class TileOutput {
 public:
  // Throws OutputError if `path` exists and !force, or cannot be created.
  // A folder's files get `extension`, rows from the south if `tms_rows`.
  static std::unique_ptr<TileOutput> open(const std::string& path, bool force,
                                          const std::string& extension, bool tms_rows);
  virtual ~TileOutput() = default;
  // (z, x, y) with y counted from the top (XYZ); empty bytes: no tile.
  virtual void put(int z, uint32_t x, uint32_t y, std::span<const uint8_t> bytes) = 0;
  // Writes the metadata and moves the output to its final name; returns its
  // size in bytes. Throws OutputError.
  virtual uint64_t finish(const ExportInfo& info) = 0;
  virtual uint64_t tiles() const = 0;
};

}  // namespace globe
