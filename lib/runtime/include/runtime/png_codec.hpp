// The one wrapper around libpng: encodes 8-bit gray, gray + alpha, RGB or
// RGBA pixels as a PNG file in memory, and decodes any PNG to RGBA. Used for image tiles (GDAL's
// PNG driver offers neither the filter nor the deflate strategy, and spent 2.4x the time for 5-17 %
// more bytes on the sample images; docs/imagery.md "Encoding").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace globe {

// Which prediction each row gets. kAdaptive: with effort 1, Paeth and
// run-length deflate (fastest; on photographs also the smallest); with 2..9,
// libpng's per-row choice among all five filters and deflate at that level
// (smaller for graphics with repeated patterns). kUp: every row predicted
// from the row above, deflate at level `effort` (1..9): encoded heights
// (Terrarium, Terrain-RGB), whose rows are smooth but whose low bytes are
// noise that the adaptive choice's sum-of-differences heuristic misjudges
// (bench/README.md "Raster-DEM PNG").
enum class PngFilter { kAdaptive, kUp };

// `pixels`: rows from the top, `channels` (1..4) interleaved bytes per pixel.
// Throws std::runtime_error if libpng fails.
std::vector<uint8_t> encode_png(const uint8_t* pixels, int width, int height, int channels,
                                int effort, PngFilter filter = PngFilter::kAdaptive);

// Decodes a PNG in memory to 8-bit RGBA rows from the top (any bit depth,
// palette, gray or transparency key). Throws std::runtime_error with libpng's
// message.
std::vector<uint8_t> decode_png_rgba(const uint8_t* data, size_t size, int& width, int& height);

}  // namespace globe
