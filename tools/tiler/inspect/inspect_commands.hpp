// What the raster kinds' `globe-tiler extract` share (extract_tiff.cpp):
// the tiles to extract, block samples as a GeoTIFF band, the GeoTIFF written
// under a temporary name. Each kind's info, validate and extract are in its
// own file (terrain_inspect.cpp …), one row of inspect_commands.cpp's table.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "geo/gdal_dataset.hpp"
#include "kit/kind_inspection.hpp"
#include "tileformat/package.hpp"
#include "tileformat/tiling.hpp"

namespace globe {

// Shared by both extracts: the tiles of the zoom (inside --bbox) and the
// range they span; throws InputError if there are none, UsageError if the
// zoom is outside min_zoom..max_zoom.
struct ExtractTiles {
  std::vector<tileformat::TileId> ids;
  uint32_t x0 = 0, y0 = 0, cols = 0, rows = 0;  // north-west tile, tiles across and down
};
ExtractTiles tiles_to_extract(tileformat::PackageReader& reader, const tileformat::Tiling& tiling,
                              const ExtractRequest& request, int min_zoom, int max_zoom);
// One band of block samples (terrain and analysis extracts) written to the
// request's GeoTIFF as `type`: pixel centres on the samples, neighbouring
// blocks sharing their edge samples, NaN where there is no value.
// `fill(id, samples)` sets a tile's block_size² values (row-major from the
// north). Throws UsageError for an extract over 10^6 samples a side.
struct SampleGrid {
  int width = 0, height = 0;
};
SampleGrid write_block_samples(
    const ExtractRequest& request, const tileformat::Tiling& tiling, const ExtractTiles& tiles,
    int block_size, GDALDataType type,
    const std::function<void(tileformat::TileId, std::vector<double>& samples)>& fill);
// The GeoTIFF an extract writes under a temporary name, renamed by commit().
class ExtractTiff {
 public:
  ExtractTiff(const ExtractRequest& request, int width, int height, int bands, GDALDataType type,
              const std::array<double, 6>& gt, const std::string& crs);
  ~ExtractTiff();  // removes the temporary file unless committed
  GdalDataset& dataset() { return ds_; }
  void commit();

 private:
  std::string output_, temp_;
  GdalDataset ds_;
  bool committed_ = false;
};

}  // namespace globe
