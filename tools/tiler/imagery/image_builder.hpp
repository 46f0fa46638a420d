// Builds an image package from a plan (docs/imagery.md "Pipeline"). The
// finest zoom is warped from the sources in blocks of up to 4 x 4 tiles;
// every coarser zoom is built from its children's pixels (image_pyramid),
// never from the sources again. Pixels of the level below live in a scratch
// SQLite file (zstd), so memory does not grow with the input. Empty tiles
// are not written, identical tiles are stored once; parallel work is done in
// batches consumed in tile order, so output is identical for any -j.
#pragma once

#include <cstdint>

#include "image_plan.hpp"
#include "progress.hpp"

namespace globe {

struct ImageSummary {
  uint64_t tiles = 0, unique_blobs = 0, blob_bytes = 0, file_bytes = 0;
  uint64_t png = 0, jpeg = 0, webp = 0;  // tiles per encoding
  double seconds = 0;
};

ImageSummary build_imagery(const ImagePlan& plan, const ImageSettings& settings,
                           Progress& progress);

}  // namespace globe
